use varmass::prelude::*;

// A support moved by an input: the Lagrangian's velocity would need ∂u/∂t, a finite
// difference of the user's function, in equations that must be exact.
#[variable_mass_system("
coordinates x
input u(t)
mass m = m0
body bob: mass m, position [x + u(t)]
")]
struct Carried {
    m0: f64,
}

impl CarriedInputs for Carried {
    fn u(&self, t: f64) -> f64 {
        t.sin()
    }
}

fn main() {}
