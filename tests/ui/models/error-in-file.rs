use varmass::prelude::*;

// trybuild builds the cases as a crate in target/tests/trybuild/varmass, whose
// CARGO_MANIFEST_DIR is that folder: the repository's root is four levels up.

#[variable_mass_system(file = "../../../../tests/ui/models/error-in-file.vms")]
struct Sled {
    m0: f64,
    c: f64,
}

fn main() {}
