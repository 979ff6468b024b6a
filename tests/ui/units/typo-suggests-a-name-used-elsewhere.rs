use varmass::prelude::*;

// `muu` is a typo of `mu`, which has a unit and is used by the mass's rate: the caret is
// on `muu` where it is written, and the help suggests `mu`.
#[variable_mass_system("
coordinates y
units y: m, mu: kg/s, u_e: m/s, g: m/s^2
mass m: state, rate -mu
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate muu, relative_velocity [-u_e]
")]
struct Rocket {
    mu: f64,
    muu: f64,
    u_e: f64,
    g: f64,
}

fn main() {}
