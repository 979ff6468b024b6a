use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, k: N/m, w: 1/s
mass m = m0
let w = sqrt(k)
body cart: mass m, position [x]
potential 1/2*m*w^2*x^2
")]
struct Oscillator {
    m0: f64,
    k: f64,
}

fn main() {}
