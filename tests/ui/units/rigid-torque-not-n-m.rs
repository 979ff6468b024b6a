// A torque is N·m: a force (N) written as a torque is refused at its component.
use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y, z, psi, th, phi
units x: m, y: m, z: m, psi: rad, th: rad, phi: rad, m0: kg, A: kg*m^2, C: kg*m^2, F: N
mass m = m0
inertia Ia = A
inertia Ic = C
rigid craft: mass m, inertia [Ia, Ia, Ic], position [x, y, z], orientation zyx(psi, th, phi)
torque craft: body [0, 0, F]
")]
struct Craft {
    m0: f64,
    A: f64,
    C: f64,
    F: f64,
}

fn main() {}
