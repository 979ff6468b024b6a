use varmass::prelude::*;

#[variable_mass_system("
coordinates type
kinetic 1/2*k*type'^2
")]
struct Free {
    k: f64,
}

fn main() {}
