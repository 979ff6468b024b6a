//! Every parameter scaled by 10^±100 in consistent units (ARCHITECTURE.md#extremes): masses by M, lengths by
//! L, times by T. The motion is the same in the new units, so the relative error of a run
//! against the closed form must be unchanged — provided the tolerances are relative: an
//! absolute tolerance, an absolute event tolerance or an absolute Newton tolerance carries
//! units and has to be scaled with the problem (the last test shows what happens if not).

mod validation_support;

use validation_support::{relative, Rocket, Sled};
use varmass::core::steppers::{ImplicitMidpointConfig, NewtonConfig};
use varmass::prelude::*;

/// (M, L, T) exponents, in hundreds. Left out: the two corners where the momentum rate
/// M L/T² would pass 10^±400 and leave f64's range (1.8e308) — no scaling of units can fix
/// that, it is the range of the type. Every other quantity of the sled and the rocket (p ~
/// M L/T, H ~ M L²/T² is not computed by a run) stays within 10^±300.
const SCALES: [(i32, i32, i32); 12] = [
    (0, 0, 0),
    (1, 0, 0),
    (-1, 0, 0),
    (0, 1, 0),
    (0, -1, 0),
    (0, 0, 1),
    (0, 0, -1),
    (1, 1, 1),
    (-1, -1, -1),
    (1, -1, 1),
    (-1, 1, -1),
    (1, -1, -1),
];

fn units((m, l, t): (i32, i32, i32)) -> (f64, f64, f64) {
    let power = |e: i32| 10f64.powi(100 * e);
    (power(m), power(l), power(t))
}

/// Purely relative Dormand–Prince control (an absolute tolerance carries units).
fn relative_control(tolerance: f64) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: 0.0,
        ..AdaptiveControl::default()
    })
}

/// A run configuration whose only scale is the problem's: end time T·1e3, events located to
/// rounding (the default 1e-12 s would be absolute).
fn config(time_unit: f64) -> RunConfig {
    RunConfig {
        event_tolerance: 0.0,
        ..RunConfig::until(1e3 * time_unit)
    }
}

/// The paper's sled in units (M, L, T), from rest to 50 L: the relative error of v at the
/// stop and the number of steps.
fn scaled_sled(scale: (i32, i32, i32)) -> (f64, usize) {
    let (m, l, t) = units(scale);
    let paper = Sled::paper();
    let sled = Sled {
        m0: paper.m0 * m,
        c: paper.c * m / l,
        g: paper.g * l / (t * t),
        ..paper
    };
    let mut stepper =
        DormandPrince::new(&sled, 0.0, SVector::zeros(), relative_control(1e-12)).unwrap();
    let stop = Event::state_reaches(0, 50.0 * l, Direction::Rising);
    let solution = run(&mut stepper, &config(t), &[stop]).unwrap();
    assert_eq!(solution.stop, StopReason::EventFound { index: 0 });
    let (time, s) = solution.last().unwrap();
    let v = sled.velocities(time, s).unwrap()[0];
    (
        relative(v, sled.exact_speed(s[0])),
        solution.statistics.accepted_steps,
    )
}

#[test]
fn sled_error_is_unchanged_by_units() {
    // Expectation: the same accuracy (~1e-13) and about the same number of steps in every
    // unit system: scaling by 10^100 is not exact in binary, so rounding differs and the
    // controller may take a step or two more or less. Measured: 7.8e-14 and 245 steps in
    // every unit system, rocket 1.3e-14 in 227 steps in every one.
    let (reference, reference_steps) = scaled_sled((0, 0, 0));
    for scale in SCALES {
        let (error, steps) = scaled_sled(scale);
        assert!(error < 1e-10, "{scale:?}: relative error {error:e}");
        assert!(
            error < 20.0 * reference.max(1e-14),
            "{scale:?}: {error:e} vs {reference:e}"
        );
        assert!(
            steps.abs_diff(reference_steps) <= 5,
            "{scale:?}: {steps} steps"
        );
    }
}

#[test]
fn rocket_error_is_unchanged_by_units() {
    // The vertical rocket (m0 = 1000 kg → 100 kg, μ = 10 kg/s, u_e = 2500 m/s, g = 9.81) in
    // units (M, L, T): v and y at burnout against the closed forms.
    for scale in SCALES {
        let (m, l, t) = units(scale);
        let rocket = Rocket {
            mu: 10.0 * m / t,
            u_e: 2500.0 * l / t,
            g: 9.81 * l / (t * t),
        };
        let m0 = 1000.0 * m;
        let start = SVector::<f64, 3>::new(0.0, 0.0, m0);
        let mut stepper = DormandPrince::new(&rocket, 0.0, start, relative_control(1e-12)).unwrap();
        let burnout = Event::mass_reaches(0, 100.0 * m);
        let solution = run(&mut stepper, &config(t), &[burnout]).unwrap();
        let (_, s) = solution.last().unwrap();
        // The reference at the mass reached: t = (m0 − m)/μ.
        let time = (m0 - s[2]) / rocket.mu;
        let (y, v) = rocket.burning(m0, time);
        let errors = (relative(s[1] / s[2], v), relative(s[0], y));
        assert!(
            errors.0 < 1e-10 && errors.1 < 1e-10,
            "{scale:?}: {errors:?}"
        );
    }
}

#[test]
fn fixed_step_methods_scale_with_the_step() {
    // RK4 and the implicit midpoint rule with h = 1e-3 T: the same discrete map in new units,
    // so the same error (RK4 ~1e-14, midpoint ~1e-8 at this step), with the Newton
    // tolerance made purely relative.
    let relative_newton = NewtonConfig {
        absolute_tolerance: 0.0,
        ..NewtonConfig::default()
    };
    for scale in SCALES {
        let (m, l, t) = units(scale);
        let paper = Sled::paper();
        let sled = Sled {
            m0: paper.m0 * m,
            c: paper.c * m / l,
            g: paper.g * l / (t * t),
            ..paper
        };
        let stop = Event::state_reaches(0, 50.0 * l, Direction::Rising);
        let error_of = |solution: Solution<1, 2>| {
            let (time, s) = solution.last().unwrap();
            relative(sled.velocities(time, s).unwrap()[0], sled.exact_speed(s[0]))
        };
        let step = 1e-3 * t;
        let mut rk4 = ClassicalRk4::new(&sled, 0.0, SVector::zeros(), FixedStep { step }).unwrap();
        let rk4_error = error_of(run(&mut rk4, &config(t), &[stop]).unwrap());
        let midpoint_config = ImplicitMidpointConfig {
            step,
            newton: relative_newton,
        };
        let mut midpoint =
            ImplicitMidpoint::new(&sled, 0.0, SVector::zeros(), midpoint_config).unwrap();
        let midpoint_error = error_of(run(&mut midpoint, &config(t), &[stop]).unwrap());
        assert!(rk4_error < 1e-12, "{scale:?}: RK4 {rk4_error:e}");
        assert!(
            midpoint_error < 1e-7,
            "{scale:?}: midpoint {midpoint_error:e}"
        );
    }
}

#[test]
fn absolute_tolerances_do_not_scale() {
    // The defaults carry units. Expectation, and a limit users must know: with lengths in
    // units of 10^-100 (the sled covers 5e-99 "m"), Dormand–Prince's default absolute
    // tolerance of 1e-9 dwarfs the state, the controller takes a handful of steps and the
    // run is accurate to nothing like its relative tolerance 1e-6.
    let paper = Sled::paper();
    let l = 1e-100;
    let sled = Sled {
        c: paper.c / l,
        g: paper.g * l,
        ..paper
    };
    let stop = Event::state_reaches(0, 50.0 * l, Direction::Rising);
    let mut dormand_prince =
        DormandPrince::new(&sled, 0.0, SVector::zeros(), StepControl::default()).unwrap();
    let solution = run(&mut dormand_prince, &config(1.0), &[stop]).unwrap();
    let (time, s) = solution.last().unwrap();
    let error = relative(sled.velocities(time, s).unwrap()[0], sled.exact_speed(s[0]));
    assert!(
        error > 1e-4,
        "DP default tolerances at L = 1e-100: {error:e}"
    );
}
