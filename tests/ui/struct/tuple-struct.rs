use varmass::prelude::*;

#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
")]
struct Free(f64);

fn main() {}
