//! Tables in generated code and in the interpreter (docs/tables.md): a rocket on the M1670's
//! thrust table of t with quadratic drag through a `pchip` density table of the state, the
//! macro's code against `TapeSystem` over the same model at pseudo-random states (state
//! rate, stop times), and the generated Jacobian, which differentiates the density table
//! through its derivative table, against the table's slope by hand.

use proptest::prelude::*;
use std::path::Path;
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::parse::parse_system;
use varmass::symbolic::{
    derive_in,
    mechanics::{Outputs, Parameters},
};
use varmass_table::{CsvTable, Cursor, Interpolation, Outside, Table};

#[variable_mass_system(
    r#"
    coordinates y
    table F(t) = "models/motors/Cesaroni_M1670.eng", outside zero
    table rho(y) = "models/atmosphere/density.csv", pchip, outside hold
    mass m: state, rate -F(t)/u_e
    body rocket: mass m, position [y]
    potential m*g*y
    outflow rocket: rate F(t)/u_e, relative_velocity [-u_e]
    force rocket: [-k*rho(y)*y'*abs(y')]
"#
)]
struct DragRocket {
    u_e: f64,
    g: f64,
    k: f64,
}

const ROCKET: DragRocket = DragRocket {
    u_e: 1152.0,
    g: 9.80665,
    k: 0.004,
};

fn tape() -> TapeSystem<1, 3> {
    let ast = parse_system(DragRocket::SOURCE).unwrap();
    let base = Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = derive_in(&ast, Parameters::Inferred, Outputs::FULL, base).unwrap();
    let parameters = [("u_e", ROCKET.u_e), ("g", ROCKET.g), ("k", ROCKET.k)];
    TapeSystem::new(Program::new(d, &parameters).unwrap()).unwrap()
}

/// Largest |a − b| / max(|a|, |b|, 1).
fn relative_gap(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(1.0))
        .fold(0.0, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Measured ≤ 6.0e-16 relative over 64 states; bound 1e-12 as tests/interpret.rs.
    #[test]
    fn generated_and_interpreted_agree(
        t in 0.0..6.0f64,
        y in 0.0..20_000.0f64,
        p in 100.0..5_000.0f64,
        m in 10.0..20.0f64,
    ) {
        let tape = tape();
        let state = SVector::<f64, 3>::new(y, p, m);
        let generated = ROCKET.state_rate(t, &state).unwrap();
        let interpreted = tape.state_rate(t, &state).unwrap();
        let gap = relative_gap(generated.as_slice(), interpreted.as_slice());
        prop_assert!(gap < 1e-12, "{generated:?} vs {interpreted:?}: {gap:e}");
        prop_assert_eq!(ROCKET.next_stop_time(t), tape.next_stop_time(t));
    }

    /// ∂ṗ/∂y holds the derivative table rho'(y). By hand: ṗ = F(t) − m g − k rho(y) v|v| − ṁ v
    /// with v = p/m, of which only the drag depends on y, so ∂ṗ/∂y = −k rho'(y) v|v|, with
    /// rho' the slope of the same pchip table built here from the data (`slope_at`), and
    /// ∂ẏ/∂y = ∂ṁ/∂y = 0. Measured ≤ 2.6e-16 relative over 64 states; bound 1e-12.
    #[test]
    fn the_jacobian_differentiates_the_density_table(
        t in 0.0..6.0f64,
        y in 100.0..20_000.0f64,
        p in 100.0..5_000.0f64,
        m in 10.0..20.0f64,
    ) {
        let state = SVector::<f64, 3>::new(y, p, m);
        let jacobian = ROCKET.jacobian(t, &state).unwrap();
        let v = p / m;
        let expected = -ROCKET.k * density().slope_at(y, &mut Cursor::default()).unwrap() * v * v.abs();
        let gap = (jacobian[(1, 0)] - expected).abs() / expected.abs();
        prop_assert!(gap < 1e-12, "{} vs {expected}: {gap:e}", jacobian[(1, 0)]);
        prop_assert_eq!(jacobian[(0, 0)], 0.0);
        prop_assert_eq!(jacobian[(2, 0)], 0.0);
    }
}

/// The density table as the model reads it: pchip, held outside.
fn density() -> Table {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/models/atmosphere/density.csv");
    let data = CsvTable::parse(&std::fs::read_to_string(path).unwrap()).unwrap();
    Table::new(&data.points, Interpolation::Pchip, Outside::Hold)
}

/// Derives `source` with files relative to the workspace.
fn program(
    source: &str,
    parameters: &[(&str, f64)],
) -> Result<Program, varmass::interpret::ProgramError> {
    let ast = parse_system(source).unwrap();
    let base = Path::new(env!("CARGO_MANIFEST_DIR"));
    let d = derive_in(&ast, Parameters::Inferred, Outputs::FULL, base).unwrap();
    Program::new(d, parameters)
}

/// `Program::accelerations` reports a lookup outside the data as the table's typed error
/// (below the atmosphere's first altitude, 0 m), not as the singular mass matrix its NaN
/// made of the solve before.
#[test]
fn accelerations_outside_a_table_name_it() {
    let source = "coordinates y\ntable rho(y) = \"models/atmosphere/density.csv\", pchip\n\
                  mass m = m0\nbody b: mass m, position [y]\nforce b: [-k*rho(y)*y']";
    let p = program(source, &[("m0", 1.0), ("k", 0.1)]).unwrap();
    let mut out = [f64::NAN];
    assert_eq!(
        p.accelerations(0.0, &[-100.0, 1.0], &mut out),
        Err(varmass::core::SystemError::TableOutside {
            table: "rho",
            argument: -100.0
        })
    );
    // Inside the data it is the force over the mass: q̈ = −k ρ(100) ẏ / m0.
    p.accelerations(0.0, &[100.0, 1.0], &mut out).unwrap();
    assert!(out[0] < 0.0 && out[0].is_finite(), "{out:?}");
}

/// A continuous input has no value in the interpreter without a law: `Program::new`
/// refuses it by name (its calls compiled to NaN before, and every state rate was NaN).
#[test]
fn an_input_without_a_law_is_refused_by_the_program() {
    let source =
        "coordinates y\ninput u(t)\nmass m = m0\nbody b: mass m, position [y]\nforce b: [u(t)]";
    let refused = program(source, &[("m0", 1.0)]).err();
    assert!(
        matches!(&refused, Some(varmass::interpret::ProgramError::InputWithoutLaw { name }) if name == "u"),
        "{refused:?}"
    );
}
