use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg
mass m = m0
kinetic 1/2*m*x'
")]
struct Cart {
    m0: f64,
}

fn main() {}
