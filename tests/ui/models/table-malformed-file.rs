use varmass::prelude::*;

// A malformed table file: the diagnostic names the file's line and column.
#[variable_mass_system("
coordinates y
table F(t) = \"tests/ui/models/bad-table.csv\"
kinetic 1/2*m*y'^2
force y: F(t)
")]
struct Rocket {
    m: f64,
}

fn main() {}
