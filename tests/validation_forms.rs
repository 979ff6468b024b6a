//! Hamilton form against Lagrange form: the run on the state [q, p, m_s] with the true
//! momentum rate (docs/mechanics.md#true-momentum-rate) and a run on the velocity state [q, q̇, m_s] with the generated
//! Lagrange-form accelerations q̈ (eq. 6 with the frozen-mass rule) trace the same motion.
//! Also the polar and Cartesian forms of the leaking pendulum trace the same bob path.

mod validation_support;

use validation_support::{pendulums, tight, Rocket, Sled};
use varmass::prelude::*;

/// Classical RK4 on the velocity state [q, q̇, m_s] with rate [q̇, q̈(q, q̇, t), ṁ_s], written
/// here independently of the library's steppers. Returns the velocity states at every step.
fn lagrange_rk4<Sys, const N: usize, const S: usize>(
    system: &Sys,
    start: SVector<f64, S>,
    step: f64,
    steps: usize,
) -> Vec<SVector<f64, S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let rate = |t: f64, v: &SVector<f64, S>| {
        let acceleration = system.accelerations(t, v).unwrap();
        let mut out = SVector::<f64, S>::zeros();
        for a in 0..N {
            out[a] = v[N + a];
            out[N + a] = acceleration[a];
        }
        for k in 0..S - 2 * N {
            out[2 * N + k] = system.mass_rate(k, t, v);
        }
        out
    };
    let mut states = vec![start];
    let mut v = start;
    for i in 0..steps {
        let t = i as f64 * step;
        let k1 = rate(t, &v);
        let k2 = rate(t + 0.5 * step, &(v + k1 * (0.5 * step)));
        let k3 = rate(t + 0.5 * step, &(v + k2 * (0.5 * step)));
        let k4 = rate(t + step, &(v + k3 * step));
        v += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (step / 6.0);
        states.push(v);
    }
    states
}

/// Runs the library's RK4 on [q, p, m_s] and the local Lagrange-form RK4 with the same step
/// and returns the largest difference of the velocity states, per component, scaled by
/// `scales`.
fn hamilton_vs_lagrange<Sys, const N: usize, const S: usize>(
    system: &Sys,
    velocity_start: SVector<f64, S>,
    step: f64,
    steps: usize,
    scales: SVector<f64, S>,
) -> f64
where
    Sys: VariableMassSystem<N, S>,
{
    let start = system.momentum_state(0.0, &velocity_start);
    let mut stepper = ClassicalRk4::new(system, 0.0, start, FixedStep { step }).unwrap();
    let end = step * steps as f64;
    let solution = run(&mut stepper, &RunConfig::until(end), &[]).unwrap();
    let lagrange = lagrange_rk4(system, velocity_start, step, steps);
    assert_eq!(solution.states.len(), lagrange.len());
    let mut worst: f64 = 0.0;
    for ((&t, state), velocity_state) in solution.times.iter().zip(&solution.states).zip(&lagrange)
    {
        let hamilton = system.velocity_state(t, state).unwrap();
        let difference = (hamilton - velocity_state).component_div(&scales);
        worst = worst.max(difference.amax());
    }
    worst
}

// Both runs are fourth order with the same step, so they differ by O(h⁴) of the two
// discretisations' error constants: with h = 1e-3 (and ~10 steps per period or more) each
// is within ~1e-10 of the exact motion (the example's RK4 at 1e-3 is 1e-9 m from the
// reference after 30 s), so 1e-8 of each component's scale leaves a wide margin while a
// wrong term (e.g. a missing ṁ ∂*p/∂m, an O(μ) change) would show at 1e-3 or more.
const ASSERTED: f64 = 1e-8;

#[test]
fn sled_hamilton_and_lagrange_agree() {
    let sled = Sled::paper();
    // Start moving (x = 0.5 m, v = 2 m/s) so q̇ is not zero; 5 s reaches x ≈ 40 m.
    let start = SVector::<f64, 2>::new(0.5, 2.0);
    let worst = hamilton_vs_lagrange(&sled, start, 1e-3, 5_000, SVector::from([50.0, 12.0]));
    assert!(worst < ASSERTED, "{worst:e}");
}

#[test]
fn rocket_hamilton_and_lagrange_agree() {
    let rocket = Rocket {
        mu: 10.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1000.0);
    let scales = SVector::from([2e5, 5e3, 1e3]);
    let worst = hamilton_vs_lagrange(&rocket, start, 1e-2, 8_000, scales);
    assert!(worst < ASSERTED, "{worst:e}");
}

#[test]
fn leaking_pendulum_hamilton_and_lagrange_agree() {
    let (polar, _) = pendulums();
    let start = SVector::<f64, 5>::from([1.1, 0.5, 0.0, 0.0, 2.0]);
    // 10 s: m goes from 2 to 1.5 kg, ~20 spring periods.
    let scales = SVector::from([1.0, 1.0, 5.0, 5.0, 2.0]);
    let worst = hamilton_vs_lagrange(&polar, start, 1e-3, 10_000, scales);
    assert!(worst < ASSERTED, "{worst:e}");
}

#[test]
fn leaking_pendulum_polar_and_cartesian_agree() {
    // The polar equations carry ṁ r² θ̇ and the jet's torque μ u_e r; the Cartesian ones
    // neither. The same bob path is a check of the frozen-mass rule under a change of
    // coordinates. Both at tolerance 1e-12 over 30 s: the example measures 7e-12 m.
    let (polar, cartesian) = pendulums();
    let (r0, theta0, m0) = (1.1, 0.5, 2.0);
    let end = 30.0;
    let mut stepper = DormandPrince::new(
        &polar,
        0.0,
        SVector::from([r0, theta0, 0.0, 0.0, m0]),
        tight(1e-12),
    )
    .unwrap();
    let polar_run = run(&mut stepper, &RunConfig::until(end), &[]).unwrap();
    let start = SVector::from([r0 * theta0.sin(), -r0 * theta0.cos(), 0.0, 0.0, m0]);
    let mut stepper = DormandPrince::new(&cartesian, 0.0, start, tight(1e-12)).unwrap();
    let cartesian_run = run(&mut stepper, &RunConfig::until(end), &[]).unwrap();
    // The two runs take different steps, so compare where both land exactly: the end.
    let (_, p) = polar_run.last().unwrap();
    let (_, c) = cartesian_run.last().unwrap();
    let bob = (p[0] * p[1].sin(), -p[0] * p[1].cos());
    let distance = (bob.0 - c[0]).hypot(bob.1 - c[1]);
    assert!(distance < 1e-9, "bob positions differ by {distance:e} m");
    // The velocities: ẋ = ṙ sin θ + r θ̇ cos θ, ẏ = −ṙ cos θ + r θ̇ sin θ.
    let pv = polar.velocity_state(end, p).unwrap();
    let cv = cartesian.velocity_state(end, c).unwrap();
    let (r, th, rdot, thdot) = (pv[0], pv[1], pv[2], pv[3]);
    let velocity = (
        rdot * th.sin() + r * thdot * th.cos(),
        -rdot * th.cos() + r * thdot * th.sin(),
    );
    let speed_difference = (velocity.0 - cv[2]).hypot(velocity.1 - cv[3]);
    assert!(speed_difference < 1e-8, "{speed_difference:e} m/s");
    // m is linear in t, so each step is exact but for rounding (~1e-16 over ~16000 steps).
    assert!((p[4] - c[4]).abs() < 1e-12);
}

#[test]
fn literal_eq_19_is_detected_by_the_lagrange_form() {
    // A control: the Lagrange form is sensitive to the mass-flux term. Removing it (the
    // variational stepper's LiteralEq19, which docs/mechanics.md#corrected-hamilton-principle shows to be wrong) moves the sled by far
    // more than the tolerance above, so agreement is not automatic.
    use varmass::core::steppers::{Principle, VariationalConfig};
    let sled = Sled::paper();
    let start = SVector::<f64, 2>::new(0.5, 2.0 * (sled.m0 + sled.c * 0.5));
    let literal = VariationalConfig {
        step: 1e-3,
        principle: Principle::LiteralEq19,
        ..VariationalConfig::default()
    };
    let mut stepper = Variational::new(&sled, 0.0, start, literal).unwrap();
    let wrong = run(&mut stepper, &RunConfig::until(5.0), &[]).unwrap();
    let lagrange = lagrange_rk4(&sled, SVector::from([0.5, 2.0]), 1e-3, 5_000);
    let (_, end) = wrong.last().unwrap();
    let right = lagrange.last().unwrap();
    assert!(
        (end[0] - right[0]).abs() > 1.0,
        "{} vs {}",
        end[0],
        right[0]
    );
}
