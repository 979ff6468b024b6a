//! The Taylor stepper across a switch (docs/mechanics.md#switches): `sign`, `abs`, `min` and
//! `max` are expanded on the branch where a step starts, so the series of a step that
//! straddles a switch continues the old branch past it. The run must end each step at the
//! crossing: shown on the rocket whose burn `sign(t_b − t)` switches off inside the run
//! (the case of `tests/switches.rs`), generated (`emit = ["taylor"]`) and interpreted.

use varmass::core::steppers::{Taylor, TaylorControl};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::{derive_source, mechanics::Parameters};

/// The model, one file for the macro and the interpreter.
const SWITCHED_OFF: &str = include_str!("data/switched_off.vms");

#[variable_mass_system(file = "tests/data/switched_off.vms", emit = ["taylor"])]
struct SwitchedOff {
    mu: f64,
    u_e: f64,
    g: f64,
    t_b: f64,
}

const BURN: SwitchedOff = SwitchedOff {
    mu: 10.0,
    u_e: 2500.0,
    g: 9.81,
    t_b: 60.0,
};
const M0: f64 = 1000.0;
const TOLERANCE: f64 = 1e-12;

/// The apex by hand: to t_b, m_b = m0 − μ t_b, v_b = u_e ln(m0/m_b) − g t_b and
/// y_b = u_e (t_b − (m_b/μ) ln(m0/m_b)) − g t_b²/2 (Tsiolkovsky with gravity, integrated);
/// then a coast of v_b/g to y_b + v_b²/(2g): 188 382.9… m at t = 233.5… s.
fn apex_by_hand() -> (f64, f64) {
    let SwitchedOff { mu, u_e, g, t_b } = BURN;
    let m_b = M0 - mu * t_b;
    let ratio = (M0 / m_b).ln();
    let v_b = u_e * ratio - g * t_b;
    let y_b = u_e * (t_b - m_b / mu * ratio) - 0.5 * g * t_b * t_b;
    (t_b + v_b / g, y_b + v_b * v_b / (2.0 * g))
}

/// The relative apex height error and the apex time error of one Taylor run (burn and
/// coast, the apex an event on p = 0 falling).
fn apex_error<Sys: VariableMassSystem<1, 3>>(system: &Sys, config: &RunConfig) -> (f64, f64) {
    let start = SVector::from([0.0, 0.0, M0]);
    let control =
        TaylorControl::adaptive(Tolerance::for_floor(TOLERANCE, TOLERANCE, Floor::Taylor).unwrap());
    let mut stepper = Taylor::new(system, 0.0, start, control).expect("a valid start");
    let apex = Event::state_reaches(1, 0.0, Direction::Falling);
    let solution = run(&mut stepper, config, &[apex]).expect("the flight runs");
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let (time, state) = solution.last().expect("points");
    let (t_apex, y_apex) = apex_by_hand();
    ((state[0] - y_apex).abs() / y_apex, (time - t_apex).abs())
}

/// Measured at tolerance 1e-12: located, the apex height is 2.0e-14 relative off and its
/// time 2.8e-12 s; stepping across the switch, 0.29 (the burn's one or two long steps
/// carry it on to their end). Bounds: 1e-13 (the issue's) and 1e-9 s located; the run
/// across must miss 1e-13.
#[test]
fn the_generated_taylor_rocket_stops_at_the_burnout_and_reaches_the_apex() {
    let (height, time) = apex_error(&BURN, &RunConfig::until(1e4));
    eprintln!("located: apex error {height:e}, time {time:e} s");
    assert!(height <= 1e-13, "{height:e}");
    assert!(time <= 1e-9, "{time:e}");
    let (across, _) = apex_error(&BURN, &RunConfig::until(1e4).without_switching());
    eprintln!("stepping across: apex error {across:e}");
    assert!(across > 1e-13, "stepped across and still hit: {across:e}");
}

/// The same through the run-time tapes (`--method taylor`). Measured the same, 2.0e-14 and
/// 0.29; bounds as above.
#[test]
fn the_interpreted_taylor_rocket_stops_at_the_burnout_as_well() {
    let derivation = derive_source(SWITCHED_OFF, Parameters::Inferred).expect("derives");
    let values = [("mu", 10.0), ("u_e", 2500.0), ("g", 9.81), ("t_b", 60.0)];
    let system = TapeSystem::<1, 3>::new(Program::new(derivation, &values).unwrap()).unwrap();
    let (height, time) = apex_error(&system, &RunConfig::until(1e4));
    eprintln!("interpreted, located: apex error {height:e}, time {time:e} s");
    assert!(height <= 1e-13, "{height:e}");
    assert!(time <= 1e-9, "{time:e}");
    let (across, _) = apex_error(&system, &RunConfig::until(1e4).without_switching());
    eprintln!("interpreted, stepping across: apex error {across:e}");
    assert!(across > 1e-13, "stepped across and still hit: {across:e}");
}
