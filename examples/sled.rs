//! The paper's sled (Zhang Jiuzhu 2015, §4): a sled starts from rest on a slope, scoops up
//! snow at rest (m = m0 + c x) and slides to x = 50 m. Five of the nine steppers are run
//! and compared with the closed form of eq. 24 (every stepper but ESDIRK4(3), on this sled
//! and two other problems: `cargo bench -p varmass-benches --bench work_precision`,
//! docs/bench/steppers.md).
//!
//! The system is the model file `models/sled.vms`, in body form: the impact force R2 is
//! derived from the inflow, not written by hand, and the paper's results (eqs. 20–24) are
//! `check`s, so a wrong derivation fails the build.
//!
//! Run with `cargo run --release --example sled`. The last line is the error of the most
//! accurate method; the process exits non-zero if it is not below 1e-9.

use std::process::ExitCode;
use std::time::Instant;

use varmass::core::steppers::{ImplicitMidpointConfig, VariationalConfig};
use varmass::core::Record;
use varmass::prelude::*;

/// The paper's sled in body form (`models/sled.vms`); each `check` is one of the paper's
/// equations. `with = ["impact"]` puts in the momentum exchange with the snow (the inflow
/// at rest, whose impact force is eq. 23).
#[variable_mass_system(file = "models/sled.vms", with = ["impact"])]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

/// Where the run stops.
const DISTANCE: f64 = 50.0;
/// Below this distance the relative error of v is not measured: v(x) ∝ √x at the start, so
/// an absolute error δx in x (even a rounding one) shows as a relative error δx/(2x) in
/// v(x), unbounded as x → 0 whatever the method. From 1 m on that amplification is ≤ ½.
const MEASURED_FROM: f64 = 1.0;
/// The acceptance threshold of the most accurate method.
const THRESHOLD: f64 = 1e-9;

impl Sled {
    /// The closed form of eq. 24 in the stable form (docs/mechanics.md#sled-stable-form): with ε = c x / m0,
    /// v²(x) = (2/3) a x (3 + 3ε + ε²)/(1 + ε)², a = g (sin θ − f_d cos θ). The paper's form
    /// [m0 + c x − m0³/(m0 + c x)²]/(3c) cancels catastrophically as c x/m0 → 0.
    fn exact_speed(&self, x: f64) -> f64 {
        let a = self.g * (self.theta.sin() - self.f_d * self.theta.cos());
        let eps = self.c * x / self.m0;
        (2.0 / 3.0 * a * x * (3.0 + 3.0 * eps + eps * eps) / ((1.0 + eps) * (1.0 + eps))).sqrt()
    }
}

/// What one method achieved.
struct Outcome {
    method: &'static str,
    setting: String,
    error_at_end: f64,
    max_error: f64,
    steps: usize,
    evaluations: usize,
    energy_residual: f64,
    seconds: f64,
}

/// Runs `stepper` from rest to x = 50 m (an event stops it there) and measures the relative
/// error of v against the closed form at every accepted point with x ≥ 1 m and at the end.
fn measure<St>(
    sled: &Sled,
    method: &'static str,
    setting: String,
    mut stepper: St,
) -> Result<Outcome, StepError<2>>
where
    St: Stepper<1, 2, System = Sled>,
{
    let config = RunConfig::until(1e3).recording(Record {
        energy_residual: true,
        ..Record::default()
    });
    let at_distance = Event::state_reaches(0, DISTANCE, Direction::Rising);
    let started = Instant::now();
    let solution = run(&mut stepper, &config, &[at_distance])?;
    let seconds = started.elapsed().as_secs_f64();
    let relative_error = |time: f64, state: &SVector<f64, 2>| -> Result<f64, StepError<2>> {
        let velocities = sled
            .velocities(time, state)
            .map_err(|error| StepError::from_system(sled, error, time, state))?;
        let exact = sled.exact_speed(state[0]);
        Ok((velocities[0] - exact).abs() / exact)
    };
    let mut max_error: f64 = 0.0;
    for (&time, state) in solution.times.iter().zip(&solution.states) {
        if state[0] >= MEASURED_FROM {
            max_error = max_error.max(relative_error(time, state)?);
        }
    }
    let (time, state) = solution.last().ok_or_else(|| {
        StepError::invalid_configuration(
            stepper.time(),
            *stepper.state(),
            "the run returned no point",
        )
    })?;
    let energy_residual = solution
        .energy_residual
        .iter()
        .fold(0.0f64, |worst, r| worst.max(r.abs()));
    Ok(Outcome {
        method,
        setting,
        error_at_end: relative_error(time, state)?,
        max_error,
        steps: solution.statistics.accepted_steps,
        evaluations: solution.statistics.rate_evaluations,
        energy_residual,
        seconds,
    })
}

/// Five of the nine steppers (the fixed-step ones and Dormand–Prince at two tolerances), each
/// at a setting that keeps the example quick in release mode.
fn all_methods(sled: &Sled) -> Result<Vec<Outcome>, StepError<2>> {
    let start = SVector::<f64, 2>::zeros();
    let adaptive = |tolerance: f64| {
        StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: tolerance,
            absolute_tolerance: tolerance,
            ..AdaptiveControl::default()
        })
    };
    let euler_step = 1e-5;
    let rk4_step = 1e-3;
    let implicit_step = 1e-4;
    Ok(vec![
        measure(
            sled,
            "explicit Euler",
            format!("h = {euler_step:.0e}"),
            ExplicitEuler::new(sled, 0.0, start, FixedStep { step: euler_step })?,
        )?,
        measure(
            sled,
            "classical RK4",
            format!("h = {rk4_step:.0e}"),
            ClassicalRk4::new(sled, 0.0, start, FixedStep { step: rk4_step })?,
        )?,
        measure(
            sled,
            "Dormand–Prince",
            "tol = 1e-6".to_string(),
            DormandPrince::new(sled, 0.0, start, adaptive(1e-6))?,
        )?,
        measure(
            sled,
            "Dormand–Prince",
            "tol = 1e-13".to_string(),
            DormandPrince::new(sled, 0.0, start, adaptive(1e-13))?,
        )?,
        measure(
            sled,
            "implicit midpoint",
            format!("h = {implicit_step:.0e}"),
            ImplicitMidpoint::new(
                sled,
                0.0,
                start,
                ImplicitMidpointConfig {
                    step: implicit_step,
                    ..ImplicitMidpointConfig::default()
                },
            )?,
        )?,
        measure(
            sled,
            "variational",
            format!("h = {implicit_step:.0e}"),
            Variational::new(
                sled,
                0.0,
                start,
                VariationalConfig {
                    step: implicit_step,
                    ..VariationalConfig::default()
                },
            )?,
        )?,
    ])
}

fn main() -> ExitCode {
    let sled = Sled {
        m0: 10.0,
        c: 2.0,
        g: 9.81,
        theta: 30f64.to_radians(),
        f_d: 0.1,
    };
    println!("{}", Sled::DERIVATION);
    println!(
        "Sled from rest to x = {DISTANCE} m: m0 = {} kg, c = {} kg/m, θ = 30°, f_d = {}, g = {} m/s².",
        sled.m0, sled.c, sled.f_d, sled.g
    );
    println!(
        "Closed form (eq. 24, stable form): v({DISTANCE} m) = {:.12} m/s.",
        sled.exact_speed(DISTANCE)
    );
    println!(
        "Relative error of v against it: at x = {DISTANCE} m (the stopping event), and the \
         maximum over every accepted step with x ≥ {MEASURED_FROM} m (below that v ∝ √x \
         turns any error in x into a large relative error in v)."
    );
    println!("|H resid.| is the largest energy-budget residual |∫ power dt − (H − H₀)| in J;");
    println!("time is the wall time of the run, including that energy-budget recording.\n");

    let outcomes = match all_methods(&sled) {
        Ok(outcomes) => outcomes,
        Err(error) => {
            eprintln!("a run failed: {error}");
            return ExitCode::FAILURE;
        }
    };
    println!(
        "{:<18} {:<11} {:>12} {:>12} {:>9} {:>10} {:>12} {:>10}",
        "method", "setting", "err @ 50 m", "max err", "steps", "f evals", "|H resid.|", "time"
    );
    for o in &outcomes {
        println!(
            "{:<18} {:<11} {:>12.3e} {:>12.3e} {:>9} {:>10} {:>12.3e} {:>8.2} ms",
            o.method,
            o.setting,
            o.error_at_end,
            o.max_error,
            o.steps,
            o.evaluations,
            o.energy_residual,
            o.seconds * 1e3
        );
    }
    let best = outcomes
        .iter()
        .map(|o| o.max_error.max(o.error_at_end))
        .fold(f64::INFINITY, f64::min);
    println!("max relative error vs closed form: {best:.3e}");
    if best < THRESHOLD {
        ExitCode::SUCCESS
    } else {
        eprintln!("the most accurate method is not below {THRESHOLD:e}");
        ExitCode::FAILURE
    }
}
