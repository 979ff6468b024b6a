// A misspelt Euler sequence names the twelve and the closest.
use varmass::prelude::*;

#[variable_mass_system("
coordinates psi, th, phi
mass m = m0
rigid craft: mass m, inertia [A, B, C], position [0, 0, 0], orientation zxy2(psi, th, phi)
")]
struct Craft {
    m0: f64,
    A: f64,
    B: f64,
    C: f64,
}

fn main() {}
