use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, g: m/s^2, f_d: m
mass m = m0
body sled: mass m, position [x]
force sled: [-f_d*m*g]
")]
struct Sled {
    m0: f64,
    g: f64,
    f_d: f64,
}

fn main() {}
