use varmass::prelude::*;

#[variable_mass_system("
coordinates x, th
units x: m, m0: kg
mass m = m0
body sled: mass m, position [x]
potential -m*g*x*sin(th)
")]
struct Sled {
    m0: f64,
    g: f64,
}

fn main() {}
