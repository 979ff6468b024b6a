//! Stop times a few roundings apart (the two stop times T₁, T₂ around a knot where an order
//! the equations read jumps, docs/tables.md#knots-are-switches) are crossed by one Euler
//! step, not left to the step controller, and no attempt is retried for ever near a stop
//! time (review of session 33: a force switched on at t = 500 failed with a step underflow
//! at 1e-12; two knots 1e-9 s apart made DOP853 retry h = 2⁻⁵² at t = 1 − 2⁻⁵² for ever).
//!
//! Every run here has a time limit far above its length (a run that never ends fails the
//! test instead of hanging the suite; the limit times nothing).

mod common;

use std::time::Duration;

use assert_cmd::Command;
use common::{csv, data, scratch};

/// Runs `varmass run ARGS --csv FILE` (in the cli crate's directory) and returns the last
/// row of FILE; fails if the run does not exit 0 within two minutes.
fn end_row(args: &[&str], name: &str) -> (Vec<String>, Vec<f64>) {
    let path = scratch(name);
    let _ = std::fs::remove_file(&path);
    let file = path.to_str().expect("a UTF-8 path");
    let output = Command::cargo_bin("varmass")
        .expect("the binary is built")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([&["run"], args, &["--csv", file]].concat())
        .timeout(Duration::from_secs(120))
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{args:?}:\n{stderr}");
    let (names, rows) = csv(&path);
    (names, rows.last().expect("a row").clone())
}

#[test]
fn a_force_switched_on_far_from_t_0_runs_at_tight_tolerances() {
    // m = 20 kg at rest, F = 2000 N on [500, 501] only: ÿ = 100 m/s² there, so at t = 502
    // ẏ = 100 m/s and y = ½·100·1² + 100·1 = 150 m, exactly. Before, DOP853 and
    // Dormand–Prince failed with a step underflow at t = 499.9999999999996.
    let model = data("tables/late_push.vms");
    for method in ["dop853", "dormand-prince"] {
        for tol in ["1e-12", "3e-14"] {
            let args = [
                model.as_str(),
                "--set",
                "m0=20",
                "--init",
                "y=0",
                "--until",
                "502",
                "--method",
                method,
                "--tol",
                tol,
                "--record",
                "y,y'",
            ];
            let (_, row) = end_row(&args, &format!("late_push_{method}_{tol}.csv"));
            // The Euler slivers across the two jumps err by a few roundings of 500 s times
            // the jump (100 m/s²): ~1e-11 m/s. Bound 1e-9 (y, m) and 1e-10 (ẏ, m/s).
            assert!(
                (row[1] - 150.0).abs() < 1e-9,
                "{method} {tol}: y = {}",
                row[1]
            );
            assert!(
                (row[2] - 100.0).abs() < 1e-10,
                "{method} {tol}: y' = {}",
                row[2]
            );
        }
    }
}

#[test]
fn knots_a_nanosecond_apart_are_crossed() {
    // M(t) linear through (0, 5) (1, 4.2) (1 + 1e-9, 4.19) (2, 3.9) (3, 3), held after:
    // from rest, ẏ = u_e ln(M(0)/M(t)) − g t (the outflow at −u_e relative to the body), so
    // at t = 3.5, ẏ = 1000 ln(5/3) − 9.81·3.5. Before, DOP853 at 1e-10 never ended.
    let model = data("tables/close_knots.vms");
    let exact = 1000.0 * (5.0_f64 / 3.0).ln() - 9.81 * 3.5;
    for (method, tol) in [
        ("dop853", "1e-10"),
        ("dormand-prince", "1e-12"),
        ("taylor", "1e-12"),
    ] {
        let args = [
            model.as_str(),
            "--set",
            "u_e=1000",
            "--set",
            "g=9.81",
            "--init",
            "y=0",
            "--until",
            "3.5",
            "--method",
            method,
            "--tol",
            tol,
            "--record",
            "y'",
        ];
        let (_, row) = end_row(&args, &format!("close_knots_{method}.csv"));
        // Bound 1e-10 relative: the tolerances' order over a run of three pieces.
        let error = (row[1] - exact).abs() / exact;
        assert!(
            error < 1e-10,
            "{method} at {tol}: y' = {}, off {error:e}",
            row[1]
        );
    }
}
