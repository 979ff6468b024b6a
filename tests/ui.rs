//! One compile-fail case per diagnostic (trybuild): the list of files under `tests/ui/` is
//! the list of errors a user can meet, and each `.stderr` is what they read.

use std::fs;
use std::path::Path;

#[test]
fn ui() {
    place_model_files();
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/dsl/*.rs");
    cases.compile_fail("tests/ui/struct/*.rs");
    cases.compile_fail("tests/ui/units/*.rs");
    cases.compile_fail("tests/ui/models/*.rs");
}

/// trybuild compiles the cases as a crate of its own, `<target dir>/tests/trybuild/varmass`,
/// and the macro reads `file = "…"` relative to that crate's directory (its
/// `CARGO_MANIFEST_DIR`). Copying the model files there lets a case name a model as a user's
/// crate does (`models/rocket.vms`), wherever the target directory is: a path counted up
/// from trybuild's crate to the repository holds only for `target/` inside it.
/// `CARGO_TARGET_TMPDIR` is `<target dir>/tmp`, the target directory trybuild takes from
/// `cargo metadata`.
fn place_model_files() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let target = tmp
        .parent()
        .expect("CARGO_TARGET_TMPDIR is inside the target directory");
    let project = target.join("tests/trybuild").join(env!("CARGO_PKG_NAME"));
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for folder in ["models", "models/motors", "tests/ui/models"] {
        let destination = project.join(folder);
        fs::create_dir_all(&destination).expect("creates the model folder");
        for entry in fs::read_dir(root.join(folder)).expect("lists the model folder") {
            let path = entry.expect("reads the model folder").path();
            // Models, and the table files they read.
            let copied = ["vms", "eng", "csv"];
            if path
                .extension()
                .is_some_and(|e| copied.iter().any(|c| e == *c))
            {
                let name = path.file_name().expect("a file has a name");
                fs::copy(&path, destination.join(name)).expect("copies a model file");
            }
        }
    }
}
