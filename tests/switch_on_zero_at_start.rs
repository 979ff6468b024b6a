//! A switch standing exactly on zero where a run starts — `abs(y')` or `sign(x')` of a
//! body released from rest — is the switch the start stands on (docs/mechanics.md#switches):
//! the rate there is the kink's (sign(0) = 0), and no first step changes g's sign from 0, so
//! before (review of session 33) the first step took the branch of g = 0 across the kink:
//! - Taylor's series of |a| took the branch of a[0] ≥ 0 (`series::abs`): |y'| = +y' over a
//!   first step on which y' < 0, the drag's sign wrong for that whole (long) step;
//! - RK4's stages straddled sign(x') (0 → + → −) and the step ended with garbage that the
//!   endpoints' signs never flagged.
//!
//! The run now probes the side the motion enters and crosses to it before the first step
//! (`SwitchWatch::leave_zero`).
//!
//! Reference by hand: a mass m falling from rest under gravity g with the drag −k ẏ|ẏ|
//! (ẏ < 0: m ÿ = −m g + k ẏ²) has ẏ(t) = −v_t tanh(g t / v_t), v_t = √(m g / k). With
//! m = 2, g = 9.81, k = 0.5: ẏ(0.5) = −4.099522494300366 m/s. Measured before (`varmass
//! run`, the same core): Taylor at 1e-13 −4.111294220313759 (2.9e-3 off, 5 steps), at 1e-6
//! −4.104790974653824; DOP853 at 1e-13 −4.099522494300344 (5e-15). After: Taylor at 1e-13
//! −4.099522494300363 (8.7e-16).

use varmass::prelude::*;

#[variable_mass_system(
    r#"
    coordinates y
    mass m = m0
    body b: mass m, position [y]
    potential m*g*y
    force b: [-k*y'*abs(y')]
"#,
    emit = ["taylor"]
)]
struct Falling {
    m0: f64,
    g: f64,
    k: f64,
}

#[test]
fn taylor_falls_from_rest_with_quadratic_drag_as_the_closed_form() {
    let body = Falling {
        m0: 2.0,
        g: 9.81,
        k: 0.5,
    };
    let terminal = (body.m0 * body.g / body.k).sqrt();
    let exact = -terminal * (body.g * 0.5 / terminal).tanh();
    let control = TaylorControl::adaptive(Tolerance::new(1e-13, 1e-13).expect("above the floor"));
    let mut stepper = Taylor::new(&body, 0.0, SVector::<f64, 2>::zeros(), control).unwrap();
    let solution = run(&mut stepper, &RunConfig::until(0.5), &[]).unwrap();
    let (t, state) = solution.last().unwrap();
    let v = body.velocity_state(t, state).unwrap()[1];
    // A tolerance of 1e-13 over 0.5 s: 1e-11 is a wide margin (measured 8.7e-16).
    let error = (v - exact).abs() / exact.abs();
    eprintln!("Taylor at 1e-13: ẏ(0.5) = {v}, {error:e} off");
    assert!(error < 1e-11, "ẏ(0.5) = {v}, exact {exact} ({error:e})");
}

#[variable_mass_system(
    r#"
    coordinates x
    mass m = m0
    body b: mass m, position [x]
    force b: [-mu*m*g*sign(x') + a*t]
"#
)]
struct Resting {
    m0: f64,
    mu: f64,
    g: f64,
    a: f64,
}

#[test]
fn rk4_does_not_step_blindly_off_a_switch_on_zero_at_the_start() {
    // A block at rest under Coulomb friction μ m g = 4.905 N and a push a·t (a = 1e-3 N/s) that stays
    // below it until t = 4905 s: by hand it does not move. The model's sign(ẋ) cannot hold
    // it (no static friction): any ẋ ≠ 0 reverses the friction, so the motion chatters on
    // ẋ = 0, and the run must end with `Chattering`, as Dormand–Prince, DOP853, SDIRK4 and
    // Euler do. RK4 at h = 0.25 stepped from ẋ = 0 (g = 0, not a crossing) with stages
    // 0 → + → −, and returned ẋ(4) = −0.196 with x barely moved: no error.
    let block = Resting {
        m0: 1.0,
        mu: 0.5,
        g: 9.81,
        a: 1e-3,
    };
    let mut stepper = ClassicalRk4::new(
        &block,
        0.0,
        SVector::<f64, 2>::zeros(),
        FixedStep { step: 0.25 },
    )
    .unwrap();
    let error = run(&mut stepper, &RunConfig::until(4.0), &[])
        .unwrap_err()
        .error;
    assert!(
        matches!(error.kind, StepErrorKind::Chattering { switch: 0, .. }),
        "{error:?}"
    );
}
