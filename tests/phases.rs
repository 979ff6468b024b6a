//! Phases (docs/mechanics.md#jumps-and-phases): the two-stage rocket of
//! `models/two_stage_rocket.vms` as one scene, separation carrying the velocity.

use varmass::core::steppers::{AdaptiveControl, StepControl};
use varmass::core::{continue_phases, run_phases, Carry, EventAction, Phase};
use varmass::prelude::*;

#[variable_mass_system(file = "models/two_stage_rocket.vms")]
#[derive(Clone, Copy)]
struct Stage {
    mu: f64,
    u_e: f64,
    g: f64,
}

const STAGE_1: Stage = Stage {
    mu: 10.0,
    u_e: 2500.0,
    g: 9.81,
};
const STAGE_2: Stage = Stage {
    mu: 2.0,
    u_e: 3000.0,
    g: 9.81,
};

fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-13,
        ..AdaptiveControl::default()
    })
}

/// The acceptance case: v(150 s) = 2500 ln 2 − 9.81·50 + 3000 ln 3 − 9.81·100
/// = 3557.204817404192 m/s (Tsiolkovsky with gravity loss per stage; the velocity carries
/// over the separation). Measured 1.1e-14 relative at tolerance 1e-13; bound 1e-12. The separated 200 kg
/// leaves with v(50 s) = 2500 ln 2 − 490.5 m/s, taking ½·200·v² of kinetic energy.
#[test]
fn the_two_stage_rocket_reaches_its_closed_form_speed() {
    let burnout = Event::mass_reaches(0, 500.0);
    let phases = [
        Phase {
            system: STAGE_1,
            carry: Carry::Separation,
            state_masses: &[],
            until: Some(burnout),
        },
        Phase {
            system: STAGE_2,
            carry: Carry::Separation,
            state_masses: &[(0, 300.0)],
            until: None,
        },
    ];
    let start = SVector::from([0.0, 0.0, 1000.0]);
    let config = RunConfig::until(150.0);
    let phased = run_phases(
        &phases,
        (0.0, start),
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &config,
    )
    .expect("the flight runs");
    let (time, state) = phased.solution.last().expect("points");
    assert_eq!(time, 150.0);
    let speed = state[1] / state[2];
    let exact = 2500.0 * 2f64.ln() - 9.81 * 50.0 + 3000.0 * 3f64.ln() - 9.81 * 100.0;
    assert_eq!(exact, 3557.204817404192);
    let error = (speed - exact).abs() / exact;
    eprintln!("v(150) = {speed}, relative error {error:e}");
    assert!(error <= 1e-12, "{error:e}");
    assert_eq!(phased.changes.len(), 1);
    let change = phased.changes[0];
    assert_eq!(change.phase, 1);
    assert!((change.time - 50.0).abs() < 1e-9, "{change:?}");
    let v_50 = 2500.0 * 2f64.ln() - 9.81 * 50.0;
    let taken = 0.5 * 200.0 * v_50 * v_50;
    assert!(
        (change.kinetic_energy_removed - taken).abs() <= 1e-9 * taken,
        "{change:?}"
    );
    // The phase column: 0 up to the separation, 1 after, as many as the points.
    assert_eq!(phased.phase.len(), phased.solution.times.len());
    assert_eq!(phased.phase.first(), Some(&0));
    assert_eq!(phased.phase.last(), Some(&1));
    assert!(phased.phase.windows(2).all(|w| w[0] <= w[1]));
}

/// Capture keeps p: stage 1 burns to 500 kg at t = 50 s, captures 100 kg arriving at rest
/// (a plastic impact, m → 600 kg at the same momentum, so v(50 s⁺) = v(50 s)·500/600), then
/// stage 2 burns 2 kg/s for 100 s to 400 kg: v(150 s) = v(50 s)·500/600 + 3000 ln(600/400)
/// − 9.81·100, v(50 s) = 2500 ln 2 − 9.81·50. The impact removes ½·500·v² − ½·600·(5v/6)²
/// = ½·500·v²/6 of kinetic energy.
#[test]
fn capture_keeps_the_momentum() {
    let phases = [
        Phase {
            system: STAGE_1,
            carry: Carry::Separation,
            state_masses: &[],
            until: Some(Event::mass_reaches(0, 500.0)),
        },
        Phase {
            system: STAGE_2,
            carry: Carry::Capture,
            state_masses: &[(0, 600.0)],
            until: None,
        },
    ];
    let start = SVector::from([0.0, 0.0, 1000.0]);
    let phased = run_phases(
        &phases,
        (0.0, start),
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &RunConfig::until(150.0),
    )
    .expect("the flight runs");
    let (_, state) = phased.solution.last().expect("points");
    let v_50 = 2500.0 * 2f64.ln() - 9.81 * 50.0;
    let exact = v_50 * 500.0 / 600.0 + 3000.0 * 1.5f64.ln() - 9.81 * 100.0;
    let error = (state[1] / state[2] - exact).abs() / exact;
    // Measured at tolerance 1e-13 as the separation above; bound 1e-12.
    assert!(error <= 1e-12, "{error:e}");
    let removed = 0.5 * 500.0 * v_50 * v_50 / 6.0;
    let removed_error = (phased.changes[0].kinetic_energy_removed - removed).abs() / removed;
    assert!(removed_error <= 1e-12, "{removed_error:e}");
}

/// A capture that shrinks the mass (500 kg → 300 kg at the same p, raising v by 5/3) or a
/// separation that grows it (500 kg → 700 kg at the same v) would create kinetic energy:
/// the "kinetic energy removed" is ½ p² (1/500 − 1/300) < 0 and ½ v² (500 − 700) < 0, and
/// both ran with exit 0 before. Refused at the change (t = 50 s) with the typed
/// configuration error.
#[test]
fn a_capture_that_loses_mass_or_a_separation_that_gains_it_is_refused() {
    let end = || Event::mass_reaches(0, 100.0);
    let mut capture = two_stages(&[(0, 300.0)], end());
    capture[1].carry = Carry::Capture;
    refused_at_the_change(&capture, varmass::core::phases::MASS_AGAINST_CARRY);
    let separation = two_stages(&[(0, 700.0)], end());
    refused_at_the_change(&separation, varmass::core::phases::MASS_AGAINST_CARRY);
}

#[variable_mass_system(file = "models/rocket.vms")]
#[derive(Clone, Copy)]
struct Burn {
    mu: f64,
    u_e: f64,
    g: f64,
}

#[variable_mass_system(file = "models/rocket.vms", with = ["drag"])]
#[derive(Clone, Copy)]
struct Coast {
    mu: f64,
    u_e: f64,
    g: f64,
    k_d: f64,
}

/// A scene that switches to another struct of the same model: the rocket of
/// `models/rocket.vms` burns without drag (g = 0, mu = 10 kg/s, u_e = 2500 m/s) from 1000 kg
/// to 900 kg (t = 10 s), then coasts as the `[drag]` struct (mu = 0, k_d = 0.5 kg/m).
/// By hand: v₁ = u_e ln(m₀/m₁) and y₁ = u_e (t₁ − (m₁/mu) ln(m₀/m₁)); then m₁ v' = −k_d v²
/// gives v(t) = v₁/(1 + k_d v₁ τ/m₁) and y(t) = y₁ + (m₁/k_d) ln(1 + k_d v₁ τ/m₁), τ = t − 10.
/// No mass separates, so the change removes no kinetic energy. Measured at tolerance 1e-13:
/// v 3.2e-14, y 1.6e-15 relative; bounds 1e-12.
#[test]
fn a_phase_switches_to_another_struct_of_the_model() {
    let burn = [Phase {
        system: Burn {
            mu: 10.0,
            u_e: 2500.0,
            g: 0.0,
        },
        carry: Carry::Separation,
        state_masses: &[],
        until: Some(Event::mass_reaches(0, 900.0)),
    }];
    let coast = [Phase {
        system: Coast {
            mu: 0.0,
            u_e: 2500.0,
            g: 0.0,
            k_d: 0.5,
        },
        carry: Carry::Separation,
        state_masses: &[],
        until: None,
    }];
    let config = RunConfig::until(30.0);
    let start = (0.0, SVector::from([0.0, 0.0, 1000.0]));
    let burnt = run_phases(
        &burn,
        start,
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &config,
    )
    .expect("the burn runs");
    let whole = continue_phases(
        burnt,
        &burn[0].system,
        &coast,
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &config,
    )
    .expect("the coast runs");
    let (time, state) = whole.solution.last().expect("points");
    assert_eq!(time, 30.0);
    let (m0, m1, u_e, k_d): (f64, f64, f64, f64) = (1000.0, 900.0, 2500.0, 0.5);
    let v1 = u_e * (m0 / m1).ln();
    let y1 = u_e * (10.0 - (m1 / 10.0) * (m0 / m1).ln());
    let grow = 1.0 + k_d * v1 * 20.0 / m1;
    let (v, y) = (v1 / grow, y1 + (m1 / k_d) * grow.ln());
    let v_error = (state[1] / state[2] - v).abs() / v;
    let y_error = (state[0] - y).abs() / y;
    eprintln!("v(30) error {v_error:e}, y(30) error {y_error:e}");
    assert!(
        v_error <= 1e-12 && y_error <= 1e-12,
        "{v_error:e} {y_error:e}"
    );
    assert_eq!(whole.changes.len(), 1);
    assert_eq!(whole.changes[0].phase, 1);
    assert!(whole.changes[0].kinetic_energy_removed.abs() <= 1e-9);
    assert_eq!(whole.phase.last(), Some(&1));
}

#[variable_mass_system(
    "
    coordinates x
    mass m: state, rate -mu
    body b: mass m, position [x]
    "
)]
#[derive(Clone, Copy)]
struct OtherCoordinate {
    mu: f64,
}

/// Continuing with a struct of other coordinates (same sizes) is refused at the change,
/// with the typed configuration error at its time, the burn's points kept.
#[test]
fn continuing_with_other_coordinates_is_refused() {
    let burn = [Phase {
        system: Burn {
            mu: 10.0,
            u_e: 2500.0,
            g: 0.0,
        },
        carry: Carry::Separation,
        state_masses: &[],
        until: Some(Event::mass_reaches(0, 900.0)),
    }];
    let other = [Phase {
        system: OtherCoordinate { mu: 1.0 },
        carry: Carry::Separation,
        state_masses: &[],
        until: None,
    }];
    let config = RunConfig::until(30.0);
    let start = (0.0, SVector::from([0.0, 0.0, 1000.0]));
    let burnt = run_phases(
        &burn,
        start,
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &config,
    )
    .expect("the burn runs");
    let points = burnt.solution.times.len();
    let failure = continue_phases(
        burnt,
        &burn[0].system,
        &other,
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &config,
    )
    .expect_err("other coordinates");
    assert!(
        matches!(
            failure.kind,
            StepErrorKind::InvalidConfiguration { reason } if reason.contains("other coordinates")
        ),
        "{:?}",
        failure.kind
    );
    assert!((failure.time - 10.0).abs() < 1e-9, "{}", failure.time);
    assert_eq!(failure.partial.times.len(), points);
}

/// A phase whose end condition already holds where it begins could never trigger: stage 2
/// of the two-stage rocket told to end when y rises through 100 m, entered at y(50 s) ≈
/// 44 km, would otherwise run silently to the end time and never hand over to stage 3.
/// The run ends at the change (t = 50 s) with the typed configuration error, stage 1's
/// points kept.
#[test]
fn a_phase_whose_end_already_holds_is_refused_at_its_start() {
    let phases = [
        Phase {
            system: STAGE_1,
            carry: Carry::Separation,
            state_masses: &[],
            until: Some(Event::mass_reaches(0, 500.0)),
        },
        Phase {
            system: STAGE_2,
            carry: Carry::Separation,
            state_masses: &[(0, 300.0)],
            until: Some(Event::state_reaches(0, 100.0, Direction::Rising)),
        },
        Phase {
            system: STAGE_2,
            carry: Carry::Separation,
            state_masses: &[],
            until: None,
        },
    ];
    let failure = run_phases(
        &phases,
        (0.0, SVector::from([0.0, 0.0, 1000.0])),
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &RunConfig::until(150.0),
    )
    .expect_err("stage 2's end already holds");
    assert!(
        matches!(
            failure.kind,
            StepErrorKind::InvalidConfiguration { reason } if reason == varmass::core::phases::ALREADY_PAST
        ),
        "{:?}",
        failure.kind
    );
    assert!((failure.time - 50.0).abs() < 1e-9, "{}", failure.time);
    assert!(failure.state[0] > 100.0, "{}", failure.state[0]);
    assert_eq!(failure.partial.times.last().copied(), Some(failure.time));
}

/// The two-stage rocket's stages with stage 2 entered by `state_masses` and ended by
/// `until`, for the refusals below.
fn two_stages<'a>(
    state_masses: &'a [(usize, f64)],
    until: Event<'a, 3>,
) -> [Phase<'a, Stage, 3>; 2] {
    [
        Phase {
            system: STAGE_1,
            carry: Carry::Separation,
            state_masses: &[],
            until: Some(Event::mass_reaches(0, 500.0)),
        },
        Phase {
            system: STAGE_2,
            carry: Carry::Separation,
            state_masses,
            until: Some(until),
        },
    ]
}

/// Runs `phases` from rest at 1000 kg to t = 150 s, expecting the typed configuration error
/// `reason` at the change (t = 50 s, where m reaches 500 kg: 1000 − 10·50).
fn refused_at_the_change(phases: &[Phase<'_, Stage, 3>], reason: &str) {
    let failure = run_phases(
        phases,
        (0.0, SVector::from([0.0, 0.0, 1000.0])),
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &RunConfig::until(150.0),
    )
    .expect_err("refused at the change");
    assert!(
        matches!(failure.kind, StepErrorKind::InvalidConfiguration { reason: r } if r == reason),
        "{:?}",
        failure.kind
    );
    assert!((failure.time - 50.0).abs() < 1e-9, "{}", failure.time);
}

/// A phase entered exactly on its end condition's boundary (stage 2 set to m = 300 kg and
/// told to end when m = 300 kg) could never trigger either: a run does not count a start at
/// g = 0. Before, the phase ran silently to the end time.
#[test]
fn a_phase_entered_on_its_boundary_is_refused() {
    let phases = two_stages(&[(0, 300.0)], Event::mass_reaches(0, 300.0));
    refused_at_the_change(&phases, varmass::core::phases::ALREADY_PAST);
}

/// A phase that sets a state mass the system lacks (index 1 of one) or to a value that is
/// not positive is refused at the change; before, the index was skipped silently.
#[test]
fn a_phase_setting_a_state_mass_wrongly_is_refused() {
    let end = || Event::mass_reaches(0, 100.0);
    for masses in [&[(1, 300.0)][..], &[(0, -1.0)], &[(0, f64::NAN)]] {
        refused_at_the_change(
            &two_stages(masses, end()),
            varmass::core::phases::BAD_STATE_MASS,
        );
    }
}

/// Continuing phases that failed is an error, not the failure handed back as `Ok`.
#[test]
fn continuing_failed_phases_is_an_error() {
    let phases = two_stages(&[(1, 300.0)], Event::mass_reaches(0, 100.0));
    let (failed, error) = varmass::core::run_phases_keeping(
        &phases,
        (0.0, SVector::from([0.0, 0.0, 1000.0])),
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &RunConfig::until(150.0),
    );
    assert!(error.is_some());
    let more = [Phase {
        system: STAGE_2,
        carry: Carry::Separation,
        state_masses: &[],
        until: None,
    }];
    let failure = continue_phases(
        failed,
        &STAGE_1,
        &more,
        |system, t, state| DormandPrince::new(system, t, state, control()),
        &RunConfig::until(150.0),
    )
    .expect_err("nothing to continue");
    assert!(
        matches!(
            failure.kind,
            StepErrorKind::InvalidConfiguration { reason } if reason == varmass::core::phases::NOTHING_TO_CONTINUE
        ),
        "{:?}",
        failure.kind
    );
}

/// A one-way condition standing on its boundary where its phase begins: stage 2 entered at
/// t = 50 s with an end g(t) = (t − 50)(60 − t), zero at the change, positive, then falling
/// through zero at t = 60 s. A run does not count its start at zero as a crossing, so the
/// fall at 60 s is the phase's end (a body lifting off at y = 0 whose phase ends at `y < 0`
/// is this case). Before, the phase was refused at the change. The same condition with
/// g(t) = 50 − t leaves zero at once to the side where it holds: it held from the start and
/// could never trigger, so it is refused at the change (after the phase's run, which is not
/// kept).
#[test]
fn a_one_way_condition_on_its_boundary_at_the_change_waits_for_its_crossing() {
    let later = |t: f64, _: &SVector<f64, 3>| (t - 50.0) * (60.0 - t);
    let at_once = |t: f64, _: &SVector<f64, 3>| 50.0 - t;
    let falling = |g| Event::function(g, Direction::Falling, EventAction::Stop);
    let run = |end| {
        run_phases(
            &two_stages(&[(0, 300.0)], end),
            (0.0, SVector::from([0.0, 0.0, 1000.0])),
            |system, t, state| DormandPrince::new(system, t, state, control()),
            &RunConfig::until(150.0),
        )
    };
    let phased = run(falling(&later)).expect("the fall at t = 60 s ends the phase");
    let end = phased.solution.times.last().copied().unwrap_or(f64::NAN);
    // The event is located to its default tolerance; measured 60 to rounding.
    assert!((end - 60.0).abs() < 1e-9, "ended at {end}");
    assert_eq!(phased.solution.stop, StopReason::EventFound { index: 0 });
    let failure = run(falling(&at_once)).expect_err("held from the start");
    assert!(
        matches!(failure.kind,
            StepErrorKind::InvalidConfiguration { reason } if reason == varmass::core::phases::ALREADY_PAST),
        "{:?}",
        failure.kind
    );
    assert!((failure.time - 50.0).abs() < 1e-9, "{}", failure.time);
    let kept = failure.partial.times.last().copied().unwrap_or(f64::NAN);
    assert!(
        (kept - 50.0).abs() < 1e-9,
        "the phase's run kept up to {kept}"
    );
}
