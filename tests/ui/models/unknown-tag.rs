use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket.vms", with = ["drag", "wind"])]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
    k_d: f64,
}

fn main() {}
