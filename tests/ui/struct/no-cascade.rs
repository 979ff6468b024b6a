use varmass::prelude::*;

// One DSL error; the use of the system below must not add "trait not implemented" errors.
#[variable_mass_system("
coordinates x
kinetic 1/2*k*x'^2 +
")]
struct Free {
    k: f64,
}

fn main() {
    let system = Free { k: 1.0 };
    let _ = <Free as VariableMassSystem<1, 2>>::COORDINATES;
    let _ = system.k;
}
