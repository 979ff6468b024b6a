use varmass::prelude::*;

#[variable_mass_system("
coordinates y
mass m = m_p + m_d*(1 + sign(t_b - t))/2 - mu*t
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: velocity [-u_e]
")]
struct Staged {
    m_p: f64,
    m_d: f64,
    t_b: f64,
    mu: f64,
    g: f64,
    u_e: f64,
}

fn main() {}
