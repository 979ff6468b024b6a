use varmass::prelude::*;

// The Taylor stepper's double-double head has no form for `sin` yet: the macro refuses
// `emit = ["taylor", "head"]` naming it, rather than evaluating it in double.
#[variable_mass_system(
    "
coordinates th
mass m = m1
body bob: mass m, position [l*sin(th), -l*cos(th)]
potential -m*g*l*cos(th)
",
    emit = ["taylor", "head"]
)]
struct Pendulum {
    m1: f64,
    g: f64,
    l: f64,
}

fn main() {}
