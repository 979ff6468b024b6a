// `angle` turns a body in the plane: a position of three components needs `orientation`.
use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y, z, th
mass m = m0
rigid body: mass m, inertia J, position [x, y, z], angle th
")]
struct Body {
    m0: f64,
    J: f64,
}

fn main() {}
