use varmass::prelude::*;

#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
lagrangian a*x'^4
")]
struct Stiff {
    k: f64,
    a: f64,
}

fn main() {}
