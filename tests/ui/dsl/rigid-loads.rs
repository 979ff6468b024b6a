// Loads that do not fit their body: a point of application on a particle, a body-frame
// vector of the wrong length, a torque of the wrong shape for the body, a torque on a
// particle.
use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y, th, u, v
mass m = m0
mass w = w0
rigid rocket: mass m, inertia J, position [x, y], angle th
body ball: mass w, position [u, v]
force ball: [0, F] at [0, 1]
force rocket: body [0, 0, F]
torque rocket: [0, 0, tau]
torque ball: tau
")]
struct Loads {
    m0: f64,
    w0: f64,
    J: f64,
    F: f64,
    tau: f64,
}

fn main() {}
