//! Inputs from code (issue 21 item 5, docs/inputs.md): a hovering rocket whose PD
//! altitude-hold autopilot is an `input` written in Rust equals the same rocket with the
//! law written in the DSL.
//!
//! The rocket (y up, mass m burning at ṁ = −F/u_e, thrust F = m u with u the commanded
//! acceleration): Meshchersky gives m ÿ = F − m g, so ÿ = u − g. With the PD law
//! u = g + kp (y_ref − y) − kd ẏ the altitude is the damped oscillator
//! ÿ + kd ẏ + kp (y − y_ref) = 0 and the mass m(t) = m₀ exp(−∫u dt/u_e). Both systems below
//! derive exactly these equations; the input's only difference is who computes u.

use varmass::core::nalgebra::{SVector, Vector3};
use varmass::core::steppers::{AdaptiveControl, DormandPrince, FixedStep, Sdirk4, StepControl};
use varmass::core::{run, RunConfig, Solution, Stepper, VariableMassSystem};
use varmass::prelude::variable_mass_system;

/// The law as an input: `HoverInputs::u` below.
#[variable_mass_system(
    r#"
    coordinates y
    input u(t, y, y')
    mass m: state, rate -m*u(t, y, y')/u_e
    body rocket: mass m, position [y]
    potential m*g*y
    outflow rocket: rate m*u(t, y, y')/u_e, relative_velocity [-u_e]
"#
)]
struct Hover {
    u_e: f64,
    g: f64,
}

/// The PD gains and the altitude held.
const KP: f64 = 4.0;
const KD: f64 = 2.5;
const Y_REF: f64 = 10.0;

impl HoverInputs for Hover {
    fn u(&self, _t: f64, y: f64, y_dot: f64) -> f64 {
        self.g + KP * (Y_REF - y) - KD * y_dot
    }
}

/// The same law in the DSL.
#[variable_mass_system(
    r#"
    coordinates y
    let u = g + kp*(y_ref - y) - kd*y'
    mass m: state, rate -m*u/u_e
    body rocket: mass m, position [y]
    potential m*g*y
    outflow rocket: rate m*u/u_e, relative_velocity [-u_e]
"#
)]
struct HoverDsl {
    u_e: f64,
    g: f64,
    kp: f64,
    kd: f64,
    y_ref: f64,
}

const U_E: f64 = 2000.0;
const G: f64 = 9.80665;
const M0: f64 = 50.0;
const END: f64 = 15.0;

fn systems() -> (Hover, HoverDsl) {
    let hover = Hover { u_e: U_E, g: G };
    let dsl = HoverDsl {
        u_e: U_E,
        g: G,
        kp: KP,
        kd: KD,
        y_ref: Y_REF,
    };
    (hover, dsl)
}

/// On the ground at rest: [y, p, m].
fn start() -> SVector<f64, 3> {
    Vector3::new(0.0, 0.0, M0)
}

/// Fixed steps of 5 ms, so that both flights take the very same steps (adaptive steps would
/// differ at rounding, through error estimates that differ at rounding).
fn fixed() -> StepControl {
    StepControl::Fixed(FixedStep { step: 0.005 })
}

fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance: 1e-10,
        ..AdaptiveControl::default()
    })
}

fn flight<St: Stepper<1, 3>>(mut stepper: St) -> Solution<1, 3> {
    run(&mut stepper, &RunConfig::until(END), &[]).unwrap()
}

/// The largest difference of the two flights' states, relative to each component's
/// largest magnitude, over points at the same times.
fn largest_difference(a: &Solution<1, 3>, b: &Solution<1, 3>) -> f64 {
    assert_eq!(a.times, b.times, "the two flights take the same steps");
    let mut scale = [0.0_f64; 3];
    for s in &a.states {
        for (k, x) in s.iter().enumerate() {
            scale[k] = scale[k].max(x.abs());
        }
    }
    let mut worst = 0.0_f64;
    for (x, y) in a.states.iter().zip(&b.states) {
        for k in 0..3 {
            worst = worst.max((x[k] - y[k]).abs() / scale[k]);
        }
    }
    worst
}

#[test]
fn the_input_and_the_dsl_law_fly_the_same_15_s() {
    let (hover, dsl) = systems();
    let a = flight(DormandPrince::new(&hover, 0.0, start(), fixed()).unwrap());
    let b = flight(DormandPrince::new(&dsl, 0.0, start(), fixed()).unwrap());
    // The flight is the one intended: near y_ref after 15 s (the oscillator's decay rate
    // kd/2 = 1.25/s leaves 10·e^(−18.75) ≈ 7e-8 m; the tolerance adds ~1e-9).
    let last = a.states.last().unwrap();
    assert!((last[0] - Y_REF).abs() < 1e-6, "y(15) = {}", last[0]);
    assert!(last[2] < M0, "the rocket burnt propellant");
    // Measured 1.2e-16 (relative to each component's largest value); the bound is the
    // issue's 1e-13.
    let difference = largest_difference(&a, &b);
    assert!(difference <= 1e-13, "{difference:e}");
}

#[test]
fn the_jacobian_of_the_input_system_drives_an_implicit_stepper() {
    // SDIRK4 iterates Newton on the Jacobian, which differentiates the input by the
    // default central differences of `HoverInputs::u_partials`: the Newton iterations
    // converge to the same stages, so the flight matches the DSL law's (whose Jacobian is
    // exact) to well within the tolerance 1e-10: measured 3.8e-13 (largest component of the
    // end states, y ≈ 10 m, m ≈ 46 kg); bound 1e-11, a margin of 26.
    let (hover, dsl) = systems();
    let a = flight(Sdirk4::new(&hover, 0.0, start(), control()).unwrap());
    let b = flight(Sdirk4::new(&dsl, 0.0, start(), control()).unwrap());
    let last = (a.states.last().unwrap(), b.states.last().unwrap());
    let difference = (last.0 - last.1).abs().max();
    assert!(difference <= 1e-11, "{difference:e}");
}

#[test]
fn the_generated_rate_calls_the_input() {
    // At y = 2, ẏ = 1 (p = m ẏ): ÿ = kp (y_ref − y) − kd ẏ = 4·8 − 2.5 = 29.5, and
    // ṁ = −m u/u_e with u = g + 29.5.
    let (hover, _) = systems();
    let state = Vector3::new(2.0, M0, M0);
    let rate = hover.state_rate(0.0, &state).unwrap();
    let u = G + 29.5;
    assert!((rate[2] + M0 * u / U_E).abs() <= 1e-12, "{}", rate[2]);
}

#[test]
fn the_taylor_stepper_refuses_an_input_with_a_typed_error() {
    // No recurrence exists for the user's function: the Taylor tape gives NaN coefficients
    // for an input, so the stepper stops with NonFiniteState instead of a wrong series.
    use varmass::core::steppers::{Taylor, TaylorControl};
    use varmass::core::StepErrorKind;
    #[variable_mass_system(
        r#"
        coordinates y
        input u(t, y, y')
        mass m: state, rate -m*u(t, y, y')/u_e
        body rocket: mass m, position [y]
        potential m*g*y
        outflow rocket: rate m*u(t, y, y')/u_e, relative_velocity [-u_e]
    "#,
        emit = ["taylor"]
    )]
    struct HoverTaylor {
        u_e: f64,
        g: f64,
    }
    impl HoverTaylorInputs for HoverTaylor {
        fn u(&self, _t: f64, y: f64, y_dot: f64) -> f64 {
            self.g + KP * (Y_REF - y) - KD * y_dot
        }
    }
    let hover = HoverTaylor { u_e: U_E, g: G };
    let error = match Taylor::new(&hover, 0.0, start(), TaylorControl::default()) {
        Err(error) => error,
        Ok(mut stepper) => {
            run(&mut stepper, &RunConfig::until(END), &[])
                .unwrap_err()
                .error
        }
    };
    assert!(
        matches!(error.kind, StepErrorKind::NonFiniteState),
        "{error}"
    );
    assert_eq!(error.time, 0.0);
}
