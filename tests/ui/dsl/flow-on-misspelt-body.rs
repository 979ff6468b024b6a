use varmass::prelude::*;

#[variable_mass_system("
coordinates y
mass m: state, rate -mu
body bucket: mass m, position [y]
potential m*g*y
outflow buckt: rate mu
")]
struct Bucket {
    mu: f64,
    g: f64,
}

fn main() {}
