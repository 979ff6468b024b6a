use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, k: N/metre, c: kg/sec
mass m = m0
body cart: mass m, position [x]
potential 1/2*k*x^2
force x: -c*x'^2
")]
struct Cart {
    m0: f64,
    k: f64,
    c: f64,
}

fn main() {}
