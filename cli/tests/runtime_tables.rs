//! `--table NAME=FILE` (docs/tables.md#runtime-tables): the data of a `table F(t) =
//! runtime` given at the command line, or other data for a file table; the path relative to
//! the current directory; every mistake exit 2 naming the table (and the file's line).

mod common;

use common::{motor, root, varmass_in as run_in, written_in};

/// The M1670 rocket's flight to 6 s at tolerance 1e-10, with `extra` options, recorded as
/// CSV text (y, y', m at every step).
fn flight(model: &str, extra: &[&str], name: &str) -> String {
    let u_e = format!("u_e={:?}", motor().exhaust_speed());
    let mut args = vec![
        "run",
        model,
        "--set",
        &u_e,
        "--set",
        "g=9.80665",
        "--init",
        "y=0",
        "--init",
        "m=20",
        "--until",
        "6",
        "--tol",
        "1e-10",
        "--record",
        "y,y',m",
    ];
    args.extend_from_slice(extra);
    std::fs::read_to_string(written_in(&root(""), &args, name)).unwrap()
}

#[test]
fn a_runtime_table_given_by_file_flies_as_the_file_table_to_the_bit() {
    let file = flight(&root("models/motor_rocket.vms"), &[], "file_table.csv");
    // The path relative to the current directory (the repository's root here).
    let given = flight(
        &root("models/motor_rocket_runtime.vms"),
        &["--table", "F=models/motors/Cesaroni_M1670.eng"],
        "runtime_table.csv",
    );
    assert!(file.lines().count() > 20, "{file}");
    // Every printed digit of every recorded step is the same (the same reader, interpolant
    // and stop times: the derivation reads the given file as it reads the statement's).
    assert_eq!(file, given);
}

#[test]
fn a_table_option_replaces_a_file_tables_data() {
    let m1670 = flight(&root("models/motor_rocket.vms"), &[], "m1670.csv");
    let k828 = flight(
        &root("models/motor_rocket.vms"),
        &["--table", "F=models/motors/AeroTech_K828FJ.eng"],
        "k828_over_file.csv",
    );
    let runtime_k828 = flight(
        &root("models/motor_rocket_runtime.vms"),
        &["--table", "F=models/motors/AeroTech_K828FJ.eng"],
        "k828_runtime.csv",
    );
    assert_ne!(m1670, k828);
    assert_eq!(k828, runtime_k828);
}

#[test]
fn a_runtime_table_without_data_is_refused_naming_it() {
    let (_, stderr) = run_in(
        &root(""),
        &[
            "run",
            &root("models/motor_rocket_runtime.vms"),
            "--set",
            "u_e=1000",
            "--set",
            "g=9.8",
            "--init",
            "m=20",
            "--until",
            "1",
        ],
        2,
    );
    assert!(
        stderr.contains("table `F` is `= runtime`") && stderr.contains("--table F="),
        "{stderr}"
    );
}

#[test]
fn table_mistakes_are_input_errors() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    let bad = dir.join("bad_motor.eng");
    std::fs::write(&bad, "M1 75 757 0 3.0 5.0 X\n0.5 100\n1.O 50\n").unwrap();
    let model = root("models/motor_rocket_runtime.vms");
    let base = [
        "run", &model, "--set", "u_e=1000", "--set", "g=9.8", "--init", "m=20", "--until", "1",
    ];
    let cases: [(String, &str); 5] = [
        (
            format!("F={}", bad.display()),
            "bad_motor.eng:3:1: `1.O` is not a number",
        ),
        (
            "F=missing.eng".to_string(),
            "--table F: cannot read the table file `missing.eng`",
        ),
        (
            "F=models/motor_rocket.vms".to_string(),
            "a RASP motor (`.eng`) or a CSV table",
        ),
        (
            "G=models/motors/AeroTech_K828FJ.eng".to_string(),
            "`G` is not a table of the model",
        ),
        ("F".to_string(), "expected NAME=FILE"),
    ];
    for (option, expected) in cases {
        let mut args = base.to_vec();
        args.extend(["--table", &option]);
        let (_, stderr) = run_in(&root(""), &args, 2);
        assert!(stderr.contains(expected), "{option}: {stderr}");
    }
    // Given twice.
    let mut args = base.to_vec();
    let option = "F=models/motors/AeroTech_K828FJ.eng";
    args.extend(["--table", option, "--table", option]);
    let (_, stderr) = run_in(&root(""), &args, 2);
    assert!(stderr.contains("--table F is given twice"), "{stderr}");
}
