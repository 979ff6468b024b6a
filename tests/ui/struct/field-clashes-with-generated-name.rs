use varmass::prelude::*;

// Generated code names the velocity of `x` `x_dot`; a parameter of that name would be shadowed.
#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
force x: -x_dot*x'
")]
struct Damped {
    k: f64,
    x_dot: f64,
}

fn main() {}
