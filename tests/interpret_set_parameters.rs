//! `Program::set_parameters`: a program compiled once and given new parameter values
//! evaluates exactly as a program made anew with those values (the tapes do not depend on
//! the values; only the parameters' slots, the Taylor environment and the stop times of the
//! tables of t do), and a bad value list is refused with `Program::new`'s errors, leaving
//! the former values in place.

use std::path::Path;

use varmass::interpret::{Program, ProgramError};
use varmass::symbolic::parse::parse_system;
use varmass::symbolic::{
    derive_in,
    mechanics::{Derivation, Outputs, Parameters},
};

/// A leaking rocket on a thrust table of t, lit at t0: a state mass, a table of t whose
/// argument t − t0 is made of a parameter, and parameters in every stage.
const MODEL: &str = r#"
    coordinates y
    table F(t) = "models/motors/Cesaroni_M1670.eng", outside zero
    mass m: state, rate -F(t - t0)/u_e
    body rocket: mass m, position [y]
    potential m*g*y
    outflow rocket: rate F(t - t0)/u_e, relative_velocity [-u_e]
    force rocket: [-k*y'*abs(y')]
"#;

fn derivation() -> Derivation {
    let ast = parse_system(MODEL).expect("parses");
    let base = Path::new(env!("CARGO_MANIFEST_DIR"));
    derive_in(&ast, Parameters::Inferred, Outputs::FULL, base).expect("derives")
}

const FIRST: [(&str, f64); 4] = [("u_e", 1152.0), ("g", 9.80665), ("k", 0.004), ("t0", 0.0)];
const SECOND: [(&str, f64); 4] = [("u_e", 900.0), ("g", 1.62), ("k", 0.01), ("t0", 1.0)];

/// States `[y, p, m]` and times inside the burn of either ignition time.
const POINTS: [(f64, [f64; 3]); 3] = [
    (1.2, [10.0, 500.0, 5.0]),
    (1.7, [250.0, 2000.0, 4.5]),
    (2.9, [900.0, 3000.0, 4.0]),
];

/// The state rate and the Taylor coefficients to order 6 at every point, bit for bit.
fn evaluations(program: &Program) -> Vec<u64> {
    let mut bits = Vec::new();
    for (t, state) in POINTS {
        let mut rate = [0.0; 3];
        program.state_rate(t, &state, &mut rate).expect("a rate");
        let mut taylor = [0.0; 21];
        program
            .taylor(t, &state, 6, &mut taylor)
            .expect("coefficients");
        bits.extend(rate.iter().chain(&taylor).map(|v| v.to_bits()));
    }
    bits
}

#[test]
fn new_values_evaluate_as_a_program_made_anew() {
    let mut reused = Program::new(derivation(), &FIRST).unwrap();
    let first = evaluations(&reused);
    reused.set_parameters(&SECOND).unwrap();
    let fresh = Program::new(derivation(), &SECOND).unwrap();
    assert_eq!(evaluations(&reused), evaluations(&fresh));
    // The values did change what is computed (a test that could not fail otherwise).
    assert_ne!(evaluations(&reused), first);
    for after in [0.5, 1.0, 1.3, 2.0, 3.5] {
        assert_eq!(reused.next_stop_time(after), fresh.next_stop_time(after));
    }
}

/// The knots of F(t − t0) are those of F(t) moved by t0: lighting 1 s later moves every
/// stop time 1 s later (to the rounding of t − t0: bound 1e-12).
#[test]
fn stop_times_follow_the_new_values() {
    let mut program = Program::new(derivation(), &FIRST).unwrap();
    let before: Vec<f64> = [0.0, 0.07, 0.3, 1.2]
        .iter()
        .map(|after| program.next_stop_time(*after).expect("a knot"))
        .collect();
    program.set_parameters(&SECOND).unwrap();
    for (after, knot) in [0.0, 0.07, 0.3, 1.2].iter().zip(before) {
        let moved = program.next_stop_time(after + 1.0).expect("a knot");
        assert!(
            (moved - (knot + 1.0)).abs() < 1e-12,
            "{moved} vs {knot} + 1"
        );
    }
}

#[test]
fn bad_values_are_refused_and_leave_the_former_ones() {
    let mut program = Program::new(derivation(), &FIRST).unwrap();
    let first = evaluations(&program);
    let missing = program.set_parameters(&FIRST[..3]).unwrap_err();
    assert!(
        matches!(&missing, ProgramError::MissingParameters { missing, .. } if missing == &["t0"]),
        "{missing:?}"
    );
    let mut typo = FIRST.to_vec();
    typo.push(("u_f", 1.0));
    let unknown = program.set_parameters(&typo).unwrap_err();
    assert!(
        matches!(&unknown, ProgramError::UnknownParameter { name, suggestion, .. }
            if name == "u_f" && suggestion.as_deref() == Some("u_e")),
        "{unknown:?}"
    );
    let mut infinite = FIRST;
    infinite[1].1 = f64::INFINITY;
    let not_finite = program.set_parameters(&infinite).unwrap_err();
    assert!(
        matches!(&not_finite, ProgramError::NonFiniteParameter { name, .. } if name == "g"),
        "{not_finite:?}"
    );
    assert_eq!(evaluations(&program), first);
}
