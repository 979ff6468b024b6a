//! `varmass run --input NAME=EXPRESSION` (docs/inputs.md#the-command-line-tool): the law
//! replaces each call of the input before anything is derived, so a model with an input
//! and its law runs as the same model with the law written in place, and every mistake in
//! the option is a message and exit 2.

mod common;

use common::{csv, data, scratch_file, varmass, written};

/// The hover flight's options: parameters, start on the ground at rest with 50 kg, 15 s.
const FLIGHT: [&str; 16] = [
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
    "15",
];

/// The CSV `varmass run MODEL FLIGHT EXTRA --csv …` writes, as rows of numbers.
fn flight(model: &str, extra: &[&str], name: &str) -> Vec<Vec<f64>> {
    let model = data(model);
    let mut args = vec!["run", model.as_str()];
    args.extend(FLIGHT);
    args.extend(extra);
    csv(&written(&args, &format!("{name}.csv"))).1
}

const PD: &str = "u=g + kp*(y_ref - y) - kd*y'";

#[test]
fn a_law_from_the_command_line_runs_as_the_law_written_in_the_model() {
    for (method, name) in [
        ("dormand-prince", "dp"),
        ("dop853", "dop853"),
        ("sdirk4", "sdirk4"),
        ("taylor", "taylor"),
    ] {
        let options = ["--method", method, "--tol", "1e-10"];
        let mut with_input = vec!["--input", PD];
        with_input.extend(options);
        let given = flight("hover_input.vms", &with_input, &format!("law_{name}"));
        let written = flight("hover_law.vms", &options, &format!("written_{name}"));
        // The same steps (the adaptive control saw the same equations) and the same
        // values: the substituted syntax tree is the written one, so the program is too
        // (Taylor too: a law has recurrences, an input from Rust has none).
        assert_eq!(given.len(), written.len(), "{method}");
        assert!(given.len() > 20, "{method}: {} rows", given.len());
        let mut worst = 0.0_f64;
        for (a, b) in given.iter().zip(&written) {
            for (x, y) in a.iter().zip(b) {
                worst = worst.max((x - y).abs() / y.abs().max(1.0));
            }
        }
        // Measured 0 (bit-identical); 1e-13 allows for rounding.
        assert!(worst <= 1e-13, "{method}: {worst:e}");
        // The controller did its work: 10 m after 15 s (a damped PD, ζ = 0.625).
        let last = given.last().expect("rows");
        assert!((last[1] - 10.0).abs() < 0.01, "{last:?}");
    }
}

#[test]
fn a_missing_law_names_the_input() {
    let model = data("hover_input.vms");
    let mut args = vec!["run", model.as_str()];
    args.extend(FLIGHT);
    let (_, stderr) = varmass(&args, 2);
    assert!(
        stderr.contains("no law for input `u`: the model declares `input u(t, y, y')`; give --input 'u=EXPRESSION'"),
        "{stderr}"
    );
}

#[test]
fn a_law_for_an_undeclared_name_suggests_the_input() {
    let model = data("hover_input.vms");
    let mut args = vec!["run", model.as_str(), "--input", "uu=1"];
    args.extend(FLIGHT);
    let (_, stderr) = varmass(&args, 2);
    assert!(
        stderr.contains("`uu` is not an input of the model (did you mean `u`?)"),
        "{stderr}"
    );
    // A model without inputs says so.
    let law = data("hover_law.vms");
    let mut args = vec!["run", law.as_str(), "--input", "u=1"];
    args.extend(FLIGHT);
    let (_, stderr) = varmass(&args, 2);
    assert!(
        stderr.contains("--input u: the model declares no input"),
        "{stderr}"
    );
}

#[test]
fn a_bad_law_is_refused_with_its_column() {
    let model = data("hover_input.vms");
    for (law, expected) in [
        // `+` at column 10 of `g - kp*y +`, and the missing operand at column 11.
        (
            "u=g - kp*y +",
            "--input u: expected an expression after `+` at column 11 of `g - kp*y +`",
        ),
        ("u", "--input `u`: expected NAME=EXPRESSION"),
        ("u=2*u(t, y, y')", "--input u: the law calls input `u`"),
    ] {
        let mut args = vec!["run", model.as_str(), "--input", law];
        args.extend(FLIGHT);
        let (_, stderr) = varmass(&args, 2);
        assert!(stderr.contains(expected), "{law}: {stderr}");
    }
}

#[test]
fn a_law_with_an_unknown_function_points_at_the_call_in_the_model() {
    let model = data("hover_input.vms");
    let mut args = vec!["run", model.as_str(), "--input", "u=sine(t)"];
    args.extend(FLIGHT);
    let (_, stderr) = varmass(&args, 1);
    assert!(stderr.contains("unknown function `sine`"), "{stderr}");
    // The first call of `u` is on line 5 of the model.
    assert!(stderr.contains(&format!("{model}:5:")), "{stderr}");
}

#[test]
fn a_sampled_input_with_a_bad_period_is_a_diagnostic_at_the_period() {
    // `every 0.01` runs (cli/tests/input_sampled.rs); a period that is no positive number of
    // seconds is the model's mistake, shown at the period (column 25 of line 4).
    let text = std::fs::read_to_string(data("hover_input.vms"))
        .expect("read")
        .replace("input u(t, y, y')", "input u(t, y, y') every 0");
    let file = scratch_file("bad_period.vms", &text);
    let mut args = vec!["run", file.as_str(), "--input", PD];
    args.extend(FLIGHT);
    let (_, stderr) = varmass(&args, 1);
    assert!(
        stderr.contains("the sample period `0` is not a positive number of seconds"),
        "{stderr}"
    );
    assert!(stderr.contains(&format!("{file}:4:25")), "{stderr}");
}
