use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y
kinetic 1/2*k*x'^2
potential 1/2*k*y^2
")]
struct Idle {
    k: f64,
}

fn main() {}
