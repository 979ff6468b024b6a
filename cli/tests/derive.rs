//! `varmass derive`: the whole derivation of the paper's sled (`models/sled.vms` with its
//! impact), as text and as LaTeX, snapshot-tested.

mod common;

use common::{model, varmass};

fn derive(extra: &[&str]) -> String {
    let file = model("sled.vms");
    let args = [&["derive", file.as_str(), "--with", "impact"][..], extra].concat();
    varmass(&args, 0).0
}

#[test]
fn the_sled_derivation_as_text() {
    insta::assert_snapshot!(derive(&[]));
}

#[test]
fn the_sled_derivation_as_latex() {
    insta::assert_snapshot!(derive(&["--latex"]));
}
