use varmass::prelude::*;

#[variable_mass_system("
coordinates x
units x: m, m0: kg
mass m = m0
body cart: mass m, position [x]
check p_x = m*x'^2
")]
struct Cart {
    m0: f64,
}

fn main() {}
