//! `table F(t) = runtime` (docs/tables.md#runtime-tables): the M1670 rocket of
//! `tests/table_dsl_rocket.rs` with its thrust curve a field of the struct
//! (`models/motor_rocket_runtime.vms`), flown on the measured curve and on the curve
//! dispersed by `Tabulated::transformed(k, s)`, against the closed form.
//!
//! Closed form (by hand). With ṁ = −F/u_e, m(t) = m₀ − I(t)/u_e, I the impulse ∫₀ᵗ F;
//! Meshchersky m v̇ = F − m g = −u_e ṁ − m g gives v(t) = u_e ln(m₀/m(t)) − g t. The
//! dispersed curve is F_ks(t) = k·F(t/s), whose impulse is ∫₀ᵗ k F(τ/s) dτ = k·s·I(t/s)
//! (substituting σ = τ/s): the total impulse scales by k·s and the burn time by s.

use varmass::core::nalgebra::{SVector, Vector3};
use varmass::core::steppers::{AdaptiveControl, Dop853, DormandPrince, StepControl};
use varmass::core::table::Tabulated;
use varmass::core::{run, RunConfig, Stepper, VariableMassSystem};
use varmass::prelude::variable_mass_system;
use varmass_table::{Interpolation, Motor, Piecewise};

#[variable_mass_system(file = "models/motor_rocket_runtime.vms")]
#[allow(non_snake_case)] // the field is named as the model's table
struct MotorRocket {
    u_e: f64,
    g: f64,
    F: Tabulated,
}

/// The same model with the file table, to hold the two bit-identical.
#[variable_mass_system(file = "models/motor_rocket.vms")]
struct FileRocket {
    u_e: f64,
    g: f64,
}

/// Gravity, m/s².
const G: f64 = 9.80665;
/// Lift-off mass, kg.
const M0: f64 = 20.0;
/// The end of the run, s: after burnout at 3.9·s for every stretch s flown.
const END: f64 = 6.0;

fn motor() -> Motor {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/models/motors/Cesaroni_M1670.eng"
    );
    Motor::parse(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The rocket on the M1670's curve scaled by k and stretched by s.
fn rocket(k: f64, s: f64) -> MotorRocket {
    let measured = MotorRocket::tabulate_F(&motor().thrust);
    MotorRocket {
        u_e: motor().exhaust_speed(),
        g: G,
        F: measured.transformed(k, s).unwrap(),
    }
}

fn control(tolerance: f64, base: AdaptiveControl) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..base
    })
}

fn start() -> SVector<f64, 3> {
    Vector3::new(0.0, 0.0, M0)
}

/// The largest relative errors of m and v against the closed form of the curve k·F(t/s)
/// over every accepted step of one run to END, and the times passed through.
fn worst<St: Stepper<1, 3, System = MotorRocket>>(
    mut stepper: St,
    k: f64,
    s: f64,
) -> ([f64; 2], Vec<f64>) {
    let impulse: Piecewise = Interpolation::Linear
        .interpolate(&motor().thrust)
        .antiderivative();
    let u_e = motor().exhaust_speed();
    let solution = run(&mut stepper, &RunConfig::until(END), &[]).unwrap();
    let mut worst = [0.0_f64; 2];
    for (&t, state) in solution.times.iter().zip(&solution.states) {
        let burnt = k * s * impulse.value((t / s).min(impulse.domain().1));
        let m = M0 - burnt / u_e;
        let v = u_e * (M0 / m).ln() - G * t;
        worst[0] = worst[0].max((state[2] - m).abs() / M0);
        // v reaches ≈ 300 m/s: relative to the largest speed, since v passes through 0.
        worst[1] = worst[1].max((state[1] / state[2] - v).abs() / 300.0);
    }
    (worst, solution.times.clone())
}

#[test]
fn the_runtime_table_is_the_file_table_to_the_bit() {
    let runtime = rocket(1.0, 1.0);
    let file = FileRocket {
        u_e: runtime.u_e,
        g: G,
    };
    for &t in &[0.0, 0.01, 0.5, 1.234, 3.0, 3.9, 4.5] {
        let state = Vector3::new(12.0, 30.0, 18.5);
        assert_eq!(
            runtime.state_rate(t, &state).unwrap(),
            file.state_rate(t, &state).unwrap()
        );
        assert_eq!(runtime.next_stop_time(t), file.next_stop_time(t));
    }
}

#[test]
fn the_dispersed_curve_meets_the_scaled_closed_form() {
    // 10 % more thrust burning 5 % shorter, and 5 % less burning 8 % longer (the knots,
    // stretched, are still the stop times: every run lands on each).
    for (k, s) in [(1.1, 0.95), (0.95, 1.08)] {
        let knots: Vec<f64> = motor().thrust.arguments().iter().map(|x| s * x).collect();
        for tolerance in [1e-12, 1e-8] {
            let system = rocket(k, s);
            let base = AdaptiveControl::dop853();
            let stepper = Dop853::new(&system, 0.0, start(), control(tolerance, base)).unwrap();
            let ([mass, speed], times) = worst(stepper, k, s);
            // Measured (m, v) at 1e-12 and 1e-8: 3.6e-16, 8.3e-15 and 1.8e-16, 8.3e-15
            // (k 1.1, s 0.95); 3.6e-16, 7.8e-15 and 5.3e-16, 8.3e-15 (k 0.95, s 1.08).
            // Bound 1e-12 at both tolerances: landing on the knots, DOP853 integrates the
            // pieces to rounding (as the file table's rocket, tests/table_dsl_rocket.rs).
            assert!(
                mass <= 1e-12 && speed <= 1e-12,
                "k {k} s {s} tol {tolerance:e}: {mass:e} {speed:e}"
            );
            for knot in &knots[1..] {
                assert!(times.contains(knot), "no step ends at the knot {knot}");
            }
        }
        let system = rocket(k, s);
        let base = AdaptiveControl::default();
        let stepper = DormandPrince::new(&system, 0.0, start(), control(1e-12, base)).unwrap();
        // Measured (m, v) at 1e-12: 5.3e-16, 4.7e-15 (k 1.1, s 0.95); 5.3e-16, 4.9e-15.
        let ([mass, speed], _) = worst(stepper, k, s);
        assert!(
            mass <= 1e-12 && speed <= 1e-12,
            "Dormand–Prince k {k} s {s}: {mass:e} {speed:e}"
        );
    }
}
