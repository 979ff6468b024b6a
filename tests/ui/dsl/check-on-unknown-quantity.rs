use varmass::prelude::*;

#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
check p_y = k*x'
")]
struct Free {
    k: f64,
}

fn main() {}
