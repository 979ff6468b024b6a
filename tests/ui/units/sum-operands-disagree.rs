use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, k: N/m, l0: m
mass m = m0
body cart: mass m, position [x]
potential 1/2*k*(x - l0*x')^2
")]
struct Spring {
    m0: f64,
    k: f64,
    l0: f64,
}

fn main() {}
