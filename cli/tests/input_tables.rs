//! `--input NAME=FILE.csv` (docs/tables.md#runtime-tables): an input given by a table of its
//! first argument (here t) runs as the same model with the table written in it, to every
//! printed digit; a bad file is exit 2 with its line.

mod common;

use common::{data, scratch_file, varmass_in, written_in};

/// Runs `varmass ARGS` in the data directory (relative table paths are read from there),
/// expecting exit `code`; returns stderr.
fn varmass(args: &[&str], code: i32) -> String {
    varmass_in(&data(""), args, code).1
}

/// The hover flight to 15 s of the data directory's `model`: the CSV text of y, y', m at
/// every step.
fn flight(model: &str, extra: &[&str], name: &str) -> String {
    flight_of(&data(model), extra, name)
}

/// [`flight`] of the model file at `model`.
fn flight_of(model: &str, extra: &[&str], name: &str) -> String {
    let mut args = vec!["run", model];
    args.extend([
        "--set",
        "u_e=2000",
        "--set",
        "g=9.80665",
        "--init",
        "y=0",
        "--init",
        "m=50",
        "--until",
        "15",
        "--tol",
        "1e-10",
        "--record",
        "y,y',m",
    ]);
    args.extend(extra);
    let csv = written_in(&data(""), &args, &format!("{name}.csv"));
    std::fs::read_to_string(csv).expect("the CSV is written")
}

#[test]
fn an_input_given_by_a_table_file_is_the_dsl_table() {
    let dsl = flight("hover_table.vms", &[], "hover_dsl_table");
    // Relative to the current directory (the data directory here).
    let given = flight(
        "hover_input.vms",
        &["--input", "u=tables/hover_u.csv"],
        "hover_input_table",
    );
    // The table's 7 knots inside (0, 15) are stop times either way: some 20 rows at least.
    assert!(dsl.lines().count() > 20, "{dsl}");
    assert_eq!(dsl, given);
}

#[test]
fn a_bad_input_table_file_is_an_input_error_with_its_line() {
    let bad = scratch_file("bad_input.csv", "t,u\n0,1\n1,x\n");
    let model = data("hover_input.vms");
    let option = format!("u={bad}");
    let stderr = varmass(
        &[
            "run", &model, "--set", "u_e=2000", "--set", "g=9.8", "--init", "m=50", "--until", "1",
            "--input", &option,
        ],
        2,
    );
    assert!(
        stderr.contains("--input u: ") && stderr.contains("bad_input.csv:3:3"),
        "{stderr}"
    );
    let stderr = varmass(
        &[
            "run",
            &model,
            "--set",
            "u_e=2000",
            "--set",
            "g=9.8",
            "--init",
            "m=50",
            "--until",
            "1",
            "--input",
            "u=missing.csv",
        ],
        2,
    );
    assert!(
        stderr.contains("cannot read the table file `missing.csv`"),
        "{stderr}"
    );
}

#[test]
fn the_table_made_for_an_input_takes_a_name_no_let_has() {
    // The table made for `--input u=FILE` is named `u_table` unless the model spells that
    // name; a `let u_table = …` was not seen (the derivation inlines lets), and the run
    // failed with "`u_table` is declared twice".
    let source = std::fs::read_to_string(data("hover_input.vms")).unwrap();
    let model = scratch_file(
        "hover_input_let.vms",
        &format!("{source}\nlet u_table = 2\n"),
    );
    let input = ["--input", "u=tables/hover_u.csv"];
    let with_let = flight_of(&model, &input, "with_let");
    let without = flight("hover_input.vms", &input, "no_let");
    assert_eq!(with_let, without);
}
