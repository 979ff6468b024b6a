//! `emit = []`: a system with only what the steppers need. It runs the paper's sled to the
//! closed form of eq. 24, its state rate is the full system's, and the trait's defaults
//! that replace the left-out methods agree with the full system's closed forms.

use varmass::prelude::*;

#[variable_mass_system(file = "models/sled.vms", with = ["impact"], emit = [])]
struct MinimalSled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

#[variable_mass_system(file = "models/sled.vms", with = ["impact"])]
struct FullSled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

const M0: f64 = 10.0;
const C: f64 = 2.0;
const G: f64 = 9.81;
const F_D: f64 = 0.1;

fn minimal() -> MinimalSled {
    MinimalSled {
        m0: M0,
        c: C,
        g: G,
        theta: 30f64.to_radians(),
        f_d: F_D,
    }
}

fn full() -> FullSled {
    FullSled {
        m0: M0,
        c: C,
        g: G,
        theta: 30f64.to_radians(),
        f_d: F_D,
    }
}

/// v(x) of eq. 24 in its stable form, ε = c x / m0: v² = (2/3) a x (3 + 3ε + ε²)/(1 + ε)².
fn exact_speed(x: f64) -> f64 {
    let theta = 30f64.to_radians();
    let a = G * (theta.sin() - F_D * theta.cos());
    let eps = C * x / M0;
    (2.0 / 3.0 * a * x * (3.0 + 3.0 * eps + eps * eps) / ((1.0 + eps) * (1.0 + eps))).sqrt()
}

#[test]
fn the_minimal_sled_reaches_the_closed_form() {
    let sled = minimal();
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-13,
        ..AdaptiveControl::default()
    });
    let start = SVector::<f64, 2>::zeros();
    let mut stepper = DormandPrince::new(&sled, 0.0, start, control).expect("valid start");
    let at_50_m = Event::state_reaches(0, 50.0, Direction::Rising);
    let solution = run(&mut stepper, &RunConfig::until(100.0), &[at_50_m]).expect("runs");
    let mut worst: f64 = 0.0;
    for (&t, state) in solution.times.iter().zip(&solution.states) {
        if state[0] >= 1.0 {
            let v = sled.velocities(t, state).expect("regular")[0];
            worst = worst.max((v - exact_speed(state[0])).abs() / exact_speed(state[0]));
        }
    }
    let (_, last) = solution.last().expect("a point");
    assert!((last[0] - 50.0).abs() < 1e-9, "stopped at x = {}", last[0]);
    // Measured: 2.5e-14 (as the full system's Dormand–Prince run in the sled example).
    assert!(worst < 1e-9, "worst relative error of v: {worst:e}");
}

#[test]
fn the_defaults_stand_in_for_the_left_out_methods() {
    let (small, big) = (minimal(), full());
    let mut worst_rate: f64 = 0.0;
    let mut worst_h: f64 = 0.0;
    let mut worst_power: f64 = 0.0;
    let mut worst_jacobian: f64 = 0.0;
    for k in 1..=20 {
        let x = 2.5 * k as f64;
        let state = SVector::<f64, 2>::new(x, (M0 + C * x) * exact_speed(x));
        let rate = small.state_rate(0.0, &state).expect("regular");
        worst_rate = worst_rate.max((rate - big.state_rate(0.0, &state).expect("regular")).norm());
        let h = big.hamiltonian(0.0, &state).expect("regular");
        worst_h =
            worst_h.max((small.hamiltonian(0.0, &state).expect("regular") - h).abs() / h.abs());
        let power = big.power(0.0, &state).expect("regular");
        worst_power = worst_power
            .max((small.power(0.0, &state).expect("regular") - power).abs() / power.abs());
        let jacobian = big.jacobian(0.0, &state).expect("regular");
        let difference = small.jacobian(0.0, &state).expect("regular") - jacobian;
        worst_jacobian = worst_jacobian.max(difference.norm() / jacobian.norm());
    }
    // The same generated state rate: bitwise.
    assert_eq!(worst_rate, 0.0);
    // H = p·q̇ − L from q̇(q, p) against the closed form: measured 2.1e-16; bound 1e-13.
    assert!(worst_h < 1e-13, "H {worst_h:e}");
    // Central differences (step ε^(1/3) of the scale): measured 1.4e-10 (power) and
    // 4.0e-11 (Jacobian, relative in norm); bound 1e-8, a margin of ~100.
    assert!(worst_power < 1e-8, "power {worst_power:e}");
    assert!(worst_jacobian < 1e-8, "Jacobian {worst_jacobian:e}");
}
