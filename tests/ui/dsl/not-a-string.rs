use varmass::prelude::*;

#[variable_mass_system(coordinates x)]
struct Free {
    k: f64,
}

fn main() {}
