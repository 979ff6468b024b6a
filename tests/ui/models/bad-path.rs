use varmass::prelude::*;

#[variable_mass_system(file = "models/no-such-model.vms")]
struct Missing {
    k: f64,
}

fn main() {}
