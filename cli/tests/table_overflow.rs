//! A table whose pchip or spline interpolant overflows is refused where it is read, naming
//! the file's lines (docs/tables.md#interpolation): before (review of 2026-11-26) the run
//! failed at t = 0 with "the state became non-finite" and a help line blaming the equations.

mod common;

use common::{scratch, varmass};

/// The data 0, 1.5e308, 0, 1.5e308 at t = 0…3 (each slope finite; the cubics' 2δ is not).
const PEAKS: &str = "t,G\n0,0\n1,1.5e308\n2,0\n3,1.5e308\n";

/// Writes `model` (a unit mass pushed by G(t)·1e-300) and peaks.csv into a directory of
/// their own; returns the model's path.
fn model(name: &str, table: &str) -> String {
    let dir = scratch(name);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("peaks.csv"), PEAKS).unwrap();
    let model = dir.join("model.vms");
    let text = format!(
        "coordinates x\n{table}\nmass m = 1\nbody b: mass m, position [x]\nforce b: [G(t)*1e-300]\n"
    );
    std::fs::write(&model, text).unwrap();
    model.to_str().unwrap().to_string()
}

/// `varmass run` with `args` from rest to 2.5 s, expecting exit `code`: its stdout and
/// stderr.
fn run(args: &[&str], code: i32) -> (String, String) {
    let start = ["--init", "x=0", "--init", "x'=0", "--until", "2.5"];
    varmass(&[&["run"][..], args, &start].concat(), code)
}

#[test]
fn a_linear_table_of_huge_values_runs() {
    // v(2.5) = 1e-300 ∫₀^2.5 G, by trapezoids (G is linear between the knots, which are stops):
    // ∫₀² G = 1.5e308, ∫₂^2.5 G = ½ · 0.5 · 0.75e308, so v = 1.5e8 + 0.1875e8 = 1.6875e8
    // (RK4 integrates a linear G exactly: measured 1.6875e8 to the digits printed).
    let file = model("peaks_linear", "table G(s) = \"peaks.csv\", outside zero");
    let (stdout, _) = run(&[&file, "--method", "rk4", "--step", "0.5"], 0);
    assert!(stdout.contains("x' = 1.6875e8"), "{stdout}");
}

#[test]
fn a_model_table_whose_cubics_overflow_is_a_diagnostic_with_its_lines() {
    // A malformed table file of the model is a model that fails (exit 1), as every other.
    for interpolation in ["pchip", "spline"] {
        let table = format!("table G(s) = \"peaks.csv\", {interpolation}, outside zero");
        let file = model(&format!("peaks_{interpolation}"), &table);
        let (_, stderr) = run(&[&file], 1);
        let message = format!(
            "peaks.csv:3:1: the {interpolation} interpolant from (0.0, 0.0) (line 2) to \
             (1.0, 1.5e308) is not finite"
        );
        assert!(stderr.contains(&message), "{stderr}");
        assert!(stderr.contains("model.vms:2:14"), "{stderr}");
        assert!(!stderr.contains("non-finite"), "{stderr}");
    }
}

#[test]
fn a_runtime_table_whose_cubics_overflow_is_an_input_error() {
    // `--table G=FILE` is the command line's input: exit 2.
    let file = model("peaks_runtime", "table G(s) = runtime, pchip, outside zero");
    let peaks = std::path::Path::new(&file).with_file_name("peaks.csv");
    let table = format!("G={}", peaks.display());
    let (_, stderr) = run(&[&file, "--table", &table], 2);
    assert!(
        stderr.contains("peaks.csv:3:1: the pchip interpolant from (0.0, 0.0) (line 2)"),
        "{stderr}"
    );
}
