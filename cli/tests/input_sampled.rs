//! A sampled input in the command line tool (docs/inputs.md#sampled-inputs):
//! `varmass run hover_sampled.vms --input 'u=…'` holds the law's value between samples at
//! 100 Hz as the macro's generated code holds the Rust method's, run for run.

mod common;

use common::{csv, data, written};
use varmass::core::nalgebra::Vector4;
use varmass::core::steppers::{AdaptiveControl, DormandPrince, StepControl};
use varmass::core::{run, RunConfig};
use varmass::prelude::variable_mass_system;

/// The model of `cli/tests/data/hover_sampled.vms`, the law in Rust.
#[variable_mass_system(file = "tests/data/hover_sampled.vms")]
struct Held {
    u_e: f64,
    g: f64,
}

impl HeldInputs for Held {
    fn u(&self, _t: f64, y: f64, y_dot: f64) -> f64 {
        G + 4.0 * (10.0 - y) - 2.5 * y_dot
    }
}

const G: f64 = 9.80665;
const END: f64 = 3.0;

/// The tool's run: rows of t, y, p_y, m, u.
fn tool(extra: &[&str], name: &str) -> Vec<Vec<f64>> {
    let model = data("hover_sampled.vms");
    let end = END.to_string();
    let mut args = vec![
        "run",
        &model,
        "--set",
        "u_e=2000",
        "--set",
        "g=9.80665",
        "--set",
        "kp=4",
        "--set",
        "kd=2.5",
        "--set",
        "y_ref=10",
        "--init",
        "y=0",
        "--init",
        "m=50",
        "--until",
        &end,
        "--input",
        "u=g + kp*(y_ref - y) - kd*y'",
        "--tol",
        "1e-10",
        "--record",
        "y,p_y,m,u",
    ];
    args.extend(extra);
    let (names, rows) = csv(&written(&args, &format!("{name}.csv")));
    assert_eq!(names, ["t", "y", "p_y", "m", "u"]);
    rows
}

/// The macro's run with the same steps: (t, [y, p, m, u]) at every point.
fn generated() -> Vec<(f64, Vector4<f64>)> {
    let system = Held { u_e: 2000.0, g: G };
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance: 1e-10,
        ..AdaptiveControl::default()
    });
    let start = Vector4::new(0.0, 0.0, 50.0, 0.0);
    let mut stepper = DormandPrince::new(&system, 0.0, start, control).unwrap();
    let solution = run(&mut stepper, &RunConfig::until(END), &[]).unwrap();
    solution.times.into_iter().zip(solution.states).collect()
}

/// The largest difference of the tool's rows from the macro's points at each sample time
/// t_k (the last row there, after the sample), relative to each column's largest value.
fn largest_difference(rows: &[Vec<f64>], points: &[(f64, Vector4<f64>)]) -> f64 {
    let mut scale = [0.0_f64; 4];
    for (_, x) in points {
        for k in 0..4 {
            scale[k] = scale[k].max(x[k].abs());
        }
    }
    let mut worst = 0.0_f64;
    let mut compared = 0;
    for k in 0..=300 {
        let t = k as f64 * 0.01;
        let row = rows.iter().rev().find(|r| r[0] == t);
        let point = points.iter().rev().find(|(time, _)| *time == t);
        let (Some(row), Some((_, x))) = (row, point) else {
            panic!("both runs land on the sample at {t}");
        };
        for j in 0..4 {
            worst = worst.max((row[j + 1] - x[j]).abs() / scale[j]);
        }
        compared += 1;
    }
    assert_eq!(compared, 301);
    worst
}

#[test]
fn the_tool_holds_a_sampled_law_as_the_macro_holds_the_method() {
    let rows = tool(&[], "sampled");
    let points = generated();
    // Measured 2.3e-16 (the tape and the generated code round differently, the steps are
    // the same); bound 1e-12.
    let difference = largest_difference(&rows, &points);
    println!("largest relative difference {difference:e}");
    assert!(difference <= 1e-12, "{difference:e}");
    // Held: every row carries the value of the last sample (at a sample time the tool
    // writes the row before the sample, then the one after).
    let mut held = f64::NAN;
    for (i, row) in rows.iter().enumerate() {
        let on_grid = (row[0] / 0.01).round() * 0.01 == row[0];
        let last_there = rows.get(i + 1).is_none_or(|next| next[0] != row[0]);
        if on_grid && last_there {
            held = row[4];
        } else {
            assert_eq!(row[4], held, "held at {}", row[0]);
        }
    }
}

#[test]
fn output_times_off_the_grid_do_not_sample() {
    // `--every 0.004` runs from output time to output time: the held value keeps its grid
    // (a run continuing another does not sample at its start), so the end state is the
    // plain run's to the tolerance's rounding.
    let every = tool(&["--every", "0.004"], "sampled_every");
    let plain = tool(&[], "sampled_plain");
    let (a, b) = (every.last().unwrap(), plain.last().unwrap());
    let worst = (1..5)
        .map(|j| (a[j] - b[j]).abs() / b[j].abs().max(1.0))
        .fold(0.0, f64::max);
    // Measured 2.9e-14 (the output times cut the steps differently, each at tolerance
    // 1e-10); bound 1e-9. Sampled at 0.004 as well, u would differ by ~1e-1 within 10 ms.
    println!("every vs plain {worst:e}");
    assert!(worst <= 1e-9, "{worst:e}");
    // Rows at 0.004 and 0.008 carry the sample at 0.
    assert_eq!(every[1][4], every[0][4]);
    assert_eq!(every[2][4], every[0][4]);
}

#[test]
fn every_method_of_the_tool_holds_the_input() {
    // Taylor (the held value a constant series of the interpreter's Taylor tapes) and
    // SDIRK4 (the interpreter's Jacobian by differences, the held column included) fly the
    // same held controller as Dormand–Prince: the end states agree to the tolerance.
    let reference = tool(&[], "sampled_dp");
    for method in ["taylor", "sdirk4", "dop853"] {
        let rows = tool(&["--method", method], &format!("sampled_{method}"));
        let (a, b) = (rows.last().unwrap(), reference.last().unwrap());
        let worst = (1..5)
            .map(|j| (a[j] - b[j]).abs() / b[j].abs().max(1.0))
            .fold(0.0, f64::max);
        println!("{method} vs dormand-prince {worst:e}");
        // Measured 1.4e-16 (Taylor), 5.0e-15 (SDIRK4), 1.2e-16 (DOP853): within 10 ms
        // the flight is nearly polynomial; bound 1e-12.
        assert!(worst <= 1e-12, "{method}: {worst:e}");
    }
}

#[test]
fn a_stop_condition_on_the_held_value_stops_at_the_sample_that_crosses_it() {
    // u only changes at samples: `--stop-when u<20` is met across the jump at a sample
    // time, and the run stops there with the value after it.
    let rows = tool(&["--stop-when", "u<20"], "sampled_stop");
    let (before, last) = (&rows[rows.len() - 2], &rows[rows.len() - 1]);
    assert_eq!(before[0], last[0], "the rows before and after the sample");
    assert_eq!(
        (last[0] / 0.01).round() * 0.01,
        last[0],
        "on the grid: {}",
        last[0]
    );
    assert!(before[4] >= 20.0 && last[4] < 20.0, "{before:?} → {last:?}");
    assert!(last[0] < END, "stopped at {}", last[0]);
}
