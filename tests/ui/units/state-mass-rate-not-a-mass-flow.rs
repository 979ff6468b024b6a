use varmass::prelude::*;

#[variable_mass_system("
coordinates y
units y: m, mu: kg/s, g: m/s^2
mass m: state, rate -mu*g
body rocket: mass m, position [y]
outflow rocket
")]
struct Rocket {
    mu: f64,
    g: f64,
}

fn main() {}
