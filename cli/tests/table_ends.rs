//! Tables at their ends through the interpreter (docs/tables.md#outside-the-data), and
//! tables of t whose derivative enters the equations (below): the runs of
//! `tests/table_ends.rs`, `tests/table_state_ends.rs` and `tests/table_derivative_knots.rs`
//! (generated code) by `varmass run`, which shares their stop times and switches
//! (`varmass_core::table`) but computes the Taylor series on its own tapes.

mod common;

use common::{data, varmass};

/// Runs `model` (in `tests/data/tables/`) with `args`, asserting the exit code; returns
/// stdout and stderr.
fn run(model: &str, args: &[&str], code: i32) -> (String, String) {
    let model = data(&format!("tables/{model}"));
    varmass(&[&["run", model.as_str()][..], args].concat(), code)
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

// Tables of t whose derivative enters the equations, through the interpreter
// (docs/tables.md#knots-are-switches): the models of `tests/table_derivative_knots.rs`
// (generated code, where the closed forms are derived) by `varmass run`, which shares
// their stop times (`varmass_core::table::next_knot_time_read`) and computes the Taylor
// series on its own tapes. The table: (0, 5) (1, 4.2) (2, 3.9) (3, 3.0), held outside.
//
// - mass law `mass m = M(t)`, outflow at −u_e = −1000, g = 9.81: frozen-mass rule,
//   m v̇ = u_e (−ṁ) − m g, so v(5) = u_e ln(M(0)/M(5)) − 5 g = 1000 ln(5/3) − 49.05;
// - inertia law `inertia I = J(t)`, torque τ = 1: I ω̇ = τ, ω(5) = Σ ln(Jᵢ/Jᵢ₊₁)/|bᵢ| + 2/3
//   over the three pieces of slopes bᵢ, then 2 s at I = 3;
// - position `[x + P(t)]`, P by pchip, spring ½ k (x + P)², k = 1, m₀ = 2: u = x + P obeys
//   ü = −ω² u, ω² = 1/2, whatever P. The tool starts from ẋ = 0 (not p = 0 as the macro's
//   test), so u(0) = P(0) = 5 and u̇(0) = P′(0) = −1.05, pchip's three-point end slope
//   ((2h₀ + h₁)δ₀ − h₀δ₁)/(h₀ + h₁) = (3·(−0.8) + 0.3)/2 (SciPy's; its sign is δ₀'s and
//   |−1.05| < 3|δ₀|, so it stands): x(5) = 5 cos 5ω + (P′(0)/ω) sin 5ω − P(5), P(5) = 3.
//
// Measured before (every knot a stop time, but the step arriving at one reading the next
// slope, and the run leaving the last knot the last slope): the mass law 700.63 by Taylor
// at 1e-12, RK4 of first order (464.69, 463.23, 462.50 at h = 0.1, 0.05, 0.025).

/// `name` printed by a run of `model` to t = 5 with `args` (exit 0).
fn at_five(model: &str, args: &[&str], name: &str) -> f64 {
    let (stdout, stderr) = run(model, &[args, &["--until", "5"]].concat(), 0);
    printed(&format!("{stdout}{stderr}"), name)
}

/// Asserts that every adaptive method at tolerance 1e-12 gives `name` within 1e-11 of
/// `exact` (relative), and RK4 converges at fourth order: its errors at h = 0.05 and
/// 0.025 fall by at least 14 (16 at fourth order; before, 2 at first order).
fn assert_every_method(model: &str, args: &[&str], name: &str, exact: f64) {
    for method in ["dormand-prince", "dop853", "sdirk4", "taylor"] {
        let adaptive = [args, &["--method", method, "--tol", "1e-12"]].concat();
        let found = at_five(model, &adaptive, name);
        let error = (found - exact).abs() / exact.abs();
        assert!(
            error <= 1e-11,
            "{model} {method}: {found} vs {exact} ({error:e})"
        );
    }
    let errors = ["0.05", "0.025"].map(|step| {
        let fixed = [args, &["--method", "rk4", "--step", step]].concat();
        (at_five(model, &fixed, name) - exact).abs()
    });
    let ratio = errors[0] / errors[1];
    assert!(
        ratio >= 14.0 && errors[1] > 1e-12,
        "{model} RK4: errors {errors:?}, ratio {ratio}"
    );
}

#[test]
fn a_mass_law_of_a_table_of_t_meets_the_closed_form() {
    let exact = 1000.0 * (5.0_f64 / 3.0).ln() - 9.81 * 5.0;
    let args = ["--set", "u_e=1000", "--set", "g=9.81", "--init", "y=0"];
    assert_every_method("mass_law_of_t.vms", &args, "y'", exact);
}

#[test]
fn an_inertia_law_of_a_table_of_t_meets_the_closed_form() {
    let exact = (5.0_f64 / 4.2).ln() / 0.8
        + (4.2_f64 / 3.9).ln() / 0.3
        + (3.9_f64 / 3.0).ln() / 0.9
        + 2.0 / 3.0;
    let args = ["--set", "m0=2", "--set", "tau=1", "--init", "th=0"];
    assert_every_method("inertia_law_of_t.vms", &args, "th'", exact);
}

#[test]
fn a_position_of_a_table_of_t_meets_the_closed_form() {
    let omega = 0.5_f64.sqrt();
    let exact = 5.0 * (5.0 * omega).cos() - 1.05 / omega * (5.0 * omega).sin() - 3.0;
    let args = ["--set", "m0=2", "--set", "k=1", "--init", "x=0"];
    assert_every_method("position_of_t.vms", &args, "x", exact);
}

/// `mass m = M(x)` of the same table, outflow at −u_e = −1, no gravity, from x = 0, ẋ = 1:
/// m v̇ = −u_e ṁ, so v − 1 − ln(5/m) = 0 along the run (m = p_x/ẋ), which passes every
/// knot and the held end. Relative to v at t = 5. Before, the crossing of the last knot
/// left x an ulp past it, where the slope still read −0.9: Taylor 6.4 % off, RK4 at
/// h = 0.025 9.6e-4. Measured: 3.1e-14 (Taylor), 2.9e-12 (DOP853), 1.6e-13
/// (Dormand–Prince), 4.4e-12 (SDIRK4); RK4 1.6e-9 and 1.1e-10 (ratio 14.9).
#[test]
fn a_mass_law_of_a_table_of_the_state_keeps_its_invariant() {
    let invariant = |method: &[&str]| {
        let args = [
            &["--set", "u_e=1", "--init", "x=0", "--init", "x'=1"],
            method,
        ]
        .concat();
        let (stdout, stderr) = run(
            "mass_law_of_x.vms",
            &[&args[..], &["--until", "5"]].concat(),
            0,
        );
        let text = format!("{stdout}{stderr}");
        let (v, p) = (printed(&text, "x'"), printed(&text, "p_x"));
        ((v - 1.0 - (5.0 * v / p).ln()) / v).abs()
    };
    for method in ["dormand-prince", "dop853", "sdirk4", "taylor"] {
        let error = invariant(&["--method", method, "--tol", "1e-12"]);
        assert!(error <= 1e-11, "{method}: {error:e}");
    }
    let errors = ["0.05", "0.025"].map(|h| invariant(&["--method", "rk4", "--step", h]));
    assert!(
        errors[0] / errors[1] >= 14.0 && errors[1] > 1e-12,
        "RK4: {errors:?}"
    );
}
