use varmass::prelude::*;

// trybuild builds the cases as a crate in target/tests/trybuild/varmass, whose
// CARGO_MANIFEST_DIR is that folder: the repository's root is four levels up.

#[variable_mass_system(file = "../../../../models/rocket.vms", whith = ["drag"])]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

fn main() {}
