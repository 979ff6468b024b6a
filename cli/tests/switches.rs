//! Jumps, failed runs and phases at the command line: a mass law that jumps is refused by
//! `check`, a failed run writes the points it computed and exits 1.

use std::path::PathBuf;

use assert_cmd::Command;

/// A file of this crate's test data.
fn data(name: &str) -> String {
    format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"))
}

/// Runs the tool, asserting the exit code; returns stdout and stderr.
fn run(args: &[&str], code: i32) -> (String, String) {
    let output = Command::cargo_bin("varmass")
        .expect("the binary is built")
        .args(args)
        .output()
        .expect("runs");
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(code), "{stdout}\n{stderr}");
    (stdout, stderr)
}

#[allow(dead_code)]
fn scratch(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name)
}

/// The 23 % example: stage separation as a `sign` in the mass law is refused at
/// `sign` (line 3, column 25 of the file), exit 1, with help pointing to phases.
#[test]
fn check_refuses_a_mass_law_that_jumps() {
    let file = data("staged_by_sign.vms");
    let (_, stderr) = run(&["check", &file], 1);
    assert!(stderr.contains("the law of `m` can jump"), "{stderr}");
    assert!(stderr.contains(&format!("--> {file}:3:25")), "{stderr}");
    assert!(stderr.contains("phases"), "{stderr}");
}
