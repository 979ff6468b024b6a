use varmass::prelude::*;

#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
")]
struct Free {
    k: f64,
    damping: f64,
}

fn main() {}
