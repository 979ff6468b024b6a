use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket.vms", whith = ["drag"])]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

fn main() {}
