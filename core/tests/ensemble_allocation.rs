//! Inside an ensemble, a member allocates per run, not per step: the ensemble adds nothing
//! per member, and a run's only allocations are its solution's vectors, which grow by
//! doubling (so their count grows with the logarithm of the steps, not with the steps).

#[path = "support/counting.rs"]
mod counting;
mod support;

use counting::allocations;
use nalgebra::Vector3;
use support::systems::Rocket;
use varmass_core::ensemble::rand::RngExt;
use varmass_core::ensemble::{Ensemble, MemberRng};
use varmass_core::steppers::{DormandPrince, FixedStep, StepControl};
use varmass_core::{run, Event, RunConfig, StepError};

/// A burning rocket run with a fixed step `step` to t = 5 (so 5/step steps), with a mass
/// event that does not trigger; observables: the final height and the step count.
fn rocket_member(step: f64) -> impl Fn(&f64) -> Result<[f64; 2], StepError<3>> + Sync {
    move |exhaust_speed: &f64| {
        let rocket = Rocket {
            burn_rate: 0.05,
            exhaust_speed: *exhaust_speed,
            gravity: 9.81,
        };
        let control = StepControl::Fixed(FixedStep { step });
        let mut stepper = DormandPrince::new(&rocket, 0.0, Vector3::new(0.0, 0.0, 1.0), control)?;
        let events = [Event::mass_reaches(0, 0.1)];
        let solution = run(&mut stepper, &RunConfig::until(5.0), &events)?;
        Ok([
            solution.states[solution.states.len() - 1][0],
            solution.statistics.accepted_steps as f64,
        ])
    }
}

fn sample(rng: &mut MemberRng) -> f64 {
    rng.random_range(250.0..350.0)
}

/// Allocations made by member 0 and the steps it took.
fn member_allocations(step: f64) -> (usize, f64) {
    let ensemble = Ensemble::new(1, ["height", "steps"], sample, rocket_member(step)).serial();
    let before = allocations();
    let (_, result) = ensemble.member(0);
    let count = allocations() - before;
    (count, result.map_or(f64::NAN, |values| values[1]))
}

#[test]
fn a_member_allocates_per_run_not_per_step() {
    // The counter must see allocations at all, or the test could not fail.
    let probe = allocations();
    let boxed = std::hint::black_box(Box::new(1.0));
    assert!(allocations() > probe);
    drop(boxed);

    let (short, short_steps) = member_allocations(5.0 / 64.0);
    let (long, long_steps) = member_allocations(5.0 / 65_536.0);
    assert_eq!((short_steps, long_steps), (64.0, 65_536.0));
    // 1024 times the steps: the two recorded vectors (times, states) double 10 more times
    // each. Measured: 14 and 34 allocations.
    assert!(long <= short + 2 * 10, "{short} → {long} allocations");
    assert!(long < 64, "{long} allocations for 65 536 steps");
}

#[test]
fn the_ensemble_adds_no_allocation_per_member() {
    // A member that allocates nothing: the ensemble's own cost is per batch (the outcome
    // vector) and the partial's columns, which grow by doubling.
    let ensemble = Ensemble::new(2, ["x"], sample, |x: &f64| Ok::<_, StepError<3>>([*x]))
        .batch_size(1000)
        .serial();
    let before = allocations();
    let (_, result) = ensemble.member(7);
    assert_eq!(allocations() - before, 0);
    assert!(result.is_ok());

    let before = allocations();
    let partial = ensemble.run(0..100_000);
    let count = allocations() - before;
    assert_eq!(partial.completed().len(), 100_000);
    // 100 batches of one vector each, plus the doublings of the growing vectors (indices,
    // the column, the covered ranges: at most ⌈log2 100 000⌉ + 1 = 18 each). Measured: 136.
    assert!(
        count <= 100 + 3 * 18,
        "{count} allocations for 100 000 members"
    );
}
