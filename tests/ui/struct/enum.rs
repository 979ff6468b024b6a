use varmass::prelude::*;

#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
")]
enum Free {
    A,
}

fn main() {}
