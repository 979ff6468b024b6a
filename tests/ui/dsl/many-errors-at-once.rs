use varmass::prelude::*;

#[variable_mass_system("
coordinates x, x
mass m = m0
body b: mass q, position [x]
force zz: 1
")]
struct Broken {
    m0: f64,
}

fn main() {}
