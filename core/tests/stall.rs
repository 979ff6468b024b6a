//! Every run makes progress or ends with a typed error (issue 34, item 2): a run built to
//! stall ends with `StepErrorKind::Stalled` at the time it stands on, its points kept.
//!
//! The system: a free unit mass (x(t) = t from x = 0, ẋ = 1) with two switching functions
//! that change nothing in its motion. g₀ is +1 before t = 1, 0 on [1, 1 + 10⁻⁶] and −1 after:
//! a switch that sits on zero longer than the run's search for its crossing reaches (a
//! million roundings of t, 9e-10 here). g₁ = 5 − t is a switch ahead. RK4 at step 0.25
//! lands on t = 1, where g₀ = 0 (the side it came from is kept); the next step sees g₀
//! cross, located at its start; no Euler step within reach changes g₀'s sign and the
//! tangent's nearest root is g₁'s, 4 ahead: the run redoes the step toward it, meets the
//! same crossing at the same start, and would go round until `max_steps` (10⁷ passes).

mod support;

use nalgebra::{SMatrix, SVector, Vector1};
use varmass_core::steppers::{ClassicalRk4, FixedStep};
use varmass_core::{run, RunConfig, StepErrorKind, StopReason, SystemError, VariableMassSystem};

/// A free unit mass with the two switches above.
struct StuckSwitch;

impl VariableMassSystem<1, 2> for StuckSwitch {
    const COORDINATES: [&'static str; 1] = ["x"];
    const MASSES: &'static [&'static str] = &["m"];

    fn mass(&self, _: usize, _: f64, _: &SVector<f64, 2>) -> f64 {
        1.0
    }
    fn mass_rate(&self, _: usize, _: f64, _: &SVector<f64, 2>) -> f64 {
        0.0
    }
    fn mass_matrix(&self, _: f64, _: &SVector<f64, 2>) -> SMatrix<f64, 1, 1> {
        SMatrix::<f64, 1, 1>::new(1.0)
    }
    fn momenta(&self, _: f64, vs: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::new(vs[1])
    }
    fn lagrangian(&self, _: f64, vs: &SVector<f64, 2>) -> f64 {
        0.5 * vs[1] * vs[1]
    }
    fn lagrangian_gradient(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn active_force(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn reactive_thrust(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn impact_force(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn mass_flux_force(&self, _: f64, _: &SVector<f64, 2>) -> SVector<f64, 1> {
        Vector1::zeros()
    }
    fn accelerations(&self, _: f64, _: &SVector<f64, 2>) -> Result<SVector<f64, 1>, SystemError> {
        Ok(Vector1::zeros())
    }
    fn switch_count(&self) -> usize {
        2
    }
    fn switching_functions(&self, t: f64, _: &SVector<f64, 2>, values: &mut [f64]) {
        values[0] = match t {
            _ if t < 1.0 => 1.0,
            _ if t <= 1.0 + 1e-6 => 0.0,
            _ => -1.0,
        };
        values[1] = 5.0 - t;
    }
}

#[test]
fn a_run_that_cannot_get_past_a_switch_ends_stalled_with_its_points() {
    let start = SVector::from([0.0, 1.0]);
    let mut stepper =
        ClassicalRk4::new(&StuckSwitch, 0.0, start, FixedStep { step: 0.25 }).unwrap();
    let config = RunConfig {
        stall_passes: 50,
        ..RunConfig::until(10.0)
    };
    let failure = run(&mut stepper, &config, &[]).expect_err("the run stalls");
    // One pass over the limit, at t = 1 where it stands, x = 1.
    assert_eq!(failure.kind, StepErrorKind::Stalled { steps: 51 });
    assert_eq!(failure.time, 1.0);
    assert_eq!(failure.state, SVector::from([1.0, 1.0]));
    // The points up to t = 1 are kept: 0, 0.25, 0.5, 0.75, 1 on x = t.
    let partial = &failure.partial;
    assert_eq!(partial.stop, StopReason::Failed);
    assert_eq!(partial.times, [0.0, 0.25, 0.5, 0.75, 1.0]);
    assert!(partial
        .times
        .iter()
        .zip(&partial.states)
        .all(|(t, s)| s[0] == *t));
    // Far fewer steps than the 10⁷ of max_steps: the 4 to t = 1 and one per pass.
    assert!(
        partial.statistics.accepted_steps <= 4 + 51,
        "{:?}",
        partial.statistics
    );
}

#[test]
fn the_default_limit_stops_the_same_run() {
    let start = SVector::from([0.0, 1.0]);
    let mut stepper =
        ClassicalRk4::new(&StuckSwitch, 0.0, start, FixedStep { step: 0.25 }).unwrap();
    let failure = run(&mut stepper, &RunConfig::until(10.0), &[]).expect_err("the run stalls");
    assert_eq!(failure.kind, StepErrorKind::Stalled { steps: 1_001 });
    assert_eq!(failure.time, 1.0);
}
