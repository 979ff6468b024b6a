use varmass::prelude::*;

#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
force x: -b*x''
")]
struct Damped {
    k: f64,
    b: f64,
}

fn main() {}
