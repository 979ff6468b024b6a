use varmass::prelude::*;

// The paper's eq. 19 taken literally would give −2c ẋ²; the derivation does not.
#[variable_mass_system("
coordinates x
mass m = m0 + c*x
body sled: mass m, position [x]
potential -m*g*x*sin(theta)
inflow sled: velocity [0]
check x'' = g*sin(theta) - 2*c*x'^2/m
")]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
}

fn main() {}
