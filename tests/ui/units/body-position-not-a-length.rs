use varmass::prelude::*;

#[variable_mass_system("
coordinates th
units th: rad, m0: kg, l: m
mass m = m0
body bob: mass m, position [l*sin(th), -th]
")]
struct Pendulum {
    m0: f64,
    l: f64,
}

fn main() {}
