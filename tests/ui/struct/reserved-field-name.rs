use varmass::prelude::*;

// `t` is the time in the DSL; a field of that name would silently replace it.
#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2
force x: sin(w*t)
")]
struct Driven {
    k: f64,
    w: f64,
    t: f64,
}

fn main() {}
