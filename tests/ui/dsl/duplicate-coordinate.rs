use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y, x
kinetic 1/2*k*(x'^2 + y'^2)
")]
struct Plane {
    k: f64,
}

fn main() {}
