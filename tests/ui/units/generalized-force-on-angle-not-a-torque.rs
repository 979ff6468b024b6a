use varmass::prelude::*;

#[variable_mass_system("
coordinates th
units th: rad, I0: kg*m^2, F: N
inertia J = I0
kinetic 1/2*J*th'^2
force th: -F
")]
struct Wheel {
    I0: f64,
    F: f64,
}

fn main() {}
