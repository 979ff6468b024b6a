use varmass::prelude::*;

#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
")]
struct Free<T> {
    k: f64,
    marker: T,
}

fn main() {}
