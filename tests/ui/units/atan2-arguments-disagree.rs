use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y
units x: m, y: m, m0: kg, E: J
mass m = m0
body ball: mass m, position [x, y]
potential E*atan2(y, x')
")]
struct Ball {
    m0: f64,
    E: f64,
}

fn main() {}
