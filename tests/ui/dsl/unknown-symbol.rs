use varmass::prelude::*;

#[variable_mass_system("
coordinates x
mass m = mm + c*x
body sled: mass m, position [x]
")]
struct Sled {
    m0: f64,
    c: f64,
}

fn main() {}
