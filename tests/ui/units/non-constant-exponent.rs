use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, k: N/m, n: 1
mass m = m0
body cart: mass m, position [x]
potential k*x^n
")]
struct Cart {
    m0: f64,
    k: f64,
    n: f64,
}

fn main() {}
