use varmass::prelude::*;

// `g` is used by the DSL but is not a field.
#[variable_mass_system("
coordinates y
mass m = m0
body ball: mass m, position [y]
potential m*g*y
")]
struct Ball {
    m0: f64,
}

fn main() {}
