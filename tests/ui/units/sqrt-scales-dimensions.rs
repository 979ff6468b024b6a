use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, k: N/m
mass m = m0
body cart: mass m, position [x]
potential k*sqrt(x)
")]
struct Cart {
    m0: f64,
    k: f64,
}

fn main() {}
