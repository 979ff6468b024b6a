//! `varmass derive`: the whole derivation of the paper's sled (`models/sled.vms` with its
//! impact), as text and as LaTeX, snapshot-tested.

use assert_cmd::Command;

fn derive(extra: &[&str]) -> String {
    let file = format!("{}/../models/sled.vms", env!("CARGO_MANIFEST_DIR"));
    let output = Command::cargo_bin("varmass")
        .expect("built")
        .args(["derive", &file, "--with", "impact"])
        .args(extra)
        .output()
        .expect("runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("UTF-8")
}

#[test]
fn the_sled_derivation_as_text() {
    insta::assert_snapshot!(derive(&[]));
}

#[test]
fn the_sled_derivation_as_latex() {
    insta::assert_snapshot!(derive(&["--latex"]));
}
