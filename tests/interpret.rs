//! The run-time system (`varmass::interpret::TapeSystem`) against the macro's generated code
//! for the same model: every trait method at pseudo-random states agrees to rounding.
//! Generated code is an independent evaluation (emitted Rust with its own CSE and staging),
//! so agreement checks the tapes, the loading of the environment and the Cholesky path.

use proptest::prelude::*;
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::{derive_source, mechanics::Parameters};

/// The paper's sled: a mass law m(x).
#[variable_mass_system(
    "
    coordinates x
    mass m = m0 + c*x
    body sled: mass m, position [x]
    potential -m*g*x*sin(theta)
    force sled: [-f_d*m*g*cos(theta)]
    inflow sled: velocity [0]
"
)]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

/// A leaking spring pendulum: two coordinates and a state mass.
#[variable_mass_system(
    "
    coordinates r, th
    mass m: state, rate -mu
    body bob: mass m, position [r*sin(th), -r*cos(th)]
    potential 1/2*k*(r - l0)^2 - m*g*r*cos(th)
    outflow bob: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]
"
)]
struct Pendulum {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

/// A leaking spherical spring pendulum: three coordinates, so q̇ comes from a numerical
/// Cholesky solve in both implementations.
#[variable_mass_system(
    "
    coordinates r, th, ph
    mass m: state, rate -mu
    body bob: mass m, position [r*sin(th)*cos(ph), r*sin(th)*sin(ph), -r*cos(th)]
    potential 1/2*k*(r - l0)^2 - m*g*r*cos(th)
    outflow bob: rate mu, relative_velocity [0, -u_e*sin(th), u_e*cos(th)]
"
)]
struct Spherical {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

/// Largest |a − b| / max(|a|, |b|, 1) over two slices.
fn relative_gap(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(1.0))
        .fold(0.0, f64::max)
}

/// Measured: at most 2.0e-15 (the state rate) over these models and states; bound 1e-12 (rounding of
/// differently ordered but equal formulas, with margin).
const BOUND: f64 = 1e-12;

/// Compares every method of the two systems at `(t, state)`; `state` is `[q, p, m_s]`.
fn compare<G, const N: usize, const S: usize>(
    generated: &G,
    tape: &TapeSystem<N, S>,
    t: f64,
    state: SVector<f64, S>,
) where
    G: VariableMassSystem<N, S>,
{
    let vs = generated.velocity_state(t, &state).expect("generated q̇");
    let vt = tape.velocity_state(t, &state).expect("tape q̇");
    let gap = |what: &str, a: &[f64], b: &[f64]| {
        let gap = relative_gap(a, b);
        assert!(gap < BOUND, "{what}: {a:?} vs {b:?} (gap {gap:e})");
    };
    gap("q̇", vs.as_slice(), vt.as_slice());
    for index in 0..G::MASSES.len() {
        gap(
            "m",
            &[generated.mass(index, t, &state)],
            &[tape.mass(index, t, &state)],
        );
        gap(
            "ṁ",
            &[generated.mass_rate(index, t, &vs)],
            &[tape.mass_rate(index, t, &vs)],
        );
    }
    gap(
        "M",
        generated.mass_matrix(t, &state).as_slice(),
        tape.mass_matrix(t, &state).as_slice(),
    );
    gap(
        "p",
        generated.momenta(t, &vs).as_slice(),
        tape.momenta(t, &vs).as_slice(),
    );
    gap(
        "L",
        &[generated.lagrangian(t, &vs)],
        &[tape.lagrangian(t, &vs)],
    );
    gap(
        "∂*L/∂q",
        generated.lagrangian_gradient(t, &vs).as_slice(),
        tape.lagrangian_gradient(t, &vs).as_slice(),
    );
    gap(
        "Q*",
        generated.active_force(t, &vs).as_slice(),
        tape.active_force(t, &vs).as_slice(),
    );
    gap(
        "R1",
        generated.reactive_thrust(t, &vs).as_slice(),
        tape.reactive_thrust(t, &vs).as_slice(),
    );
    gap(
        "R2",
        generated.impact_force(t, &vs).as_slice(),
        tape.impact_force(t, &vs).as_slice(),
    );
    gap(
        "flux",
        generated.mass_flux_force(t, &vs).as_slice(),
        tape.mass_flux_force(t, &vs).as_slice(),
    );
    let qdd = generated.accelerations(t, &vs).expect("generated q̈");
    gap(
        "q̈",
        qdd.as_slice(),
        tape.accelerations(t, &vs).expect("tape q̈").as_slice(),
    );
    gap(
        "H",
        &[generated.hamiltonian(t, &state).unwrap()],
        &[tape.hamiltonian(t, &state).unwrap()],
    );
    gap(
        "power",
        &[generated.power(t, &state).unwrap()],
        &[tape.power(t, &state).unwrap()],
    );
    let rate = generated.state_rate(t, &state).unwrap();
    gap(
        "state rate",
        rate.as_slice(),
        tape.state_rate(t, &state).unwrap().as_slice(),
    );
    assert!(generated.check_masses(t, &state).is_ok() && tape.check_masses(t, &state).is_ok());
}

fn tape_system<const N: usize, const S: usize>(
    source: &str,
    parameters: &[(&str, f64)],
) -> TapeSystem<N, S> {
    let derivation = derive_source(source, Parameters::Inferred).expect("derives");
    TapeSystem::new(Program::new(derivation, parameters).expect("parameters fit"))
        .expect("sizes fit")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn sled_agrees(x in 0.0..60.0f64, p in -50.0..200.0f64, t in 0.0..10.0f64) {
        let sled = Sled { m0: 10.0, c: 2.0, g: 9.81, theta: 0.5, f_d: 0.1 };
        let tape = tape_system::<1, 2>(Sled::SOURCE, &[("m0", 10.0), ("c", 2.0), ("g", 9.81), ("theta", 0.5), ("f_d", 0.1)]);
        compare(&sled, &tape, t, SVector::<f64, 2>::new(x, p));
    }

    #[test]
    fn pendulum_agrees(r in 0.5..2.0f64, th in -3.0..3.0f64, pr in -5.0..5.0f64, pth in -5.0..5.0f64, m in 0.2..2.0f64) {
        let pendulum = Pendulum { mu: 0.1, u_e: 3.0, k: 40.0, l0: 1.0, g: 9.81 };
        let tape = tape_system::<2, 5>(Pendulum::SOURCE, &[("mu", 0.1), ("u_e", 3.0), ("k", 40.0), ("l0", 1.0), ("g", 9.81)]);
        compare(&pendulum, &tape, 0.3, SVector::<f64, 5>::from_column_slice(&[r, th, pr, pth, m]));
    }

    #[test]
    fn spherical_agrees(r in 0.5..2.0f64, th in 0.2..2.9f64, ph in -3.0..3.0f64, p in prop::array::uniform3(-5.0..5.0f64), m in 0.2..2.0f64) {
        let spherical = Spherical { mu: 0.1, u_e: 3.0, k: 40.0, l0: 1.0, g: 9.81 };
        let tape = tape_system::<3, 7>(Spherical::SOURCE, &[("mu", 0.1), ("u_e", 3.0), ("k", 40.0), ("l0", 1.0), ("g", 9.81)]);
        compare(&spherical, &tape, 0.0, SVector::<f64, 7>::from_column_slice(&[r, th, ph, p[0], p[1], p[2], m]));
    }
}

#[test]
fn a_parameter_list_that_does_not_fit_is_a_typed_error() {
    use varmass::interpret::ProgramError;
    let derivation = || derive_source(Sled::SOURCE, Parameters::Inferred).expect("derives");
    let all = [
        ("m0", 10.0),
        ("c", 2.0),
        ("g", 9.81),
        ("theta", 0.5),
        ("f_d", 0.1),
    ];
    let typo = [
        ("m0", 10.0),
        ("c", 2.0),
        ("g", 9.81),
        ("theta", 0.5),
        ("f_e", 0.1),
    ];
    match Program::new(derivation(), &typo) {
        Err(ProgramError::UnknownParameter {
            name, suggestion, ..
        }) => {
            assert_eq!((name.as_str(), suggestion.as_deref()), ("f_e", Some("f_d")));
        }
        other => panic!("expected an unknown parameter, got {other:?}"),
    }
    match Program::new(derivation(), &all[..4]) {
        Err(ProgramError::MissingParameters { missing, .. }) => assert_eq!(missing, ["f_d"]),
        other => panic!("expected a missing parameter, got {other:?}"),
    }
    let program = Program::new(derivation(), &all).expect("fits");
    match TapeSystem::<2, 5>::new(program) {
        Err(ProgramError::WrongSize {
            coordinates: 1,
            state_masses: 0,
            n: 2,
            s: 5,
        }) => {}
        other => panic!("expected a size mismatch, got {other:?}"),
    }
}

#[test]
fn a_singular_mass_matrix_and_a_spent_mass_are_typed_errors() {
    let tape = tape_system::<2, 5>(
        Pendulum::SOURCE,
        &[
            ("mu", 0.1),
            ("u_e", 3.0),
            ("k", 40.0),
            ("l0", 1.0),
            ("g", 9.81),
        ],
    );
    // r = 0: the θ row of M = diag(m, m r²) vanishes.
    let at_pivot = SVector::<f64, 5>::from_column_slice(&[0.0, 0.3, 1.0, 1.0, 1.0]);
    assert_eq!(
        tape.state_rate(0.0, &at_pivot),
        Err(SystemError::SingularMassMatrix)
    );
    let spent = SVector::<f64, 5>::from_column_slice(&[1.0, 0.3, 1.0, 1.0, 0.0]);
    assert_eq!(
        tape.check_masses(0.0, &spent),
        Err(SystemError::NonPositiveMass { index: 0 })
    );
}
