use varmass::prelude::*;

#[variable_mass_system("
coordinates y
units y: m, mu: kg/s, u_e: m
mass m: state, rate -mu
body rocket: mass m, position [y]
outflow rocket: rate mu, relative_velocity [-u_e]
")]
struct Rocket {
    mu: f64,
    u_e: f64,
}

fn main() {}
