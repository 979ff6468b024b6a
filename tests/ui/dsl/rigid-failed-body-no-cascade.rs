// A `rigid` statement with two mistakes reports both, and the loads and flows on its body
// are not reported again as naming no body.
use varmass::prelude::*;

#[variable_mass_system("
coordinates x, y, th
mass m = m0
inertia J = m*k^2
rigid rocket: mass m, inertia [J, J, J], position [x, y], angle th, centre [0, 0, c]
force rocket: body [0, F] at [0, -l]
torque rocket: tau
outflow rocket: rate mu, at [0, -l], relative_velocity body [0, -u_e]
")]
struct Rocket {
    m0: f64,
    k: f64,
    c: f64,
    F: f64,
    l: f64,
    tau: f64,
    mu: f64,
    u_e: f64,
}

fn main() {}
