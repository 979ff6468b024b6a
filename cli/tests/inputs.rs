//! Bad input: a clear message on stderr, a non-zero exit, never a panic. `check` on a broken
//! model points at FILE:line:column with a caret.

mod common;

use common::{data, model, scratch_file, varmass};

/// Runs `varmass ARGS`, expecting exit `code`; returns stderr.
fn fails(args: &[&str], code: i32) -> String {
    varmass(args, code).1
}

/// `varmass run` of the sled with `extra` replacing nothing: all parameters set unless
/// `without` names one.
fn sled(without: &str, extra: &[&str]) -> Vec<String> {
    let mut args: Vec<String> = [
        "run",
        &model("sled.vms"),
        "--with",
        "impact",
        "--init",
        "x=0",
        "--until",
        "1",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    for s in ["m0=10", "c=2", "g=9.81", "theta=0.5", "f_d=0.1"] {
        if !s.starts_with(&format!("{without}=")) {
            args.extend(["--set".to_string(), s.to_string()]);
        }
    }
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn run_sled(without: &str, extra: &[&str], code: i32) -> String {
    let args = sled(without, extra);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    fails(&args, code)
}

#[test]
fn check_passes_on_a_good_model() {
    let (stdout, _) = varmass(&["check", &model("sled.vms"), "--with", "impact"], 0);
    assert!(
        stdout.contains("check x'' = g*sin(theta) - f_d*g*cos(theta) - c*x'^2/m ... ok"),
        "{stdout}"
    );
}

#[test]
fn check_on_a_broken_file_points_at_file_line_column() {
    let file = data("broken.vms");
    let stderr = fails(&["check", &file], 1);
    // `mm` on line 3, column 17.
    assert!(stderr.contains(&format!("--> {file}:3:17")), "{stderr}");
    assert!(
        stderr.contains("body sled: mass mm, position [x]"),
        "{stderr}"
    );
    assert!(stderr.contains("^^"), "{stderr}");
}

#[test]
fn a_check_that_does_not_hold_exits_1_at_its_line() {
    let file = data("wrong_check.vms");
    let stderr = fails(&["check", &file], 1);
    assert!(stderr.contains(&format!("{file}:6:")), "{stderr}");
}

#[test]
fn a_missing_file_is_named() {
    let stderr = fails(&["check", "no/such/model.vms"], 2);
    assert!(
        stderr.contains("cannot read `no/such/model.vms`"),
        "{stderr}"
    );
}

#[test]
fn an_unknown_parameter_suggests_the_nearest_and_lists_them() {
    let stderr = run_sled("f_d", &["--set", "f_e=0.1"], 2);
    assert!(
        stderr.contains("`f_e` is not a parameter of the model (did you mean `f_d`?)"),
        "{stderr}"
    );
    assert!(stderr.contains("m0, c, g, theta, f_d"), "{stderr}");
}

#[test]
fn a_missing_parameter_lists_the_parameters() {
    let stderr = run_sled("g", &[], 2);
    assert!(
        stderr.contains(
            "missing value for g; the model's parameters are: m0, c, g, theta, f_d; give --set g=VALUE"
        ),
        "{stderr}"
    );
}

#[test]
fn an_unknown_initial_name_suggests_the_nearest() {
    let stderr = run_sled("", &["--init", "xx=1"], 2);
    assert!(
        stderr.contains(
            "`xx` is not a coordinate, velocity or state mass of the model (did you mean `x`?)"
        ),
        "{stderr}"
    );
}

#[test]
fn a_missing_initial_coordinate_is_named() {
    let stderr = fails(
        &[
            "run",
            &model("rocket.vms"),
            "--set",
            "mu=1",
            "--set",
            "u_e=1",
            "--set",
            "g=1",
            "--init",
            "y=0",
            "--until",
            "1",
        ],
        2,
    );
    assert!(stderr.contains("no initial value for m"), "{stderr}");
}

#[test]
fn an_unknown_recorded_name_suggests_the_nearest() {
    let stderr = run_sled("", &["--record", "x,powr"], 2);
    assert!(
        stderr.contains("`powr` is not a quantity of the model (did you mean `power`?)"),
        "{stderr}"
    );
}

#[test]
fn a_stop_condition_must_be_a_comparison_not_yet_true() {
    let stderr = run_sled("", &["--stop-when", "x ~ 5"], 2);
    assert!(
        stderr.contains("--stop-when `x ~ 5`: expected NAME = VALUE, NAME > VALUE or NAME < VALUE"),
        "{stderr}"
    );
    // x starts at 0: `x < 1` holds already, and a crossing would never come.
    let stderr = run_sled("", &["--stop-when", "x < 1"], 2);
    assert!(
        stderr.contains("--stop-when `x < 1` already holds at the start (the value there is 0)"),
        "{stderr}"
    );
}

#[test]
fn an_unparsable_number_is_named() {
    let stderr = run_sled("m0", &["--set", "m0=ten"], 2);
    assert!(stderr.contains("--set: `ten` is not a number"), "{stderr}");
    let stderr = run_sled("", &["--stop-when", "x = fifty"], 2);
    assert!(
        stderr.contains("--stop-when: `fifty` is not a number"),
        "{stderr}"
    );
    let stderr = run_sled("", &["--init", "x"], 2);
    assert!(
        stderr.contains("--init `x`: expected NAME=VALUE"),
        "{stderr}"
    );
}

#[test]
fn a_fixed_step_method_without_a_step_says_so() {
    let stderr = run_sled("", &["--method", "rk4"], 2);
    assert!(
        stderr.contains("--method rk4 takes a fixed step: give --step H"),
        "{stderr}"
    );
}

#[test]
fn a_failed_run_reports_the_typed_error_with_its_time_and_state() {
    // m = 1 − t runs out at t = 1, before --until 2, with no burnout condition.
    let stderr = fails(
        &[
            "run",
            &model("rocket.vms"),
            "--set",
            "mu=1",
            "--set",
            "u_e=10",
            "--set",
            "g=1",
            "--init",
            "y=0",
            "--init",
            "m=1",
            "--until",
            "2",
            "--method",
            "rk4",
            "--step",
            "0.3",
        ],
        1,
    );
    // RK4 at h = 0.3 steps t = 0.9 → 1.2, where m = −0.2: refused, and the run lands
    // halfway again and again looking for an event before the mass runs out (docs/
    // mechanics.md#switches), so it fails where m reaches 0, a rounding before t = 1 (before
    // issue 34: at t = 1.2 with m = −0.2).
    assert!(
        stderr.contains("the run failed at t = 0.9999999999999999: the mass `m` is not positive"),
        "{stderr}"
    );
    assert!(stderr.contains("m = 0\n"), "{stderr}");
}

#[test]
fn an_oversized_model_names_the_limit() {
    let file = scratch_file(
        "nine.vms",
        "coordinates a, b, c, d, e, f, g, h, i\nmass m = 1\nbody p: mass m, position [a, b, c]\nbody q: mass m, position [d, e, f]\nbody r: mass m, position [g, h, i]\n",
    );
    let mut args = vec!["run", file.as_str(), "--until", "1"];
    for init in [
        "a=0", "b=0", "c=0", "d=0", "e=0", "f=0", "g=0", "h=0", "i=0",
    ] {
        args.extend(["--init", init]);
    }
    let stderr = fails(&args, 2);
    assert!(stderr.contains("the model has 9 coordinates and 0 state masses; the tool runs models with 1 to 8 coordinates"), "{stderr}");
}

#[test]
fn an_unknown_tag_names_the_models_tags() {
    let stderr = fails(&["check", &model("sled.vms"), "--with", "drag"], 2);
    assert!(
        stderr.contains("--with: unknown tag `drag`; the model's tags are `impact`"),
        "{stderr}"
    );
}

#[test]
fn a_tag_brings_its_parameters() {
    let stderr = fails(
        &[
            "run",
            &model("rocket.vms"),
            "--with",
            "drag",
            "--set",
            "mu=1",
            "--set",
            "u_e=10",
            "--set",
            "g=1",
            "--init",
            "y=0",
            "--init",
            "m=1",
            "--until",
            "0.5",
        ],
        2,
    );
    assert!(stderr.contains("missing value for k_d"), "{stderr}");
}

#[test]
fn a_model_with_an_input_and_no_law_is_refused_naming_it() {
    let stderr = fails(
        &[
            "run",
            &data("hover_input.vms"),
            "--set",
            "u_e=2000",
            "--set",
            "g=9.8",
            "--init",
            "m=50",
            "--until",
            "1",
        ],
        2,
    );
    assert!(stderr.contains("no law for input `u`"), "{stderr}");
}
