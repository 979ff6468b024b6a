//! Switches located and restarted at (docs/mechanics.md#switches): a burn switched off by
//! `sign` inside one run, a thrust curve of `max` hinges, a Coulomb block that chatters.

use varmass::core::steppers::{AdaptiveControl, StepControl};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::{derive_source, mechanics::Parameters};

/// Both tolerances at `tolerance`, with `defaults` (the method's own factors).
fn control(tolerance: f64, defaults: AdaptiveControl) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..defaults
    })
}

/// A vertical rocket whose burn is switched off at t_b inside the run: the mass rate and
/// the thrust jump to zero where sign(t_b − t) flips. One file for the macro and the
/// interpreter (shared with `tests/taylor_switches.rs`).
const SWITCHED_OFF: &str = include_str!("data/switched_off.vms");

#[variable_mass_system(file = "tests/data/switched_off.vms")]
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

/// The apex by hand: to t_b, m_b = m0 − μ t_b, v_b = u_e ln(m0/m_b) − g t_b and
/// y_b = u_e (t_b − (m_b/μ) ln(m0/m_b)) − g t_b²/2 (Tsiolkovsky with gravity, integrated);
/// then a coast of v_b/g to y_b + v_b²/(2g). Here 188 382.9… m at t = 233.5… s.
fn apex_by_hand() -> (f64, f64) {
    let SwitchedOff { mu, u_e, g, t_b } = BURN;
    let m_b = M0 - mu * t_b;
    let ratio = (M0 / m_b).ln();
    let v_b = u_e * ratio - g * t_b;
    let y_b = u_e * (t_b - m_b / mu * ratio) - 0.5 * g * t_b * t_b;
    (t_b + v_b / g, y_b + v_b * v_b / (2.0 * g))
}

/// The apex of one run (burn and coast) at tolerance 1e-12: an event on p = 0 falling.
fn apex<St: Stepper<1, 3>>(stepper: &mut St, config: &RunConfig) -> (f64, f64) {
    let apex = Event::state_reaches(1, 0.0, Direction::Falling);
    let solution = run(stepper, config, &[apex]).expect("the flight runs");
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let (time, state) = solution.last().expect("points");
    (time, state[0])
}

#[test]
fn the_generated_rocket_has_one_switch_named_by_its_text() {
    assert_eq!(BURN.switch_count(), 1);
    assert_eq!(BURN.switch_name(0), Some("t_b - t"));
    let mut g = [0.0];
    BURN.switching_functions(12.5, &SVector::from([0.0, 0.0, M0]), &mut g);
    assert_eq!(g, [47.5]);
}

/// The first case, at tolerance 1e-12. Measured relative apex errors (height):
/// Dormand–Prince 3.1e-14 with switches located, 3.3e-11 stepping across; DOP853 1.8e-13
/// located (its burn alone carries that: v is 1.75e-13 off at t = 59.99 s, before the
/// switch; `dop853_loses_nothing_at_the_switch` shows the two-run form misses by as much)
/// and 3.9e-11 across, 1.2e-14 located at tolerance 1e-13. Bounds:
/// 1e-13 (the issue's) for Dormand–Prince and for DOP853 at 1e-13, 2.5e-13 for DOP853 at
/// 1e-12; the runs stepping across must miss 1e-13.
#[test]
fn a_burn_switched_off_by_sign_reaches_the_closed_form_apex() {
    let (t_apex, y_apex) = apex_by_hand();
    let start = SVector::from([0.0, 0.0, M0]);
    let dp = |tol| DormandPrince::new(&BURN, 0.0, start, control(tol, AdaptiveControl::default()));
    let dop = |tol| Dop853::new(&BURN, 0.0, start, control(tol, AdaptiveControl::dop853()));
    let config = RunConfig::until(1e4);
    let located = [
        (
            "Dormand–Prince",
            apex(&mut dp(1e-12).unwrap(), &config),
            1e-13,
        ),
        ("DOP853", apex(&mut dop(1e-12).unwrap(), &config), 2.5e-13),
        (
            "DOP853 at 1e-13",
            apex(&mut dop(1e-13).unwrap(), &config),
            1e-13,
        ),
    ];
    for (name, (time, height), bound) in located {
        let error = (height - y_apex).abs() / y_apex;
        eprintln!("{name}: apex error {error:e}, time {:e}", time - t_apex);
        assert!(error <= bound, "{name}: {error:e}");
        assert!((time - t_apex).abs() < 1e-9, "{name}: t = {time}");
    }
    let across = RunConfig::until(1e4).without_switching();
    let stepped_across = [
        ("Dormand–Prince", apex(&mut dp(1e-12).unwrap(), &across)),
        ("DOP853", apex(&mut dop(1e-12).unwrap(), &across)),
    ];
    for (name, (_, height)) in stepped_across {
        let error = (height - y_apex).abs() / y_apex;
        eprintln!("{name} without switching: apex error {error:e}");
        assert!(
            error > 1e-13,
            "{name} stepped across and still hit: {error:e}"
        );
    }
}

/// Why DOP853 misses 1e-13 at tolerance 1e-12 (item 1 of issue 20 asks for it): not the
/// switch. The same flight run in two pieces that never meet a switch — the burn with
/// t_b out of reach, stopped at t = 60 s by the end time, then the coast (t_b = 0) from
/// that state — reaches the same apex to within a few roundings of the one-run form,
/// and the same distance from the closed form: DOP853's global error on the smooth burn at
/// this tolerance, which the switch neither adds to nor could remove. Measured (apex
/// height, relative): one run 1.81e-13, two runs 1.85e-13, their difference 4.2e-15;
/// bound on the difference 1e-14 (and DOP853 at 1e-13 meets 1e-13: 1.2e-14, above).
#[test]
fn dop853_loses_nothing_at_the_switch() {
    let (_, y_apex) = apex_by_hand();
    let start = SVector::from([0.0, 0.0, M0]);
    let ctl = || control(1e-12, AdaptiveControl::dop853());
    let mut one = Dop853::new(&BURN, 0.0, start, ctl()).unwrap();
    let (_, one_run) = apex(&mut one, &RunConfig::until(1e4));
    let burning = SwitchedOff { t_b: 1e9, ..BURN };
    let coasting = SwitchedOff { t_b: 0.0, ..BURN };
    let mut burn = Dop853::new(&burning, 0.0, start, ctl()).unwrap();
    let burnt = run(&mut burn, &RunConfig::until(BURN.t_b), &[]).expect("the burn runs");
    let (t_b, at_burnout) = burnt.last().expect("points");
    assert_eq!(t_b, BURN.t_b);
    let mut coast = Dop853::new(&coasting, t_b, *at_burnout, ctl()).unwrap();
    let (_, two_runs) = apex(&mut coast, &RunConfig::until(1e4));
    let (one_error, two_error) = (
        (one_run - y_apex).abs() / y_apex,
        (two_runs - y_apex).abs() / y_apex,
    );
    let difference = (one_run - two_runs).abs() / y_apex;
    eprintln!(
        "DOP853 at 1e-12: one run {one_error:e}, two runs {two_error:e}, difference \
         {difference:e}"
    );
    assert!(difference <= 1e-14, "{difference:e}");
}

/// The run-time interpreter finds the same switch as the macro, and a run of the tapes
/// lands on it as well.
#[test]
fn the_interpreter_has_the_same_switch() {
    let derivation = derive_source(SWITCHED_OFF, Parameters::Inferred).expect("derives");
    let values = [("mu", 10.0), ("u_e", 2500.0), ("g", 9.81), ("t_b", 60.0)];
    let system = TapeSystem::<1, 3>::new(Program::new(derivation, &values).unwrap()).unwrap();
    assert_eq!(system.switch_count(), 1);
    assert_eq!(system.switch_name(0), Some("t_b - t"));
    let mut g = [0.0];
    system.switching_functions(12.5, &SVector::from([0.0, 0.0, M0]), &mut g);
    assert_eq!(g, [47.5]);
    let start = SVector::from([0.0, 0.0, M0]);
    let control = control(1e-12, AdaptiveControl::default());
    let mut stepper = DormandPrince::new(&system, 0.0, start, control).unwrap();
    let (_, height) = apex(&mut stepper, &RunConfig::until(1e4));
    let (_, y_apex) = apex_by_hand();
    // Measured 1.5e-16 as the generated code; bound 1e-13.
    assert!((height - y_apex).abs() / y_apex <= 1e-13, "{height}");
}

/// A thrust curve of `max` hinges: F rises at s1 to F1 = s1 t1 at t1, holds to t2, falls at
/// s2 to zero at t3 = t2 + F1/s2, and stays zero; the mass flow is F/u_e.
#[variable_mass_system(
    "coordinates y
let F = s1*(t - max(0, t - t1)) - s2*(max(0, t - t2) - max(0, t - t3))
mass m: state, rate -F/u_e
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate F/u_e, relative_velocity [-u_e]"
)]
struct Hinged {
    s1: f64,
    s2: f64,
    t1: f64,
    t2: f64,
    t3: f64,
    u_e: f64,
    g: f64,
}

const CURVE: Hinged = Hinged {
    s1: 15_000.0,
    s2: 6_000.0,
    t1: 2.0,
    t2: 20.0,
    t3: 25.0,
    u_e: 2000.0,
    g: 9.81,
};

/// The impulse I(t) = ∫₀ᵗ F, the trapezoids of the curve by hand: s1 t²/2 to t1, then
/// F1 (t − t1), then F1 (t − t2) − s2 (t − t2)²/2 to t3, constant after.
fn impulse(t: f64) -> f64 {
    let Hinged {
        s1, s2, t1, t2, t3, ..
    } = CURVE;
    let f1 = s1 * t1;
    let rise = |t: f64| 0.5 * s1 * t.min(t1).powi(2);
    let hold = |t: f64| f1 * (t.clamp(t1, t2) - t1);
    let fall = |t: f64| {
        let d = t.clamp(t2, t3) - t2;
        f1 * d - 0.5 * s2 * d * d
    };
    rise(t) + hold(t) + fall(t)
}

/// The second case: at every point of a run at tolerance 1e-8, m(t) = m0 − I(t)/u_e
/// and v(t) = u_e ln(m0/m(t)) − g t (constant exhaust speed, vertical flight). Measured
/// relative errors (v against max(|v|, 1 m/s)): Dormand–Prince 3.4e-16 (m) and 5.0e-11 (v);
/// DOP853 1.7e-16 and 9.1e-13; Dormand–Prince stepping across the kinks 4.0e-8 and 1.8e-6.
/// Bound 1e-10 as the issue asks.
#[test]
fn a_thrust_curve_of_max_hinges_is_integrated_to_the_tolerance() {
    let Hinged { u_e, g, .. } = CURVE;
    let start = SVector::from([0.0, 0.0, M0]);
    let dp_control = || control(1e-8, AdaptiveControl::default());
    let dp = DormandPrince::new(&CURVE, 0.0, start, dp_control());
    let dp_across = DormandPrince::new(&CURVE, 0.0, start, dp_control());
    let dop = Dop853::new(&CURVE, 0.0, start, control(1e-8, AdaptiveControl::dop853()));
    let config = RunConfig::until(30.0);
    let across = RunConfig::until(30.0).without_switching();
    let solutions = [
        ("Dormand–Prince", run(&mut dp.unwrap(), &config, &[]), 1e-10),
        ("DOP853", run(&mut dop.unwrap(), &config, &[]), 1e-10),
        (
            "Dormand–Prince across",
            run(&mut dp_across.unwrap(), &across, &[]),
            1.0,
        ),
    ];
    assert_eq!(CURVE.switch_count(), 3);
    for (name, solution, bound) in solutions {
        let solution = solution.expect("the flight runs");
        let (mut worst_m, mut worst_v): (f64, f64) = (0.0, 0.0);
        for (&t, state) in solution.times.iter().zip(&solution.states).skip(1) {
            let m = M0 - impulse(t) / u_e;
            let v = u_e * (M0 / m).ln() - g * t;
            worst_m = worst_m.max((state[2] - m).abs() / m);
            // Relative to |v| or 1 m/s: v starts from rest.
            worst_v = worst_v.max((state[1] / state[2] - v).abs() / v.abs().max(1.0));
        }
        eprintln!("{name}: m {worst_m:e}, v {worst_v:e}");
        assert!(
            worst_m <= bound && worst_v <= bound,
            "{name}: {worst_m:e} {worst_v:e}"
        );
        if bound == 1.0 {
            assert!(
                worst_v > 1e-10,
                "{name} stepped across and hit: {worst_v:e}"
            );
        }
    }
}

/// A block pushed by F below its breakaway force μ m g, sliding at first: Coulomb friction
/// `-mu_k*m*g*sign(x')` stops it at t* = v0/(μ g − F/m) and then chatters about x' = 0.
#[variable_mass_system(
    "coordinates x
mass m = m0
body block: mass m, position [x]
force block: [push - mu_k*m*g*sign(x')]"
)]
struct Coulomb {
    m0: f64,
    push: f64,
    mu_k: f64,
    g: f64,
}

/// The chattering case: the run ends with the typed error naming switch 0, `x'`,
/// at the stop t* = 1/(0.5·9.81 − 2) = 0.3442… s (v0 = 1), within a bounded number of steps
/// (measured: 76 accepted and 89 rejected steps for Dormand–Prince; bound 200).
#[test]
fn coulomb_friction_at_rest_is_a_chattering_error() {
    let block = Coulomb {
        m0: 1.0,
        push: 2.0,
        mu_k: 0.5,
        g: 9.81,
    };
    assert_eq!(block.switch_name(0), Some("x'"));
    let t_stop = 1.0 / (0.5 * 9.81 - 2.0);
    let start = SVector::from([0.0, 1.0]);
    let mut stepper = DormandPrince::new(
        &block,
        0.0,
        start,
        control(1e-10, AdaptiveControl::default()),
    )
    .unwrap();
    let config = RunConfig {
        max_steps: 10_000,
        ..RunConfig::until(10.0)
    };
    let Err(failure) = run(&mut stepper, &config, &[]) else {
        panic!("the block ran to the end");
    };
    let StepErrorKind::Chattering {
        switch,
        crossings,
        within,
    } = failure.kind
    else {
        panic!("expected chattering, got {}", failure.error);
    };
    assert_eq!(switch, 0);
    assert_eq!(crossings, Switching::default().chatter_crossings);
    assert!(within <= 1e-8, "{within:e}");
    eprintln!(
        "stop {:e} off, {:?}",
        failure.time - t_stop,
        stepper.statistics()
    );
    // The crossings after the stop drift by a tangent root each: measured 1.3e-8 s.
    assert!((failure.time - t_stop).abs() < 3e-8, "t = {}", failure.time);
    let work = stepper.statistics();
    assert!(work.accepted_steps + work.rejected_steps < 200, "{work:?}");
    // The run before the stop is kept: the block slides on v = v0 − (μ g − F/m) t.
    let (last, state) = failure.partial.last().expect("points");
    assert!(
        last <= failure.time && state[1].abs() < 1e-9,
        "{last}: {state:?}"
    );
}
