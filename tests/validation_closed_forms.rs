//! Every closed form of docs/mechanics.md#reference-solutions against runs of the generated systems: the sled's v(x)
//! (eq. 24), the vertical rocket's y(t) and v(t), Tsiolkovsky in free space, and the
//! constant-mass limits, which must be ordinary mechanics.

mod validation_support;

use validation_support::{relative, tight, Oscillator, Rocket, Sled};
use varmass::prelude::*;

/// Dormand–Prince at tolerance 1e-13: the error per step is held at about 1e-13 relative,
/// and the sled and the rocket take a few hundred steps, so even a worst-case sum of local
/// errors stays near 1e-11. Each test bounds its errors at about ten times what it measured
/// (stated beside each bound), so that a regression by an order of magnitude fails; motions
/// that Dormand–Prince integrates exactly (polynomials of degree ≤ 5 in t) are held to a few
/// roundings.
const TOLERANCE: f64 = 1e-13;

/// Runs the sled from rest to x = 50 m and returns the worst relative error of v against
/// eq. 24 over the accepted points with x ≥ 1 m, and at the stopping event.
fn sled_error(sled: &Sled) -> (f64, f64) {
    let mut stepper = DormandPrince::new(sled, 0.0, SVector::zeros(), tight(TOLERANCE)).unwrap();
    let at_50_m = Event::state_reaches(0, 50.0, Direction::Rising);
    let solution = run(&mut stepper, &RunConfig::until(1e3), &[at_50_m]).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let error = |t: f64, s: &SVector<f64, 2>| {
        relative(sled.velocities(t, s).unwrap()[0], sled.exact_speed(s[0]))
    };
    // From 1 m on: v ∝ √x near the start turns an error δx into δx/(2x) in v(x), which no
    // method can avoid as x → 0.
    let worst = solution
        .times
        .iter()
        .zip(&solution.states)
        .filter(|(_, s)| s[0] >= 1.0)
        .map(|(&t, s)| error(t, s))
        .fold(0.0, f64::max);
    let (t, end) = solution.last().unwrap();
    assert!((end[0] - 50.0).abs() < 1e-9, "stopped at x = {}", end[0]);
    (worst, error(t, end))
}

#[test]
fn sled_speed_matches_eq_24() {
    let (worst, at_end) = sled_error(&Sled::paper());
    // Measured 2.5e-14 over the run and 6.8e-15 at 50 m.
    assert!(worst < 2.5e-13, "max relative error {worst:e}");
    assert!(at_end < 7e-14, "relative error at 50 m {at_end:e}");
}

#[test]
fn sled_without_accretion_is_the_constant_mass_sled() {
    // c = 0: the stable form reduces to v² = 2 a x, so compare with that directly.
    let sled = Sled {
        c: 0.0,
        ..Sled::paper()
    };
    let mut stepper = DormandPrince::new(&sled, 0.0, SVector::zeros(), tight(TOLERANCE)).unwrap();
    let at_50_m = Event::state_reaches(0, 50.0, Direction::Rising);
    let solution = run(&mut stepper, &RunConfig::until(1e3), &[at_50_m]).unwrap();
    let a = sled.acceleration();
    // Constant acceleration from rest: x = a t²/2, p = m0 a t, which a fifth-order method
    // integrates exactly; measured at most 3.3e-16 relative (x, p and v²), 4e-15 asserted.
    let rounding = 4e-15;
    for (&t, s) in solution.times.iter().zip(&solution.states) {
        if t > 0.0 {
            assert!(relative(s[0], 0.5 * a * t * t) < rounding, "x at t = {t}");
            assert!(relative(s[1], sled.m0 * a * t) < rounding, "p at t = {t}");
        }
        if s[0] >= 1.0 {
            let v = s[1] / sled.m0;
            assert!(
                relative(v * v, 2.0 * a * s[0]) < rounding,
                "v² at x = {}",
                s[0]
            );
        }
    }
}

#[test]
fn sled_equations_reduce_to_ordinary_mechanics_when_c_is_zero() {
    // Exactly (to rounding): the generated state rate with c = 0 is Newton's m ẍ = m a for
    // a constant mass, and no impact force or mass-flux term survives.
    let sled = Sled {
        c: 0.0,
        ..Sled::paper()
    };
    for (x, p) in [(0.0, 0.0), (3.0, -7.5), (120.0, 4e3), (-2.0, 1e-3)] {
        let state = SVector::<f64, 2>::new(x, p);
        let rate = sled.state_rate(0.0, &state).unwrap();
        assert!(relative(rate[0] + 1.0, p / sled.m0 + 1.0) < 1e-15);
        assert!(relative(rate[1], sled.m0 * sled.acceleration()) < 1e-15);
        let velocity_state = sled.velocity_state(0.0, &state).unwrap();
        assert_eq!(sled.impact_force(0.0, &velocity_state)[0], 0.0);
        assert_eq!(sled.mass_flux_force(0.0, &velocity_state)[0], 0.0);
    }
}

#[test]
fn rocket_height_and_speed_match_the_closed_forms_while_burning() {
    let rocket = Rocket {
        mu: 10.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let (m0, dry) = (1000.0, 100.0);
    let start = SVector::<f64, 3>::new(0.0, 0.0, m0);
    let mut stepper = DormandPrince::new(&rocket, 0.0, start, tight(TOLERANCE)).unwrap();
    let solution = run(
        &mut stepper,
        &RunConfig::until(1e3),
        &[Event::mass_reaches(0, dry)],
    )
    .unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    for (&t, s) in solution.times.iter().zip(&solution.states) {
        // m is integrated too: it is linear in t, so any method gets it to rounding.
        assert!(relative(s[2], m0 - rocket.mu * t) < 1e-14, "m at t = {t}");
        // y and v start at 0: measure from 1 s on, where y ≈ 7 m and v ≈ 15 m/s. Measured
        // at most 3.4e-12 (y) and 1.9e-14 (v).
        if t >= 1.0 {
            let (y, v) = rocket.burning(m0, t);
            assert!(relative(s[0], y) < 3e-11, "y at t = {t}");
            assert!(relative(s[1] / s[2], v) < 2e-13, "v at t = {t}");
        }
    }
    // The event is located to 1e-12 in t on a mass integrated to ~1e-14 relative; measured
    // 7.4e-13 from t = 90.
    let (t_burnout, _) = solution.last().unwrap();
    assert!((t_burnout - 90.0).abs() < 5e-12, "{t_burnout}");
}

#[test]
fn tsiolkovsky_in_free_space() {
    // g = 0: Δv = u_e ln(m0/m1) for any burn rate; three mass ratios, each with its bound:
    // measured 2.2e-15, 2.5e-15 and 7.1e-14.
    for (mu, ratio, bound) in [(1.0, 2.0, 3e-14), (0.3, 10.0, 3e-14), (5.0, 1e3, 7e-13)] {
        let rocket = Rocket {
            mu,
            u_e: 3000.0,
            g: 0.0,
        };
        let m0 = 50.0;
        let start = SVector::<f64, 3>::new(0.0, 0.0, m0);
        let mut stepper = DormandPrince::new(&rocket, 0.0, start, tight(TOLERANCE)).unwrap();
        let burnout = Event::mass_reaches(0, m0 / ratio);
        let solution = run(&mut stepper, &RunConfig::until(1e6), &[burnout]).unwrap();
        let (_, s) = solution.last().unwrap();
        let delta_v = s[1] / s[2];
        let exact = rocket.u_e * (m0 / s[2]).ln();
        assert!(
            relative(delta_v, exact) < bound,
            "ratio {ratio}: Δv {delta_v} vs {exact}"
        );
        // The event is located to 1e-12 in t (RunConfig's default), i.e. μ·1e-12 in m.
        assert!((s[2] - m0 / ratio).abs() < 2.0 * mu * 1e-12 + 1e-14 * m0);
    }
}

#[test]
fn rocket_without_burn_is_a_ballistic_throw() {
    // μ = 0: no mass change, y = v0 t − g t²/2, v = v0 − g t (textbook).
    let rocket = Rocket {
        mu: 0.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let (mass, v0) = (3.0, 40.0);
    let start = SVector::<f64, 3>::new(0.0, mass * v0, mass);
    let mut stepper = DormandPrince::new(&rocket, 0.0, start, tight(TOLERANCE)).unwrap();
    let apex = Event::state_reaches(1, 0.0, Direction::Falling);
    let solution = run(&mut stepper, &RunConfig::until(100.0), &[apex]).unwrap();
    // A quadratic in t, integrated exactly: measured at most 8.9e-17 of the scales v0²/g
    // and v0, and the apex exact; 1e-15 (a few roundings) asserted.
    let rounding = 1e-15;
    for (&t, s) in solution.times.iter().zip(&solution.states) {
        let y = v0 * t - 0.5 * rocket.g * t * t;
        assert!(
            (s[0] - y).abs() < rounding * v0 * v0 / rocket.g,
            "y at t = {t}"
        );
        assert!((s[1] / mass - (v0 - rocket.g * t)).abs() < rounding * v0);
        assert_eq!(s[2], mass);
    }
    let (t_apex, s) = solution.last().unwrap();
    assert!(relative(t_apex, v0 / rocket.g) < rounding);
    // The apex height, located on the dense output: measured 1.2e-15 (about ten roundings of
    // its 81.5 m) since Dormand–Prince's stage states are accumulated onto y₀ (the explicit
    // core's order); 2e-15 asserted.
    let apex_error = relative(s[0], v0 * v0 / (2.0 * rocket.g));
    assert!(apex_error < 2e-15, "apex height off by {apex_error:e}");
}

#[test]
fn constant_mass_oscillator_is_the_textbook_one() {
    // x = A cos ωt, p = −m A ω sin ωt, ω = √(k/m), over ten periods.
    let oscillator = Oscillator { m0: 2.0, k: 50.0 };
    let omega = (oscillator.k / oscillator.m0).sqrt();
    let amplitude = 0.3;
    let start = SVector::<f64, 2>::new(amplitude, 0.0);
    let end = 10.0 * std::f64::consts::TAU / omega;
    let mut stepper = DormandPrince::new(&oscillator, 0.0, start, tight(TOLERANCE)).unwrap();
    let solution = run(&mut stepper, &RunConfig::until(end), &[]).unwrap();
    let momentum_scale = oscillator.m0 * amplitude * omega;
    for (&t, s) in solution.times.iter().zip(&solution.states) {
        let x = amplitude * (omega * t).cos();
        let p = -momentum_scale * (omega * t).sin();
        // Errors against the amplitude: the solution crosses zero, so no pointwise relative
        // error. Measured at most 2.3e-12 (x) and 2.2e-12 (p) over ten periods.
        assert!((s[0] - x).abs() < 2.5e-11 * amplitude, "x at t = {t}");
        assert!((s[1] - p).abs() < 2.5e-11 * momentum_scale, "p at t = {t}");
    }
}
