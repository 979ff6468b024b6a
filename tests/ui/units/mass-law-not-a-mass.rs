use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, c: kg*s/m
mass m = m0 + c*x
body sled: mass m, position [x]
")]
struct Sled {
    m0: f64,
    c: f64,
}

fn main() {}
