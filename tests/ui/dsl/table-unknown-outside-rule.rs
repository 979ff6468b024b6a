use varmass::prelude::*;

// A misspelt rule after `outside`: "did you mean `zero`?".
#[variable_mass_system("
coordinates y
table F(t) = \"motors/Cesaroni_M1670.eng\", outside zeros
kinetic 1/2*m*y'^2
force y: F(t)
")]
struct Rocket {
    m: f64,
}

fn main() {}
