use varmass::prelude::*;

#[variable_mass_system("
coordinates y
units y: m, mu: kg/s, u_e: m/s
mass m: state, rate -mu
body rocket: mass m, position [y]
outflow rocket: rate mu*u_e, relative_velocity [-u_e]
")]
struct Rocket {
    mu: f64,
    u_e: f64,
}

fn main() {}
