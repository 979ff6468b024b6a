use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg, g: m/s^2, theta: rad
mass m = m0
body sled: mass m, position [x]
potential -m*g*x*sin(theta) + m*g*x'*sin(theta)
")]
struct Sled {
    m0: f64,
    g: f64,
    theta: f64,
}

fn main() {}
