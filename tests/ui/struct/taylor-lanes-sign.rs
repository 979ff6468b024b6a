use varmass::prelude::*;

// Taylor's method in lanes (`emit = ["taylor", "lanes"]`) has no lane form for `sign` (its
// runtime function is scalar): the macro refuses it naming the reason, rather than
// expanding some lanes on another lane's branch.
#[variable_mass_system(
    "
coordinates x
mass m = m0
body b: mass m, position [x]
potential k*x^2/2
force b: [-f*sign(x')]
",
    emit = ["taylor", "lanes"]
)]
struct Block {
    m0: f64,
    k: f64,
    f: f64,
}

fn main() {}
