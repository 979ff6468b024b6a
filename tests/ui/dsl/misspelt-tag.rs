use varmass::prelude::*;

#[variable_mass_system("
coordinates y
mass m = m0
body rocket: mass m, position [y]
potential m*g*y
[drag] force rocket: [-k_d*y'*abs(y')]
", with = ["darg"])]
struct Rocket {
    m0: f64,
    g: f64,
}

fn main() {}
