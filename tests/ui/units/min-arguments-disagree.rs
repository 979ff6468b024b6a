use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, g: m/s^2, h: m
mass m = m0
body ball: mass m, position [x]
potential m*g*min(x, h*x')
")]
struct Ball {
    m0: f64,
    g: f64,
    h: f64,
}

fn main() {}
