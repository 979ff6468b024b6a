//! Extremes of the mass (ARCHITECTURE.md#extremes): mass ratios up to 10⁶, accretion rates from 10⁻¹² to 10⁶,
//! a near-massless start, and masses that run out. Each test states what is expected.

mod validation_support;

use validation_support::{relative, tight, Rocket, Sled};
use varmass::core::steppers::{ImplicitMidpointConfig, VariationalConfig};
use varmass::prelude::*;

/// Burns a rocket from rest to m0/ratio with Dormand–Prince at tolerance 1e-12 and returns
/// the relative errors of v and y at burnout and the steps taken.
fn burn(ratio: f64, g: f64) -> (f64, f64, usize) {
    let m0 = 1e6;
    let dry = m0 / ratio;
    // A 100 s burn whatever the ratio.
    let rocket = Rocket {
        mu: (m0 - dry) / 100.0,
        u_e: 3000.0,
        g,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, m0);
    let mut stepper = DormandPrince::new(&rocket, 0.0, start, tight(1e-12)).unwrap();
    let solution = run(
        &mut stepper,
        &RunConfig::until(1e3),
        &[Event::mass_reaches(0, dry)],
    )
    .unwrap();
    let (_, s) = solution.last().unwrap();
    // The reference at the mass actually reached (the event is located to 1e-12 in t, which
    // at μ ≈ 10⁴ kg/s is 1e-8 kg of a 1 kg dry mass): t from m, then the closed forms.
    let t = (m0 - s[2]) / rocket.mu;
    let (y, v) = rocket.burning(m0, t);
    (
        relative(s[1] / s[2], v),
        relative(s[0], y),
        solution.statistics.accepted_steps,
    )
}

#[test]
fn mass_ratio_up_to_a_million() {
    // Expectation: the acceleration μ u_e/m grows by the mass ratio over the burn, and the
    // adaptive steps shrink with it (the steps grow only like ln(ratio)), so the closed
    // forms hold to ~1e-11 at every ratio, with gravity and in free space (Tsiolkovsky).
    // Measured, worst of g = 0 and 9.81 (v error, y error, steps): at 10, 4.3e-13, 1.5e-13,
    // 239; at 10³, 1.2e-12, 8.2e-15, 488; at 10⁶, 6.2e-12, 7.8e-16, 802. Bounds: ten times
    // the errors, a quarter more steps.
    let cases = [
        (10.0, 5e-12, 1.5e-12, 300),
        (1e3, 1.5e-11, 1e-13, 610),
        (1e6, 6e-11, 1e-14, 1_000),
    ];
    for g in [0.0, 9.81] {
        for (ratio, v_bound, y_bound, step_bound) in cases {
            let (v_error, y_error, steps) = burn(ratio, g);
            assert!(
                v_error < v_bound,
                "ratio {ratio}, g {g}: v error {v_error:e}"
            );
            assert!(
                y_error < y_bound,
                "ratio {ratio}, g {g}: y error {y_error:e}"
            );
            assert!(steps < step_bound, "ratio {ratio}: {steps} steps");
        }
    }
}

/// The sled with accretion rate c (and initial mass m0) from rest to 50 m, Dormand–Prince
/// at 1e-12: the relative error of v at the stop against the stable closed form.
fn sled_at_50_m(m0: f64, c: f64) -> (f64, usize) {
    let sled = Sled {
        m0,
        c,
        ..Sled::paper()
    };
    let mut stepper = DormandPrince::new(&sled, 0.0, SVector::zeros(), tight(1e-12)).unwrap();
    let at_50_m = Event::state_reaches(0, 50.0, Direction::Rising);
    let solution = run(&mut stepper, &RunConfig::until(1e3), &[at_50_m]).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let (t, s) = solution.last().unwrap();
    let v = sled.velocities(t, s).unwrap()[0];
    (
        relative(v, sled.exact_speed(s[0])),
        solution.statistics.accepted_steps,
    )
}

#[test]
fn accretion_rates_from_1e_minus_12_to_1e6() {
    // Expectation: the state (x, p = m ẋ) has a smooth rate at every c (ṗ = m a, ẋ = p/m),
    // so Dormand–Prince meets its tolerance across 18 decades of c; the reference must be
    // the stable form (see the next test). Measured: 1.4e-12 at c = 1e-3, ≤ 2.4e-13 at
    // every other c; 4 steps at c ≤ 1e-6 (constant acceleration, integrated exactly) to 909
    // at c = 1e6. Bounds: ten times the worst error, a third more steps.
    for exponent in (-12..=6).step_by(3) {
        let c = 10f64.powi(exponent);
        let (error, steps) = sled_at_50_m(10.0, c);
        assert!(error < 1.5e-11, "c = {c:e}: relative error {error:e}");
        // The cost stays bounded too: no step-size collapse at either end.
        assert!(steps < 1_200, "c = {c:e}: {steps} steps");
    }
}

#[test]
fn the_papers_closed_form_cancels_for_small_accretion() {
    // Why the stable form: the paper's v² = 2a/(3c) [m0 + c x − m0³/(m0 + c x)²] subtracts
    // two numbers of size m0 to leave one of size 3 c x = 1.5e-10, so at c = 1e-12 it keeps
    // only ε_mach m0/(3 c x) ≈ 1.5e-5 relative accuracy in v² (measured 9e-6 in v), and none
    // at all below c ≈ 1e-16.
    let sled = Sled {
        c: 1e-12,
        ..Sled::paper()
    };
    let x = 50.0;
    let (m0, c, a) = (sled.m0, sled.c, sled.acceleration());
    let m = m0 + c * x;
    let paper = (2.0 * a / (3.0 * c) * (m - m0 * m0 * m0 / (m * m))).sqrt();
    let stable = sled.exact_speed(x);
    // The constant-mass speed √(2 a x) is right to ~1e-11 relative here (ε = 5e-12).
    let constant_mass = (2.0 * a * x).sqrt();
    assert!(relative(stable, constant_mass) < 1e-10);
    assert!(
        relative(paper, stable) > 1e-7,
        "paper form {paper} vs {stable}"
    );
}

#[test]
fn near_massless_start() {
    // m0 down to 1e-12 kg with c = 2 kg/m, like a chain falling from a heap: the mass law
    // passes from m0 to c x within x ~ m0/c (5e-13 m), and v² from 2 a x to (2/3) a x there.
    // Expectation: the first step (chosen from the rates at rest, HNW II.4) and the
    // controller resolve that layer, and v at 50 m meets the tolerance. Measured: ≤ 2.3e-13
    // in 571–657 steps for every m0. Bounds: ten times the error, a third more steps.
    for m0 in [1e-3, 1e-6, 1e-9, 1e-12] {
        let (error, steps) = sled_at_50_m(m0, 2.0);
        assert!(error < 2.5e-12, "m0 = {m0:e}: relative error {error:e}");
        assert!(steps < 875, "m0 = {m0:e}: {steps} steps");
    }
}

#[test]
fn no_mass_at_all_is_a_typed_error() {
    // m0 = 0 at x = 0: the mass matrix is singular at the start; no stepper may start.
    let sled = Sled {
        m0: 0.0,
        ..Sled::paper()
    };
    let error = DormandPrince::new(&sled, 0.0, SVector::zeros(), tight(1e-12)).unwrap_err();
    assert_eq!(
        error.kind,
        StepErrorKind::System(varmass::core::SystemError::NonPositiveMass { index: 0 })
    );
    assert_eq!((error.time, error.state), (0.0, SVector::zeros()));
}

/// Whether a run's result is a typed failure with a finite time, or a success whose every
/// point is finite: what "never NaN" means.
fn never_nan<const N: usize, const S: usize>(result: &Result<Solution<N, S>, RunError<N, S>>) {
    match result {
        Ok(solution) => {
            for state in &solution.states {
                assert!(state.iter().all(|c| c.is_finite()), "{state:?}");
            }
        }
        Err(error) => assert!(error.time.is_finite(), "{error:?}"),
    }
}

#[test]
fn a_rocket_running_out_of_mass_stops_with_a_typed_error() {
    // m = 1 − 0.1 t reaches 0 at t = 10; the run asks for 20 s with no burnout event.
    // Expectation: every stepper fails with NonPositiveMass as the state mass turns
    // non-positive, never with a NaN state, and where the mass runs out, t = 10: a step
    // refused for the mass is retried by halves (an event before it would stop the run,
    // docs/mechanics.md#switches) until the gap is a rounding, so the fixed steppers fail
    // within rounding of t = 10 too (before issue 34: Euler and RK4 at 10 + h, the implicit
    // midpoint and variational steppers at 10 + h/2, where they evaluate); Dormand–Prince
    // shrinks its steps onto t = 10 itself. 1e-11 asserted.
    let rocket = Rocket {
        mu: 0.1,
        u_e: 100.0,
        g: 9.81,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1.0);
    let config = RunConfig::until(20.0);
    let h = 1e-3;
    let expected_times = [10.0; 5];
    let results = [
        (
            "Euler",
            run(
                &mut ExplicitEuler::new(&rocket, 0.0, start, FixedStep { step: h }).unwrap(),
                &config,
                &[],
            ),
        ),
        (
            "RK4",
            run(
                &mut ClassicalRk4::new(&rocket, 0.0, start, FixedStep { step: h }).unwrap(),
                &config,
                &[],
            ),
        ),
        (
            "DP",
            run(
                &mut DormandPrince::new(&rocket, 0.0, start, tight(1e-10)).unwrap(),
                &config,
                &[],
            ),
        ),
        (
            "midpoint",
            run(
                &mut ImplicitMidpoint::new(
                    &rocket,
                    0.0,
                    start,
                    ImplicitMidpointConfig {
                        step: h,
                        ..Default::default()
                    },
                )
                .unwrap(),
                &config,
                &[],
            ),
        ),
        (
            "variational",
            run(
                &mut Variational::new(
                    &rocket,
                    0.0,
                    start,
                    VariationalConfig {
                        step: h,
                        ..Default::default()
                    },
                )
                .unwrap(),
                &config,
                &[],
            ),
        ),
    ];
    for ((name, result), expected) in results.iter().zip(expected_times) {
        never_nan(result);
        let error = result.as_ref().expect_err(name);
        let time = error.time;
        assert!(
            (time - expected).abs() < 1e-11,
            "{name}: failed at t = {time}, expected {expected}"
        );
        assert_eq!(
            error.kind,
            StepErrorKind::System(varmass::core::SystemError::NonPositiveMass { index: 0 }),
            "{name}: {error:?}"
        );
        assert!(error.state[2] <= 0.0, "{name}: {error:?}");
    }
}

#[test]
fn a_mass_event_stops_before_the_mass_runs_out() {
    // With Event::mass_reaches the same run ends cleanly at the threshold instead.
    let rocket = Rocket {
        mu: 0.1,
        u_e: 100.0,
        g: 9.81,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1.0);
    let mut stepper = DormandPrince::new(&rocket, 0.0, start, tight(1e-10)).unwrap();
    let solution = run(
        &mut stepper,
        &RunConfig::until(20.0),
        &[Event::mass_reaches(0, 1e-6)],
    )
    .unwrap();
    let (t, s) = solution.last().unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    // Located to the run's event tolerance, 1e-12 in t (measured 1.8e-15: m is linear).
    assert!((t - (1.0 - 1e-6) / 0.1).abs() < 1e-12);
    // Tsiolkovsky at a mass ratio 10⁶: v = u_e ln 10⁶ − g t. Measured 3.8e-8 relative (the
    // tolerance 1e-10 against an acceleration that grows 10⁶-fold); 4e-7 asserted.
    let v = 100.0 * 1e6f64.ln() - 9.81 * t;
    assert!(relative(s[1] / s[2], v) < 4e-7, "{} vs {v}", s[1] / s[2]);
}

/// The time a sled from rest reaches x = −m0/c, where its mass m0 + c x runs out (c < 0):
/// t* = ∫ dx / v(x) with the closed form v² = (2/3) a x (3 + 3ε + ε²)/(1 + ε)², ε = c x/m0,
/// which holds for any ε > −1. With x = u² the integrand 2u/v(u²) = 2(1 + ε)/√((2/3) a
/// (3 + 3ε + ε²)) is smooth on the whole interval (v grows like 1/m at the end), so Simpson's
/// rule on 2000 intervals gives t* to about 1e-15 (1000 and 10⁴ intervals agree to 9e-14).
fn mass_runs_out_at(sled: &Sled) -> f64 {
    let end = (-sled.m0 / sled.c).sqrt();
    let a = sled.acceleration();
    let integrand = |u: f64| {
        let eps = sled.c * u * u / sled.m0;
        2.0 * (1.0 + eps) / (2.0 / 3.0 * a * (3.0 + 3.0 * eps + eps * eps)).sqrt()
    };
    let intervals = 2000;
    let width = end / intervals as f64;
    let inner: f64 = (1..intervals)
        .map(|i| integrand(i as f64 * width) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (integrand(0.0) + inner + integrand(end)) * width / 3.0
}

/// The paper's sled shedding its mass (c < 0) where it stands: an `outflow` at rest, of
/// rate −ṁ = −c ẋ ≥ 0. (The paper's `inflow` with c < 0 has the same equation, since
/// −R1 = −Q1 (0 − ẋ) with Q1 = −c ẋ equals R2 = Q2 (0 − ẋ) with Q2 = c ẋ, but its rate
/// c ẋ is negative, which every run refuses: see the next test.)
#[variable_mass_system(
    "
    coordinates x
    mass m = m0 + c*x
    body sled: mass m, position [x]
    potential -m*g*x*sin(theta)
    force sled: [-f_d*m*g*cos(theta)]
    outflow sled: velocity [0]
    check x'' = g*sin(theta) - f_d*g*cos(theta) - c*x'^2/m
"
)]
struct SheddingSled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

#[test]
fn a_sled_shedding_its_mass_stops_with_a_typed_error() {
    // c < 0: m = m0 + c x reaches 0 at x = 5 m, a mass law (not a state) running out, at
    // t* = 1.1727509466788 s (by quadrature of the closed form). The equation ẍ = a − c ẋ²/m
    // then diverges. Expectation: NonPositiveMass at t*, never NaN. Measured: DP at
    // t* + 3.5e-10 (x = 5 + 6.5e-8; 3.5e-9 asserted), RK4 (h = 0.01) at the end of the
    // step containing t*, 1.18, having jumped to x = 7.07.
    let closed_form = Sled {
        c: -2.0,
        ..Sled::paper()
    };
    let t_star = mass_runs_out_at(&closed_form);
    let Sled {
        m0,
        c,
        g,
        theta,
        f_d,
    } = closed_form;
    let sled = SheddingSled {
        m0,
        c,
        g,
        theta,
        f_d,
    };
    let start = SVector::<f64, 2>::new(0.0, 0.0);
    let result = run(
        &mut DormandPrince::new(&sled, 0.0, start, tight(1e-10)).unwrap(),
        &RunConfig::until(100.0),
        &[],
    );
    never_nan(&result);
    let error = result.unwrap_err();
    assert_eq!(
        error.kind,
        StepErrorKind::System(varmass::core::SystemError::NonPositiveMass { index: 0 })
    );
    assert!(
        (error.time - t_star).abs() < 3.5e-9,
        "{error:?}, t* = {t_star}"
    );
    let step = 1e-2;
    let result = run(
        &mut ClassicalRk4::new(&sled, 0.0, start, FixedStep { step }).unwrap(),
        &RunConfig::until(100.0),
        &[],
    );
    never_nan(&result);
    let error = result.unwrap_err();
    assert_eq!(
        error.kind,
        StepErrorKind::System(varmass::core::SystemError::NonPositiveMass { index: 0 })
    );
    // Where RK4's own mass runs out, found by halving the refused step (before: at the end
    // of the step past t*): within a step of t*, where the motion is singular.
    assert!(
        (error.time - t_star).abs() < step,
        "{error:?}, t* = {t_star}"
    );
}

/// The same shedding written as the paper's `inflow` (c < 0 makes its rate c ẋ negative):
/// from rest the rate is 0 at t = 0 (allowed), and below 0 at the end of the first step,
/// where the run ends with `NegativeFlowRate` (rate c ẋ there, ẋ ≈ a h = 0.0405 for RK4 at
/// h = 0.01, so ≈ −0.081), long before the mass runs out.
#[test]
fn a_sled_shedding_through_an_inflow_is_refused_at_its_first_step() {
    let sled = Sled {
        c: -2.0,
        ..Sled::paper()
    };
    let start = SVector::<f64, 2>::new(0.0, 0.0);
    let step = 1e-2;
    let mut stepper = ClassicalRk4::new(&sled, 0.0, start, FixedStep { step }).unwrap();
    let error = run(&mut stepper, &RunConfig::until(100.0), &[]).unwrap_err();
    let StepErrorKind::NegativeFlowRate { index: 0, rate } = error.kind else {
        panic!("{error:?}");
    };
    assert_eq!(error.time, step);
    let speed = error.state[1] / sled.mass(0, step, &error.state);
    assert!(
        (rate - sled.c * speed).abs() <= 1e-14 * rate.abs(),
        "{rate} vs {speed}"
    );
    assert!(
        (speed - sled.acceleration() * step).abs() < 1e-3 * speed,
        "{speed}"
    );
    assert_eq!(sled.flow_name(0), Some("inflow `sled`"));
}
