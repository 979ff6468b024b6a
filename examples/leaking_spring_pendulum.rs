//! A spring pendulum whose bob leaks through a nozzle pointing backwards along the swing: two
//! degrees of freedom (length r and angle θ from the downward vertical) where the mass change
//! and the geometry interact. The jet's thrust μ u_e acts along ê_θ, so in polar coordinates
//! it is a torque μ u_e r on θ, and the mass-flux term Σ ṁ ∂*p/∂m = −μ (ṙ, r² θ̇) couples the
//! loss of mass to both coordinates.
//!
//! There is no closed form, so the example checks itself two ways:
//! * the same physics in Cartesian coordinates (x, y), where the nozzle direction is
//!   (−y, x)/r, must give the same bob path (a check of the frozen-mass rule under a change
//!   of coordinates: the polar equations carry ṁ r² θ̇ terms the Cartesian ones do not);
//! * each stepper's energy-budget residual ∫ power dt − (H − H₀) (docs/mechanics.md#energy-budget), an error estimate
//!   that needs no reference solution.
//!
//! Run with `cargo run --release --example leaking_spring_pendulum`.

use std::process::ExitCode;
use std::time::Instant;

use varmass::core::steppers::{ImplicitMidpointConfig, VariationalConfig};
use varmass::core::Record;
use varmass::prelude::*;

/// Polar form (`models/leaking_spring_pendulum.vms`): the bob at r (sin θ, −cos θ), the
/// exhaust leaving at −u_e ê_θ relative to it.
#[variable_mass_system(file = "models/leaking_spring_pendulum.vms")]
struct PolarPendulum {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

/// Cartesian form of the same system (`models/leaking_spring_pendulum_cartesian.vms`):
/// ê_θ = (−y, x)/r.
#[variable_mass_system(file = "models/leaking_spring_pendulum_cartesian.vms")]
struct CartesianPendulum {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

/// Start mass and dry mass (kg): the run ends as the propellant runs out.
const M0: f64 = 2.0;
const DRY_MASS: f64 = 0.5;
/// The start: stretched and swung out, at rest.
const R0: f64 = 1.1;
const THETA0: f64 = 0.5;
/// The largest difference allowed between the polar and the Cartesian bob paths (m), about
/// a thousand times the tolerance the tight runs are given.
const PATH_THRESHOLD: f64 = 1e-8;

/// One stepper's run of the polar system: its worst energy-budget residual, its H range
/// (for scale), the bob position at the end, its work and its wall time.
struct Outcome {
    method: String,
    residual: f64,
    energy_scale: f64,
    end: (f64, f64),
    steps: usize,
    seconds: f64,
}

fn polar_run<St>(method: String, mut stepper: St, end: f64) -> Result<Outcome, StepError<5>>
where
    St: Stepper<2, 5, System = PolarPendulum>,
{
    let config = RunConfig::until(end).recording(Record {
        hamiltonian: true,
        energy_residual: true,
        ..Record::default()
    });
    let started = Instant::now();
    let solution = run(&mut stepper, &config, &[])?;
    let seconds = started.elapsed().as_secs_f64();
    let residual = solution
        .energy_residual
        .iter()
        .fold(0.0f64, |worst, r| worst.max(r.abs()));
    let (lowest, highest) = solution
        .hamiltonian
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &h| {
            (lo.min(h), hi.max(h))
        });
    let state = solution.last().map_or(SVector::zeros(), |(_, s)| *s);
    Ok(Outcome {
        method,
        residual,
        energy_scale: highest - lowest,
        end: (state[0] * state[1].sin(), -state[0] * state[1].cos()),
        steps: solution.statistics.accepted_steps,
        seconds,
    })
}

fn simulate() -> Result<f64, StepError<5>> {
    let polar = PolarPendulum {
        mu: 0.05,
        u_e: 2.0,
        k: 200.0,
        l0: 1.0,
        g: 9.81,
    };
    let cartesian = CartesianPendulum {
        mu: polar.mu,
        u_e: polar.u_e,
        k: polar.k,
        l0: polar.l0,
        g: polar.g,
    };
    let end = (M0 - DRY_MASS) / polar.mu;
    let tight = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::default()
    });
    let start = SVector::<f64, 5>::from([R0, THETA0, 0.0, 0.0, M0]);
    let step = 1e-3;
    let implicit = ImplicitMidpointConfig {
        step,
        ..ImplicitMidpointConfig::default()
    };
    let variational = VariationalConfig {
        step,
        ..VariationalConfig::default()
    };
    let outcomes = [
        polar_run(
            format!("explicit Euler, h = {:.0e}", step / 10.0),
            ExplicitEuler::new(&polar, 0.0, start, FixedStep { step: step / 10.0 })?,
            end,
        )?,
        polar_run(
            format!("classical RK4, h = {step:.0e}"),
            ClassicalRk4::new(&polar, 0.0, start, FixedStep { step })?,
            end,
        )?,
        polar_run(
            "Dormand–Prince, tol = 1e-6".to_string(),
            DormandPrince::new(&polar, 0.0, start, StepControl::default())?,
            end,
        )?,
        polar_run(
            "Dormand–Prince, tol = 1e-12".to_string(),
            DormandPrince::new(&polar, 0.0, start, tight)?,
            end,
        )?,
        polar_run(
            format!("implicit midpoint, h = {step:.0e}"),
            ImplicitMidpoint::new(&polar, 0.0, start, implicit)?,
            end,
        )?,
        polar_run(
            format!("variational, h = {step:.0e}"),
            Variational::new(&polar, 0.0, start, variational)?,
            end,
        )?,
    ];

    // The Cartesian reference, from the same initial position at rest.
    let cartesian_start =
        SVector::<f64, 5>::from([R0 * THETA0.sin(), -R0 * THETA0.cos(), 0.0, 0.0, M0]);
    let mut stepper = DormandPrince::new(&cartesian, 0.0, cartesian_start, tight)?;
    let reference = run(&mut stepper, &RunConfig::until(end), &[])?;
    let bob = reference.last().map_or((0.0, 0.0), |(_, s)| (s[0], s[1]));

    println!("Leaking spring pendulum: m {M0} → {DRY_MASS} kg over {end} s (μ = {} kg/s, u_e = {} m/s along −ê_θ), k = {} N/m, l0 = {} m", polar.mu, polar.u_e, polar.k, polar.l0);
    println!(
        "Energy budget: |∫ power dt − (H − H₀)| (max over the run), against the range of H.\n"
    );
    println!(
        "{:<32} {:>12} {:>10} {:>9} {:>12} {:>10}",
        "method (polar form)", "|residual|", "H range", "steps", "|bob − ref|", "time"
    );
    let mut path_difference = f64::INFINITY;
    for o in &outcomes {
        let distance = (o.end.0 - bob.0).hypot(o.end.1 - bob.1);
        println!(
            "{:<32} {:>10.3e} J {:>8.2} J {:>9} {:>10.3e} m {:>7.1} ms",
            o.method,
            o.residual,
            o.energy_scale,
            o.steps,
            distance,
            o.seconds * 1e3
        );
        path_difference = path_difference.min(distance);
    }
    println!(
        "\nCartesian form (Dormand–Prince, tol = 1e-12): bob at ({:.10}, {:.10}) m after {} steps",
        bob.0, bob.1, reference.statistics.accepted_steps
    );
    println!("polar vs Cartesian bob position at burnout: {path_difference:.3e} m");
    Ok(path_difference)
}

fn main() -> ExitCode {
    println!("{}", PolarPendulum::DERIVATION);
    match simulate() {
        Ok(difference) if difference < PATH_THRESHOLD => ExitCode::SUCCESS,
        Ok(difference) => {
            eprintln!("the polar and Cartesian forms disagree by {difference:e} m");
            ExitCode::FAILURE
        }
        Err(error) => {
            eprintln!("a run failed: {error}");
            ExitCode::FAILURE
        }
    }
}
