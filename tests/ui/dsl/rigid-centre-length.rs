// A centre of mass offset has as many components as the body's position.
use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y, z, psi, th, phi
mass m = m0
rigid craft: mass m, inertia [A, A, C], position [x, y, z], orientation zyx(psi, th, phi), centre [0, c]
")]
struct Craft {
    m0: f64,
    A: f64,
    C: f64,
    c: f64,
}

fn main() {}
