use varmass::prelude::*;

#[variable_mass_system(file = "tests/ui/models/error-in-file.vms")]
struct Sled {
    m0: f64,
    c: f64,
}

fn main() {}
