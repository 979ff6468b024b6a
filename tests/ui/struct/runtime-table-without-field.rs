use varmass::prelude::*;

#[variable_mass_system("
coordinates y
table F(t) = runtime, outside zero
mass m = m0
kinetic 1/2*m*y'^2
force y: F(t)
")]
struct Pushed {
    m0: f64,
}

fn main() {}
