//! A flow's rate is ≥ 0 by definition (the statement says which way the mass goes), so a run
//! of generated code ends with `NegativeFlowRate`, naming the flow, at the first point where
//! one is negative: the core's run checks `VariableMassSystem::flow_rate` at the start and
//! after every step, as the command line tool does for the interpreter.

use varmass::core::observe;
use varmass::prelude::*;

/// A cart gathering sand that falls in at rest: m' = μ − k t, Q2 = μ − k t, u = 0. By hand:
/// R2 = Q2 (u − ẋ) = −Q2 ẋ and Σ ṁ ∂*p/∂m = ṁ ẋ cancel in ṗ, so p = m ẋ is constant. The
/// rate reaches 0 at t = μ/k and is negative after.
#[variable_mass_system(
    "coordinates x
mass m: state, rate mu - k*t
body cart: mass m, position [x]
inflow cart: rate mu - k*t, velocity [0]"
)]
struct EmptyingCart {
    mu: f64,
    k: f64,
}

/// A bucket leaking through a hole, with a second, silent flow the rate of which is the
/// default −ṁ of its body (`outflow` without `rate`): the index and name of the second.
#[variable_mass_system(
    "coordinates y
mass m: state, rate -mu
mass w = w0
body bucket: mass m, position [y]
body weight: mass w, position [y]
outflow bucket: rate mu, relative_velocity [0]
outflow weight: relative_velocity [0]
potential (m + w)*g*y"
)]
struct TwoFlows {
    mu: f64,
    w0: f64,
    g: f64,
}

/// The generated system names its flows as the model declares them and evaluates their
/// rates: μ − k t at t = 0.5 is 1 − 0.5 (exact in binary).
#[test]
fn generated_code_names_its_flows_and_evaluates_their_rates() {
    let cart = EmptyingCart { mu: 1.0, k: 1.0 };
    assert_eq!(cart.flow_count(), 1);
    assert_eq!(cart.flow_name(0), Some("inflow `cart`"));
    assert_eq!(cart.flow_name(1), None);
    let velocity_state = SVector::from([0.0, 2.0, 3.0]);
    assert_eq!(cart.flow_rate(0, 0.5, &velocity_state), 0.5);
    assert!(cart.flow_rate(1, 0.5, &velocity_state).is_nan());
    let bucket = TwoFlows {
        mu: 2.0,
        w0: 1.0,
        g: 9.81,
    };
    assert_eq!(bucket.flow_count(), 2);
    assert_eq!(bucket.flow_name(0), Some("outflow `bucket`"));
    assert_eq!(bucket.flow_name(1), Some("outflow `weight`"));
    // w = w0 is constant: the weight's default rate −ẇ is 0 (allowed).
    assert_eq!(
        bucket.flow_rate(1, 0.0, &SVector::from([0.0, 0.0, 5.0])),
        0.0
    );
}

/// `mu = -5`: the run ends at its start, t = 0, with the rate −5 of flow 0, and no step.
#[test]
fn a_negative_rate_at_the_start_ends_the_run_there() {
    let cart = EmptyingCart { mu: -5.0, k: 0.0 };
    let start = SVector::from([0.0, 1.0, 1.0]);
    let mut stepper = ClassicalRk4::new(&cart, 0.0, start, FixedStep { step: 0.25 }).unwrap();
    let failure = run(&mut stepper, &RunConfig::until(1.0), &[]).unwrap_err();
    assert_eq!(
        failure.error.kind,
        StepErrorKind::NegativeFlowRate {
            index: 0,
            rate: -5.0
        }
    );
    assert_eq!(failure.error.time, 0.0);
    assert_eq!(failure.error.state, start);
    assert_eq!(stepper.time(), 0.0);
    assert!(failure.partial.times.is_empty());
}

/// μ = k = 1: RK4 at h = 0.25 lands on t = 1 (rate 0, allowed), then on t = 1.25, where the
/// rate is 1 − 1.25 = −0.25 (exact). The run ends there with that state, and its points are
/// those up to t = 1, along which p = m ẋ stays 1 (the closed form above; measured to
/// rounding, bound 1e-14).
#[test]
fn a_rate_turning_negative_ends_the_run_at_the_first_step_past_it() {
    let cart = EmptyingCart { mu: 1.0, k: 1.0 };
    let start = SVector::from([0.0, 1.0, 1.0]);
    let mut stepper = ClassicalRk4::new(&cart, 0.0, start, FixedStep { step: 0.25 }).unwrap();
    let failure = run(&mut stepper, &RunConfig::until(2.0), &[]).unwrap_err();
    assert_eq!(
        failure.error.kind,
        StepErrorKind::NegativeFlowRate {
            index: 0,
            rate: -0.25
        }
    );
    assert_eq!(failure.error.time, 1.25);
    assert_eq!(failure.error.state, *stepper.state());
    assert_eq!(failure.partial.times, [0.0, 0.25, 0.5, 0.75, 1.0]);
    for state in &failure.partial.states {
        assert!((state[1] - 1.0).abs() <= 1e-14, "p = {}", state[1]);
    }
    // The same cart stopped before the rate turns runs to its end.
    let mut stepper = ClassicalRk4::new(&cart, 0.0, start, FixedStep { step: 0.25 }).unwrap();
    let solution = run(&mut stepper, &RunConfig::until(1.0), &[]).expect("the rate is ≥ 0");
    assert_eq!(solution.stop, StopReason::ReachedEnd);
}

/// An adaptive run and an observation end the same way: Dormand–Prince's first step end
/// past t = 1 (where 1 − t < 0) is where the run stops, and the error names that rate.
#[test]
fn adaptive_runs_and_observations_refuse_the_negative_rate_too() {
    let cart = EmptyingCart { mu: 1.0, k: 1.0 };
    let start = SVector::from([0.0, 1.0, 1.0]);
    let mut stepper = DormandPrince::new(&cart, 0.0, start, StepControl::default()).unwrap();
    let failure = run(&mut stepper, &RunConfig::until(2.0), &[]).unwrap_err();
    let time = failure.error.time;
    assert!(time > 1.0 && time <= 2.0, "t = {time}");
    assert_eq!(
        failure.error.kind,
        StepErrorKind::NegativeFlowRate {
            index: 0,
            rate: 1.0 - time
        }
    );
    let last = *failure.partial.times.last().expect("points before");
    assert!(last <= 1.0, "last accepted point {last}");
    let mut stepper = DormandPrince::new(&cart, 0.0, start, StepControl::default()).unwrap();
    let error = observe(&mut stepper, &[0.5, 1.5], &[]).unwrap_err();
    assert!(
        matches!(error.kind, StepErrorKind::NegativeFlowRate { index: 0, rate } if rate < 0.0),
        "{error}"
    );
}

/// The interpreter's `TapeSystem` gives the same flows (names and rates) as generated code,
/// so the core's run refuses the same point: t = 1.25, rate −0.25, for RK4 at h = 0.25.
#[test]
fn the_interpreter_refuses_the_same_point() {
    use varmass::interpret::{Program, TapeSystem};
    use varmass::symbolic::{derive_source, mechanics::Parameters};
    let derivation = derive_source(EmptyingCart::SOURCE, Parameters::Inferred).expect("derives");
    let program = Program::new(derivation, &[("mu", 1.0), ("k", 1.0)]).expect("fits");
    let system = TapeSystem::<1, 3>::new(program).expect("sizes");
    assert_eq!(system.flow_count(), 1);
    assert_eq!(system.flow_name(0), Some("inflow `cart`"));
    let velocity_state = SVector::from([0.0, 2.0, 3.0]);
    assert_eq!(system.flow_rate(0, 0.5, &velocity_state), 0.5);
    assert!(system.flow_rate(1, 0.5, &velocity_state).is_nan());
    let start = SVector::from([0.0, 1.0, 1.0]);
    let mut stepper = ClassicalRk4::new(&system, 0.0, start, FixedStep { step: 0.25 }).unwrap();
    let failure = run(&mut stepper, &RunConfig::until(2.0), &[]).unwrap_err();
    assert_eq!(
        failure.error.kind,
        StepErrorKind::NegativeFlowRate {
            index: 0,
            rate: -0.25
        }
    );
    assert_eq!(failure.error.time, 1.25);
}
