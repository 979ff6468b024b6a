use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, g: m/s^2, c: kg
mass m = m0 + c*x
body sled: mass m, position [x]
potential m*g*x + x'
impact x: -c*x'^2
check p_x = m
")]
struct Sled {
    m0: f64,
    g: f64,
    c: f64,
}

fn main() {}
