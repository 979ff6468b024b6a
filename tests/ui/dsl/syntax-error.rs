use varmass::prelude::*;

#[variable_mass_system("
coordinates x
mass m = m0 + * x
kinetic 1/2*m*x'^2
")]
struct Sled {
    m0: f64,
}

fn main() {}
