//! The stiff leaking spring pendulum: the model of `examples/leaking_spring_pendulum.rs`
//! with a spring of k = 1e8 N/m. The radial mode then oscillates at √(k/m) ≈ 7·10³ rad/s
//! while the swing has a period of about 2 s. Started on the slow manifold (the spring
//! stretched to balance the weight, at rest), the radial oscillation is barely excited and
//! the motion is smooth, but every explicit method must still resolve its period for
//! stability: Dormand–Prince's stiffness test says so, and the L-stable SDIRK4 does not
//! need to, nor does the L-stable ESDIRK4(3)6L[2]SA. (Against a tight explicit run,
//! DOP853 at 1e-12.)
//!
//! By hand, with p_r = m ṙ, p_θ = m r² θ̇, the radial equation is
//! ṗ_r = m r θ̇² − k (r − l₀) + m g cos θ − μ ṙ: at rest the spring balances the weight at
//! r₀ = l₀ + m₀ g cos θ₀ / k.

use varmass::core::steppers::{Dop853, Esdirk43, Sdirk4};
use varmass::prelude::*;

#[variable_mass_system(
    "
    coordinates r, th
    mass m: state, rate -mu
    body bob: mass m, position [r*sin(th), -r*cos(th)]
    potential 1/2*k*(r - l0)^2 - m*g*r*cos(th)
    outflow bob: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]
    check p_th = m*r^2*th'
    check R1_th = -mu*u_e*r
"
)]
struct Pendulum {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

const M0: f64 = 2.0;
const THETA0: f64 = 0.5;
const END: f64 = 10.0;

fn pendulum(k: f64) -> Pendulum {
    Pendulum {
        mu: 0.05,
        u_e: 2.0,
        k,
        l0: 1.0,
        g: 9.81,
    }
}

/// At rest, the spring balancing the weight along the string.
fn start(system: &Pendulum) -> SVector<f64, 5> {
    let r0 = system.l0 + M0 * system.g * THETA0.cos() / system.k;
    SVector::<f64, 5>::from([r0, THETA0, 0.0, 0.0, M0])
}

fn tolerance(tolerance: f64, control: AdaptiveControl) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..control
    })
}

/// The end state and the statistics of a run to `END`.
fn end<St: Stepper<2, 5, System = Pendulum>>(
    mut stepper: St,
) -> (SVector<f64, 5>, varmass::core::Statistics) {
    let solution = run(&mut stepper, &RunConfig::until(END), &[]).unwrap();
    let (time, state) = solution.last().unwrap();
    assert_eq!(time, END);
    (*state, solution.statistics)
}

/// The reference: DOP853 at 1e-12, whose steps are set by stability, far below what its
/// accuracy needs. Dormand–Prince (a second method, also stability-limited) agrees to
/// 2.0e-13 relative in θ(10).
fn reference(system: &Pendulum) -> SVector<f64, 5> {
    let control = tolerance(1e-12, AdaptiveControl::dop853());
    let (state, statistics) = end(Dop853::new(system, 0.0, start(system), control).unwrap());
    eprintln!("reference θ(10) = {}, {statistics:?}", state[1]);
    state
}

/// Adaptive Dormand–Prince with the default control: its statistics, after checking its
/// angle against the reference (measured 2.0e-13 relative: the two explicit runs agree far
/// below the 1e-6 asked of the implicit ones).
fn dormand_prince(system: &Pendulum, reference: &SVector<f64, 5>) -> varmass::core::Statistics {
    let (state, statistics) =
        end(DormandPrince::new(system, 0.0, start(system), StepControl::default()).unwrap());
    eprintln!(
        "Dormand–Prince (default control): θ(10) = {}, {statistics:?}",
        state[1]
    );
    assert!(((state[1] - reference[1]) / reference[1]).abs() < 1e-9);
    statistics
}

/// Measured: Dormand–Prince (default tolerances) 75 933 steps and stiffness reported;
/// SDIRK4 at 1e-8 855 steps (89× fewer), θ(10) within 2.2e-8 relative of the reference.
#[test]
fn sdirk4_reaches_the_angle_with_fifty_times_fewer_steps_than_dormand_prince() {
    let system = pendulum(1e8);
    let reference = reference(&system);
    let dp = dormand_prince(&system, &reference);
    let control = tolerance(1e-8, AdaptiveControl::sdirk4());
    let (state, sdirk) = end(Sdirk4::new(&system, 0.0, start(&system), control).unwrap());
    let relative = ((state[1] - reference[1]) / reference[1]).abs();
    eprintln!(
        "SDIRK4 (1e-8): θ(10) = {}, relative error {relative:e}, {sdirk:?}",
        state[1]
    );
    assert!(relative < 1e-6, "{relative:e}");
    assert!(
        50 * sdirk.accepted_steps <= dp.accepted_steps,
        "SDIRK4 {} steps, Dormand–Prince {}",
        sdirk.accepted_steps,
        dp.accepted_steps
    );
    assert!(dp.stiffness_detected, "{dp:?}");
    assert!(!sdirk.stiffness_detected);
}

/// With k = 1e2 the radial period is 0.9 s: not stiff, and the test, which runs every
/// 1000 steps, stays silent over a tight run of more than 1000 steps.
#[test]
fn dormand_prince_reports_no_stiffness_on_a_soft_spring() {
    let system = pendulum(1e2);
    let control = tolerance(1e-10, AdaptiveControl::default());
    let (_, dp) = end(DormandPrince::new(&system, 0.0, start(&system), control).unwrap());
    eprintln!("k = 1e2: {dp:?}");
    assert!(
        dp.accepted_steps >= 1000,
        "the test runs every 1000 steps: {dp:?}"
    );
    assert!(!dp.stiffness_detected, "{dp:?}");
}

/// ESDIRK4(3)6L[2]SA on the same run. Measured at 1e-9: 592 steps (128× fewer than
/// Dormand–Prince), 5 923 rate evaluations, θ(10) within 1.3e-7 relative. (At 1e-8 it takes
/// 332 steps for 1.3e-6: its embedded third-order solution, designed to be accurate, gives
/// a less conservative estimate than SDIRK4's, so it needs a tighter tolerance for the
/// same error and still takes fewer steps.)
#[test]
fn esdirk_reaches_the_angle_with_fifty_times_fewer_steps_than_dormand_prince() {
    let system = pendulum(1e8);
    let reference = reference(&system);
    let dp = dormand_prince(&system, &reference);
    let control = tolerance(1e-9, AdaptiveControl::sdirk4());
    let (state, esdirk) = end(Esdirk43::new(&system, 0.0, start(&system), control).unwrap());
    let relative = ((state[1] - reference[1]) / reference[1]).abs();
    eprintln!(
        "ESDIRK4(3) (1e-9): θ(10) = {}, relative error {relative:e}, {esdirk:?}",
        state[1]
    );
    assert!(relative < 1e-6, "{relative:e}");
    assert!(
        50 * esdirk.accepted_steps <= dp.accepted_steps,
        "ESDIRK {} steps, Dormand–Prince {}",
        esdirk.accepted_steps,
        dp.accepted_steps
    );
    assert!(dp.stiffness_detected, "{dp:?}");
}

/// The time θ first falls through zero, located on the dense output of `stepper`.
fn first_zero<St: Stepper<2, 5, System = Pendulum>>(mut stepper: St) -> f64 {
    let events = [Event::state_reaches(1, 0.0, Direction::Falling)];
    let solution = run(&mut stepper, &RunConfig::until(END), &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    eprintln!(
        "zero at {}, {:?}",
        solution.events[0].time, solution.statistics
    );
    solution.events[0].time
}

/// The first zero of θ (about a quarter swing, t ≈ 0.5 s), located on ESDIRK's
/// third-order dense output to 1e-10 in t against DOP853 at 1e-12 on its seventh-order
/// one (Dormand–Prince at 1e-12, a second reference, agrees to 7e-16; bound 1e-11).
/// Measured at 1e-11: 2.0e-12 from the reference after 1 428 steps.
#[test]
fn esdirk_locates_the_first_zero_of_the_angle_on_its_dense_output() {
    let system = pendulum(1e8);
    let tight = |control| tolerance(1e-12, control);
    let dop853 = Dop853::new(
        &system,
        0.0,
        start(&system),
        tight(AdaptiveControl::dop853()),
    );
    let reference = first_zero(dop853.unwrap());
    let dp = DormandPrince::new(
        &system,
        0.0,
        start(&system),
        tight(AdaptiveControl::default()),
    );
    let second = first_zero(dp.unwrap());
    assert!(
        (second - reference).abs() < 1e-11,
        "{second} against {reference}"
    );
    let control = tolerance(1e-11, AdaptiveControl::sdirk4());
    let esdirk = Esdirk43::new(&system, 0.0, start(&system), control);
    let time = first_zero(esdirk.unwrap());
    eprintln!("ESDIRK: {:e} from the reference", time - reference);
    assert!(
        (time - reference).abs() < 1e-10,
        "{time} against {reference}"
    );
}

/// Past the end of the propellant (m = 2 − 0.05 t reaches 0 at t = 40 s): with a mass
/// event the run ends in it, at t = 39.98 where m = 1e-3 (m is linear in t); without, in
/// a typed error near t = 40 with a finite state. The radial mode stiffens as √(k/m)
/// grows; never a NaN.
#[test]
fn esdirk_running_out_of_propellant_ends_in_the_event_or_a_typed_error() {
    let system = pendulum(1e8);
    let control = tolerance(1e-8, AdaptiveControl::sdirk4());
    let until = RunConfig::until(50.0);
    let mut stepper = Esdirk43::new(&system, 0.0, start(&system), control).unwrap();
    let events = [Event::mass_reaches(0, 1e-3)];
    let solution = run(&mut stepper, &until, &events).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let (time, state) = solution.last().unwrap();
    eprintln!("mass event at {time}: {state}, {:?}", solution.statistics);
    assert!((time - 39.98).abs() < 1e-10, "{time}");
    assert!(state.iter().all(|x| x.is_finite()), "{state}");

    let mut stepper = Esdirk43::new(&system, 0.0, start(&system), control).unwrap();
    let error = run(&mut stepper, &until, &[]).unwrap_err();
    eprintln!("past burn-out: {error:?}");
    // The last step lands on t = 40 within rounding (measured 40 + 6.4e-14).
    assert!((39.0..=40.0 + 1e-9).contains(&error.time), "{error:?}");
    assert!(
        matches!(
            error.kind,
            StepErrorKind::System(varmass::core::SystemError::NonPositiveMass { index: 0, .. })
                | StepErrorKind::System(varmass::core::SystemError::SingularMassMatrix)
                | StepErrorKind::NewtonDivergence { .. }
                | StepErrorKind::StepSizeUnderflow { .. }
        ),
        "{error:?}"
    );
    assert!(error.state.iter().all(|x| !x.is_nan()), "{:?}", error.state);
}

/// The phases of a scene: the stiff spring (k = 1e8) until t = 2, then the soft one
/// (k = 1e2, measured silent above) from there to `END`.
fn stiff_then_soft() -> [Pendulum; 2] {
    [pendulum(1e8), pendulum(1e2)]
}

/// The stiffness verdict of Dormand–Prince on the soft spring alone, from the state the
/// stiff phase ends in: what the second phase would report by itself.
fn soft_alone(from: f64, state: SVector<f64, 5>) -> varmass::core::Statistics {
    let soft = pendulum(1e2);
    let control = tolerance(1e-9, AdaptiveControl::default());
    let mut stepper = DormandPrince::new(&soft, from, state, control).unwrap();
    run(&mut stepper, &RunConfig::until(END), &[])
        .unwrap()
        .statistics
}

/// A phased run adds up its phases' work with `Statistics::combine`: the stiffness found
/// in the first phase (about 15 000 stability-limited steps over 2 s, so the test, run
/// every 1000 steps, decides) is still reported after a second phase that finds none.
#[test]
fn the_stiffness_flag_survives_a_phased_run() {
    use varmass::core::{run_phases, Carry, EventAction, Phase};
    let [stiff, soft] = stiff_then_soft();
    let at_two = |t: f64, _: &SVector<f64, 5>| t - 2.0;
    let phases = [
        Phase {
            system: stiff,
            carry: Carry::Separation,
            state_masses: &[],
            until: Some(Event::function(
                &at_two,
                Direction::Rising,
                EventAction::Stop,
            )),
        },
        Phase {
            system: soft,
            carry: Carry::Separation,
            state_masses: &[],
            until: None,
        },
    ];
    let control = tolerance(1e-9, AdaptiveControl::default());
    let phased = run_phases(
        &phases,
        (0.0, start(&phases[0].system)),
        |system, t, state| DormandPrince::new(system, t, state, control),
        &RunConfig::until(END),
    )
    .unwrap();
    let change = phased.changes[0];
    assert!((change.time - 2.0).abs() < 1e-12, "{change:?}");
    let entered = phased.phase.iter().position(|&p| p == 1).unwrap();
    let second = soft_alone(
        phased.solution.times[entered],
        phased.solution.states[entered],
    );
    assert!(!second.stiffness_detected, "{second:?}");
    let all = phased.solution.statistics;
    assert!(all.stiffness_detected, "{all:?}");
}

/// A recording made phase by phase (`observe`, then `Recording::append`) keeps the verdict
/// of a later phase: `append` used to add the counts and drop the later phase's flag. The
/// soft spring from its rest to t = 2, then the stiff one from its own rest (the state
/// need not be continuous for the bookkeeping) to `END`.
#[test]
fn the_stiffness_flag_survives_an_appended_recording() {
    use varmass::core::observe::{observe, Observable};
    let [stiff, soft] = stiff_then_soft();
    let x = |_: f64, s: &SVector<f64, 5>| s[0];
    let observables = [Observable::function("r", &x)];
    let control = tolerance(1e-9, AdaptiveControl::default());
    let mut first = DormandPrince::new(&soft, 0.0, start(&soft), control).unwrap();
    let mut recording = observe(&mut first, &[2.0], &observables).unwrap();
    let soft_work = recording.statistics;
    assert!(!soft_work.stiffness_detected, "{soft_work:?}");
    let mut second = DormandPrince::new(&stiff, 2.0, start(&stiff), control).unwrap();
    let later = observe(&mut second, &[END], &observables).unwrap();
    let stiff_work = later.statistics;
    assert!(stiff_work.stiffness_detected, "{stiff_work:?}");
    recording.append(later);
    let all = recording.statistics;
    assert!(all.stiffness_detected, "{all:?}");
    assert_eq!(
        all.accepted_steps,
        stiff_work.accepted_steps + soft_work.accepted_steps
    );
}
