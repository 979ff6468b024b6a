use varmass::prelude::*;

#[variable_mass_system("
coordinates x
mass m = m0
kinetic 1/2*m*x'^2
[friction] force x: -f*x'
", with = ["frction"])]
struct Block {
    m0: f64,
}

fn main() {}
