//! `--record` reads a model's tables and its `let`s that call `sqrt` (before, `--record G`
//! and `--record "G(x)"` were refused as tables, and `--record r` with `let r = sqrt(…)`
//! as "`sqrt` is not a function of the DSL").

mod common;

use common::{column, csv, root, varmass, written};

/// `cli/tests/data/tables/affine_box.vms`: a unit mass pushed by G(a x + c), G = 1 on
/// [1, 2] and 0 outside (`outside zero`). With a = 2, c = −1.5 from x = 1.5 at rest the
/// argument starts at 1.5, so x = 1.5 + t²/2 until 2x − 1.5 = 2 (x = 1.75, t = √0.5), then
/// G = 0 and x moves on at t = √0.5. `--record G` is the table at the model's argument
/// 2x − 1.5, `--record "GX=G(x)"` the table at x (1 while x ≤ 2, 0 after): each row must
/// say so from its own x (rows within 1e-9 of a knot, where either side is right, skipped).
#[test]
fn a_table_is_recorded_at_the_model_argument_or_at_any_argument() {
    let model = root("cli/tests/data/tables/affine_box.vms");
    let args = [
        "run",
        &model,
        "--set",
        "a=2",
        "--set",
        "c=-1.5",
        "--init",
        "x=1.5",
        "--until",
        "3",
        "--tol",
        "1e-12",
        "--record",
        "x,G,GX=G(x)",
    ];
    let (header, rows) = csv(&written(&args, "record_tables_box.csv"));
    let (x, g, h) = (
        column(&header, "x"),
        column(&header, "G"),
        column(&header, "GX"),
    );
    let inside = |s: f64| if (1.0..=2.0).contains(&s) { 1.0 } else { 0.0 };
    let near_knot = |s: f64| [1.0, 2.0].iter().any(|k| (s - k).abs() < 1e-9);
    let (mut ones, mut zeros) = (0, 0);
    for row in &rows {
        let argument = 2.0 * row[x] - 1.5;
        if !near_knot(argument) {
            assert_eq!(row[g], inside(argument), "G at x = {}", row[x]);
            if row[g] == 1.0 {
                ones += 1
            } else {
                zeros += 1
            }
        }
        if !near_knot(row[x]) {
            assert_eq!(row[h], inside(row[x]), "G(x) at x = {}", row[x]);
        }
    }
    // Both sides of the push's end were recorded (x reaches 1.5 + 3·√0.5 − 0.25 > 2).
    assert!(ones > 0 && zeros > 0, "{ones} {zeros}");
}

/// `models/leaking_spring_pendulum_cartesian.vms` has `let r = sqrt(x^2 + y^2)`: the column
/// `r` equals √(x² + y²) from the row's own x and y, to rounding (bound 4 ulp of r).
#[test]
fn a_let_that_calls_sqrt_is_recorded() {
    let model = root("models/leaking_spring_pendulum_cartesian.vms");
    let args = [
        "run",
        &model,
        "--set",
        "mu=0.05",
        "--set",
        "u_e=3",
        "--set",
        "k=50",
        "--set",
        "l0=1",
        "--set",
        "g=9.81",
        "--init",
        "x=0.5",
        "--init",
        "y=-1",
        "--init",
        "m=2",
        "--until",
        "2",
        "--record",
        "x,y,r,q=sqrt(r)",
    ];
    let (header, rows) = csv(&written(&args, "record_tables_sqrt.csv"));
    let (x, y, r, q) = (
        column(&header, "x"),
        column(&header, "y"),
        column(&header, "r"),
        column(&header, "q"),
    );
    assert!(rows.len() > 10, "{}", rows.len());
    for row in &rows {
        let exact = row[x].hypot(row[y]);
        assert!(
            (row[r] - exact).abs() <= 4.0 * f64::EPSILON * exact,
            "{row:?}"
        );
        assert!(
            (row[q] - exact.sqrt()).abs() <= 4.0 * f64::EPSILON,
            "{row:?}"
        );
    }
}

/// A table given two arguments is refused naming it, with exit 2.
#[test]
fn a_table_given_two_arguments_is_refused() {
    let model = root("cli/tests/data/tables/affine_box.vms");
    let args = [
        "run", &model, "--set", "a=2", "--set", "c=-1.5", "--init", "x=1.5", "--until", "1",
        "--record", "G(x, x)",
    ];
    let (_, stderr) = varmass(&args, 2);
    assert!(
        stderr.contains("`G` is a table: a function of one argument, given 2"),
        "{stderr}"
    );
}
