//! What the tool's integration tests share: the repository's files, a scratch directory,
//! the `varmass` binary run with arguments (its exit code asserted), and the CSV a run
//! writes. Each test file is its own crate and uses some of these (`mod common;`).
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use varmass::core::table::Motor;

/// A file of the repository by its path from the root (`models/sled.vms`); the cli crate
/// sits one level below the root.
pub fn root(path: &str) -> String {
    format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"))
}

/// A model file of `models/`.
pub fn model(name: &str) -> String {
    root(&format!("models/{name}"))
}

/// A file of the tool's own test data, `cli/tests/data/`.
pub fn data(name: &str) -> String {
    format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// A path in the tests' scratch directory (cargo's, kept between runs).
pub fn scratch(name: impl AsRef<Path>) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

/// The Cesaroni M1670 motor of `models/motors/`, whose thrust table the model rocket
/// `models/motor_rocket.vms` reads.
pub fn motor() -> Motor {
    let text = std::fs::read_to_string(root("models/motors/Cesaroni_M1670.eng")).unwrap();
    Motor::parse(&text).unwrap()
}

/// Writes `text` to the scratch file `name`; returns its path.
pub fn scratch_file(name: &str, text: &str) -> String {
    let path = scratch(name);
    std::fs::write(&path, text).expect("writable");
    path.display().to_string()
}

/// Runs `varmass ARGS` (in the cli crate's directory, as cargo runs the tests), asserting
/// exit `code` and that nothing panicked; returns stdout and stderr.
pub fn varmass(args: &[&str], code: i32) -> (String, String) {
    varmass_in(env!("CARGO_MANIFEST_DIR"), args, code)
}

/// [`varmass`] run in the directory `dir` (where relative paths are read from).
pub fn varmass_in(dir: &str, args: &[&str], code: i32) -> (String, String) {
    let (status, stdout, stderr) = output_in(dir, args);
    assert_eq!(status, Some(code), "{args:?}:\n{stdout}\n{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    (stdout, stderr)
}

/// Runs `varmass ARGS` in the cli crate's directory without asserting its exit: the exit
/// code (`None` if a signal ended it), stdout and stderr.
pub fn output(args: &[&str]) -> (Option<i32>, String, String) {
    output_in(env!("CARGO_MANIFEST_DIR"), args)
}

/// [`output`] run in the directory `dir`.
pub fn output_in(dir: &str, args: &[&str]) -> (Option<i32>, String, String) {
    let output = Command::cargo_bin("varmass")
        .expect("the binary is built")
        .current_dir(dir)
        .args(args)
        .output()
        .expect("runs");
    let text = |bytes: &[u8]| String::from_utf8_lossy(bytes).into_owned();
    (
        output.status.code(),
        text(&output.stdout),
        text(&output.stderr),
    )
}

/// Runs `varmass ARGS --csv FILE` in `dir`, FILE the scratch file `name` (removed first, so
/// a run that writes nothing cannot pass on an old file), expecting exit 0; returns FILE.
pub fn written_in(dir: &str, args: &[&str], name: &str) -> PathBuf {
    let path = scratch(name);
    let _ = std::fs::remove_file(&path);
    let file = path.to_str().expect("a UTF-8 path");
    varmass_in(dir, &[args, &["--csv", file]].concat(), 0);
    path
}

/// [`written_in`] the cli crate's directory.
pub fn written(args: &[&str], name: &str) -> PathBuf {
    written_in(env!("CARGO_MANIFEST_DIR"), args, name)
}

/// The CSV a run wrote at `path`: its column names and its rows of numbers.
pub fn csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).expect("the CSV is written");
    let mut lines = text.lines();
    let header = lines.next().expect("a header");
    let names = header.split(',').map(str::to_string).collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect())
        .collect();
    (names, rows)
}

/// The index of the column `name` among `names`.
pub fn column(names: &[String], name: &str) -> usize {
    names
        .iter()
        .position(|n| n == name)
        .unwrap_or_else(|| panic!("no column {name} in {names:?}"))
}

/// The stored median and spread columns of one quantity of NASA's check-case `case`
/// (`validation/nasa/case_NN.csv`): {time (ms): (median, spread)}.
pub fn nasa_reference(case: u32, name: &str) -> std::collections::HashMap<i64, (f64, f64)> {
    let text = std::fs::read_to_string(root(&format!("validation/nasa/case_{case:02}.csv")))
        .expect("the stored medians");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let at = |n: &str| header.iter().position(|h| *h == n).expect(n);
    let (m, s) = (at(name), at(&format!("{name}_spread")));
    lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap())
                .collect::<Vec<f64>>()
        })
        .map(|v| ((v[0] * 1000.0).round() as i64, (v[m], v[s])))
        .collect()
}

/// The value a `varmass fit` report `stdout` gives `name` (its line `name = value ± error`).
pub fn reported(stdout: &str, name: &str) -> f64 {
    let line = (stdout.lines())
        .find(|l| l.trim_start().starts_with(&format!("{name} = ")))
        .unwrap_or_else(|| panic!("{name} in {stdout}"));
    let value = line.split(" = ").nth(1).and_then(|v| v.split('±').next());
    value.expect("a value").trim().parse().expect("a number")
}

/// The standard error a `varmass fit` report `stdout` gives `name` (its line `name = value ±
/// error`, the error to two significant digits).
pub fn reported_error(stdout: &str, name: &str) -> f64 {
    let line = (stdout.lines())
        .find(|l| l.trim_start().starts_with(&format!("{name} = ")))
        .unwrap_or_else(|| panic!("{name} in {stdout}"));
    let error = line
        .split('±')
        .nth(1)
        .and_then(|e| e.split_whitespace().next());
    error.expect("an error").parse().expect("a number")
}

/// The residuals' rms a `varmass fit` report `stdout` gives `quantity`.
pub fn reported_rms(stdout: &str, quantity: &str) -> f64 {
    (stdout.lines())
        .find_map(|l| l.strip_prefix(&format!("residuals of {quantity}: rms ")))
        .and_then(|l| l.split(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("the residuals' rms of {quantity} in {stdout}"))
}

/// The predicted event's time on the data's clock a `varmass fit --predict` report
/// `stdout` gives (`(the data's clock: T ± E)`).
pub fn reported_clock(stdout: &str) -> f64 {
    (stdout.split("(the data's clock: ").nth(1))
        .and_then(|v| v.split(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("the event's time on the data's clock in {stdout}"))
}
