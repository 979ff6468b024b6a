use varmass::prelude::*;

// A table file that does not exist: read relative to the crate's directory for an inline
// system.
#[variable_mass_system("
coordinates y
table F(t) = \"motors/no-such-motor.eng\", outside zero
kinetic 1/2*m*y'^2
force y: F(t)
")]
struct Rocket {
    m: f64,
}

fn main() {}
