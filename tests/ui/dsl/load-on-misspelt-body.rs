use varmass::prelude::*;

#[variable_mass_system("
coordinates y
mass m = m0
body bucket: mass m, position [y]
potential m*g*y
force bukcet: [-k*y']
")]
struct Bucket {
    m0: f64,
    g: f64,
    k: f64,
}

fn main() {}
