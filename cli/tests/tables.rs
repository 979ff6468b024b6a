//! Tables at the command line (docs/tables.md): `varmass run` reads a model's table files
//! relative to the model file, lands on the knots of tables of t, and a table asked for a
//! value outside its data ends the run with exit 1 naming the table and the argument.

use varmass::core::table::Interpolation;

mod common;

use common::{data, motor, root, scratch, varmass as run};

/// `models/motor_rocket.vms` run from another directory: the mass follows the closed form
/// m(t) = m₀ − I(t)/u_e (I the exact trapezoid integral of the thrust curve) at every
/// recorded time; ṁ is piecewise linear in t between knots, so landing on them integrates m
/// exactly up to rounding.
#[test]
fn the_motor_rocket_runs_from_its_table_file() {
    let u_e = motor().exhaust_speed();
    let impulse = Interpolation::Linear
        .interpolate(&motor().thrust)
        .antiderivative();
    let csv = scratch("motor_rocket.csv");
    run(
        &[
            "run",
            &root("models/motor_rocket.vms"),
            "--set",
            &format!("u_e={u_e:?}"),
            "--set",
            "g=9.80665",
            "--init",
            "y=0",
            "--init",
            "m=20",
            "--until",
            "6",
            "--tol",
            "1e-12",
            "--record",
            "m",
            "--csv",
            csv.to_str().unwrap(),
        ],
        0,
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut worst = 0.0_f64;
    let mut rows = 0;
    for line in text.lines().skip(1) {
        let row: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let (t, m) = (row[0], row[1]);
        let exact = 20.0 - impulse.value(t.min(impulse.domain().1)) / u_e;
        worst = worst.max((m - exact).abs() / 20.0);
        rows += 1;
    }
    assert!(rows > 10, "{rows} rows");
    // Measured 5.3e-16 over 116 recorded rows; bound 1e-12 (the at tolerance 1e-12).
    assert!(worst <= 1e-12, "relative error in m {worst:e}");
}

/// Without `outside …`, past the last point of the curve (burnout at 3.9 s): exit 1 naming
/// the table and the argument.
#[test]
fn a_table_outside_its_data_fails_the_run_naming_it() {
    let u_e = motor().exhaust_speed();
    let (_, stderr) = run(
        &[
            "run",
            &data("tables/strict_rocket.vms"),
            "--set",
            &format!("u_e={u_e:?}"),
            "--set",
            "g=9.80665",
            "--init",
            "y=0",
            "--init",
            "m=20",
            "--until",
            "6",
        ],
        1,
    );
    assert!(stderr.contains("the run failed at t = 3.9"), "{stderr}");
    assert!(stderr.contains("table `F` has no value at"), "{stderr}");
}

/// A table file that is malformed is a diagnostic at the file's name with the file's line,
/// exit 1 (a model that fails).
#[test]
fn a_malformed_table_file_is_a_diagnostic_with_its_line() {
    let dir = scratch("bad_table");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("thrust.csv"), "time_s,thrust_N\n0,1\n0.5,x\n").unwrap();
    let model = dir.join("model.vms");
    std::fs::write(
        &model,
        "coordinates y\ntable F(t) = \"thrust.csv\"\nkinetic 1/2*y'^2\nforce y: F(t)\n",
    )
    .unwrap();
    let (_, stderr) = run(&["check", model.to_str().unwrap()], 1);
    assert!(
        stderr.contains("thrust.csv:3:5: `x` is not a number"),
        "{stderr}"
    );
    assert!(stderr.contains("model.vms:2:14"), "{stderr}");
}

/// `varmass run` of `tests/data/tables/recorded_only.vms` (m0 = 2, g = 10, from y = 0) with
/// `extra`, recording `record` into the CSV `name`.csv (removed first); expects exit `code`;
/// returns the CSV's path and stderr.
fn recorded_only(
    name: &str,
    extra: &[&str],
    record: &str,
    code: i32,
) -> (std::path::PathBuf, String) {
    let csv = scratch(format!("{name}.csv"));
    let _ = std::fs::remove_file(&csv);
    let model = data("tables/recorded_only.vms");
    let mut args = vec![
        "run", &model, "--set", "m0=2", "--set", "g=10", "--init", "y=0", "--record", record,
    ];
    args.extend(extra);
    args.extend(["--csv", csv.to_str().unwrap()]);
    let (_, stderr) = run(&args, code);
    (csv, stderr)
}

/// V = m0 g y + h(t) of `tests/data/tables/recorded_only.vms` at (t, y): y = −g t²/2 from
/// rest, h the linear ramp (0, 0), (0.5, 1), (1, 3) of `ramp.csv`.
fn ramp_potential(t: f64, y: f64) -> f64 {
    let h = if t <= 0.5 {
        2.0 * t
    } else {
        1.0 + 4.0 * (t - 0.5)
    };
    2.0 * 10.0 * y + h
}

/// A table that only a recorded quantity reads (h(t) in V, not in the equations): past its
/// data the run goes on, V has no value, and the run fails there with exit 1 naming the
/// quantity and the time — the CSV keeping every row before that point, each the closed
/// form (before the fix the first unrecordable point dropped every row: no CSV at all).
#[test]
fn a_point_that_cannot_be_recorded_keeps_the_rows_before_it() {
    let (csv, stderr) = recorded_only(
        "recorded_only",
        &["--until", "2", "--every", "0.25"],
        "y,V",
        1,
    );
    assert!(
        stderr.contains("cannot record `V` at t = 1.25: table `h` has no value at 1.25"),
        "{stderr}"
    );
    let text = std::fs::read_to_string(&csv).expect("the CSV is written");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,y,V"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let times: Vec<f64> = rows.iter().map(|r| r[0]).collect();
    assert_eq!(times, [0.0, 0.25, 0.5, 0.75, 1.0]);
    for row in &rows {
        let (t, y, v) = (row[0], row[1], row[2]);
        // y is quadratic in t: Dormand–Prince is exact to rounding (measured ≤ 1 ulp).
        assert!((y + 5.0 * t * t).abs() <= 1e-14, "y({t}) = {y}");
        let exact = ramp_potential(t, y);
        assert!(
            (v - exact).abs() <= 1e-13 * (1.0 + exact.abs()),
            "V({t}) = {v}"
        );
    }
}

/// The interpreter's stop times are the generated code's: the knots of a table of t that
/// only V (L, H) reads — `emit`'s code roots hold L and H, so the macro's `next_stop_time`
/// gives h's knots — are stop times of `varmass run` too: every accepted step, recorded,
/// lands on t = 0.5 and t = 1 exactly (before the fix the steps went from 0.0555 to 2).
#[test]
fn a_table_read_only_by_a_recorded_quantity_places_stop_times() {
    let (csv, _) = recorded_only("recorded_stops", &["--until", "1"], "y", 0);
    let text = std::fs::read_to_string(&csv).expect("the CSV is written");
    let times: Vec<f64> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert!(times.contains(&0.5), "{times:?}");
    assert_eq!(times.last(), Some(&1.0));
}
