use varmass::prelude::*;

// The `units` statement misspells `theta`: the caret is on `theta` where it is used, and
// the help reads the right way round (fix `thetta` in `units`).
#[variable_mass_system("
coordinates x
units x: m, m: kg, k: N/m, thetta: rad
kinetic 1/2*m*x'^2
potential 1/2*k*x^2*cos(theta)
")]
struct Slope {
    m: f64,
    k: f64,
    theta: f64,
}

fn main() {}
