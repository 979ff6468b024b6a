//! Tables at their ends through the interpreter (docs/tables.md#outside-the-data): the runs
//! of `tests/table_ends.rs` and `tests/table_state_ends.rs` (generated code) by
//! `varmass run`, which shares their stop times and switches (`varmass_core::table`) but
//! computes the Taylor series on its own tapes.

use assert_cmd::Command;

/// Runs `model` (in `tests/data/tables/`) with `args`, asserting the exit code; returns
/// stdout and stderr.
fn run(model: &str, args: &[&str], code: i32) -> (String, String) {
    let model = format!("{}/tests/data/tables/{model}", env!("CARGO_MANIFEST_DIR"));
    let output = Command::cargo_bin("varmass")
        .expect("the binary is built")
        .arg("run")
        .arg(model)
        .args(args)
        .output()
        .expect("runs");
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(code), "{stdout}\n{stderr}");
    (stdout, stderr)
}

/// The value printed for `name` (`  name = value`) in a run's summary.
fn printed(output: &str, name: &str) -> f64 {
    let prefix = format!("  {name} = ");
    let line = output
        .lines()
        .find_map(|line| line.strip_prefix(&prefix))
        .unwrap_or_else(|| panic!("no `{name}` in {output}"));
    line.trim().parse().unwrap()
}

#[test]
fn taylor_falls_from_the_last_knot_of_an_outside_error_table() {
    // F(1 − t) = 0.7 − t for t ≤ 0.7: v(0.5) = 0.7·0.5 − 0.5²/2 = 0.225. Measured: Taylor
    // 2.5e-16 relative, Dormand–Prince 1.2e-16; bound 1e-14 (before: Taylor exit 1 at t = 0).
    for method in ["taylor", "dormand-prince"] {
        let args = [
            "--set", "m0=1", "--set", "c=1", "--init", "x=0", "--until", "0.5",
        ];
        let (stdout, stderr) = run(
            "falling_from_the_end.vms",
            &[&args[..], &["--method", method, "--tol", "1e-12"]].concat(),
            0,
        );
        let v = printed(&format!("{stdout}{stderr}"), "x'");
        assert!((v - 0.225).abs() <= 1e-14 * 0.225, "{method}: {v}");
    }
}

#[test]
fn an_adaptive_taylor_run_leaving_the_data_fails_there_without_the_fixed_step_help() {
    // The argument leaves the data at t = 1: Taylor's series is NaN past the last knot
    // and the run fails within rounding of t = 1 (measured 1.0000000000000002), with help
    // that names the equations, not a fixed step (there is none).
    let args = [
        "--set", "m0=1", "--set", "c=1", "--init", "x=0", "--until", "2",
    ];
    let (_, stderr) = run(
        "falling_from_the_end.vms",
        &[&args[..], &["--method", "taylor", "--tol", "1e-12"]].concat(),
        1,
    );
    let time: f64 = stderr
        .split("the run failed at t = ")
        .nth(1)
        .and_then(|rest| rest.split(':').next())
        .and_then(|time| time.parse().ok())
        .unwrap_or_else(|| panic!("{stderr}"));
    assert!((1.0..=1.0 + 1e-12).contains(&time), "{stderr}");
    assert!(stderr.contains("a table read outside its data"), "{stderr}");
    assert!(!stderr.contains("stability limit"), "{stderr}");
}

#[test]
fn a_box_of_the_state_jumping_at_both_ends_meets_its_closed_form() {
    // v = √3 past x = 2 (tests/table_state_ends.rs). Measured: ≤ 2.3e-15 relative by RK4
    // and Dormand–Prince at step 0.01, Taylor and Dormand–Prince at 1e-12; bound 2e-14
    // (before: RK4 9.6e-4, Dormand–Prince fixed 7.6e-4).
    let runs: [&[&str]; 4] = [
        &["--method", "rk4", "--step", "0.01"],
        &["--method", "dormand-prince", "--step", "0.01"],
        &["--method", "dormand-prince", "--tol", "1e-12"],
        &["--method", "taylor", "--tol", "1e-12"],
    ];
    for method in runs {
        let args = [
            "--set", "m0=1", "--init", "x=0", "--init", "x'=1", "--until", "3",
        ];
        let (stdout, stderr) = run("box_of_the_state.vms", &[&args[..], method].concat(), 0);
        let v = printed(&format!("{stdout}{stderr}"), "x'");
        let exact = 3f64.sqrt();
        let error = (v - exact).abs() / exact;
        assert!(error <= 2e-14, "{method:?}: {v} ({error:e})");
    }
}

#[test]
fn a_box_of_a_slowly_varying_argument_of_the_state_is_switched_where_the_lookup_jumps() {
    // G(a·x + c) = 1 for x between (1 − c)/a and (2 − c)/a, a length 1/|a|, entered at
    // x = 0.5 from x(0) = 0, x'(0) = 1: after it v = √(1 + 2/|a|) (energy; the derivation in
    // tests/table_state_ends.rs). Measured (v, rk4 and dormand-prince at step 0.01, taylor
    // at 1e-12): a = ±0.01 ≤ 7.8e-15, a = 100 ≤ 8.8e-16; bound 5e-14 (before the fix, by
    // RK4 5.5e-5 and Dormand–Prince 2.5e-4 at a = ±0.01: the crossing, located to a rounding
    // of t, had not moved s by an ulp, and the step crossed the box blindly).
    let cases = [
        ("0.01", "0.995", "16"),
        ("-0.01", "2.005", "16"),
        ("100", "0.5", "2"),
    ];
    for (a, c, until) in cases {
        let leaving = (1.0 + 2.0 / a.parse::<f64>().unwrap().abs()).sqrt();
        for method in [
            ["rk4", "--step", "0.01"],
            ["dormand-prince", "--step", "0.01"],
            ["taylor", "--tol", "1e-12"],
        ] {
            let set = [format!("a={a}"), format!("c={c}")];
            let args = [
                "--set", &set[0], "--set", &set[1], "--init", "x=0", "--init", "x'=1", "--until",
                until, "--method",
            ];
            let (stdout, _) = run("affine_box.vms", &[&args[..], &method[..]].concat(), 0);
            let v = printed(&stdout, "x'");
            let error = (v - leaving).abs() / leaving;
            assert!(error <= 5e-14, "a = {a}, {method:?}: v = {v} ({error:e})");
        }
    }
}
