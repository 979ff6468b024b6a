use varmass::prelude::*;

// `input u(..)` makes the macro emit the trait `HoverInputs`, which the struct must
// implement: without it, the generated equations cannot call `u`.
#[variable_mass_system("
coordinates y
input u(t, y, y')
mass m = m0
body rocket: mass m, position [y]
potential m*g*y
force y: m*u(t, y, y')
")]
struct Hover {
    m0: f64,
    g: f64,
}

fn main() {}
