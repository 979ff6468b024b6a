use varmass::prelude::*;

// Two interpolations for one table: the second is the error.
#[variable_mass_system("
coordinates y
table F(t) = \"motors/Cesaroni_M1670.eng\", pchip, spline
kinetic 1/2*m*y'^2
force y: F(t)
")]
struct Rocket {
    m: f64,
}

fn main() {}
