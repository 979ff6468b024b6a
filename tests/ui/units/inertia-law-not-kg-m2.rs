use varmass::prelude::*;

#[variable_mass_system("
coordinates th
units th: rad, J0: kg*m
inertia J = J0
kinetic 1/2*J*th'^2
")]
struct Wheel {
    J0: f64,
}

fn main() {}
