use varmass::prelude::*;

#[variable_mass_system("
coordinates x
mass m = m0 + c*x
body sled: mass m, position [x]
inflow sled: rate 2*c*x', velocity [0]
")]
struct Sled {
    m0: f64,
    c: f64,
}

fn main() {}
