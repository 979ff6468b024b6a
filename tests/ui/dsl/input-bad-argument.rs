use varmass::prelude::*;

// An input's arguments are `t`, coordinates and their velocities; a call has as many
// arguments as the declaration.
#[variable_mass_system("
coordinates y
input u(t, z, y')
mass m = m0
body rocket: mass m, position [y]
force y: u(t, y)
")]
struct Hover {
    m0: f64,
}

fn main() {}
