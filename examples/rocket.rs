//! A vertical rocket in uniform gravity: a state mass burning at a constant rate μ with the
//! exhaust leaving at −u_e relative to the rocket, up to burnout at the dry mass, then a
//! ballistic coast to the apex. Each phase is checked against its closed form (docs/mechanics.md#vertical-rocket):
//!
//! * burning, m = m0 − μ t: v(t) = u_e ln(m0/m) − g t,
//!   y(t) = u_e (t − (m/μ) ln(m0/m)) − ½ g t² (Tsiolkovsky with gravity loss);
//! * coasting from burnout (t_b, y_b, v_b): apex at t_b + v_b/g, height y_b + v_b²/(2g).
//!
//! Run with `cargo run --release --example rocket`; it exits non-zero if an error exceeds
//! 1e-9 (relative).

use std::process::ExitCode;

use varmass::prelude::*;

/// The rocket of `models/rocket.vms`, without its optional `[drag]`: the reactive thrust
/// R1 = μ·(−u_e) is derived from the outflow, and the checks restate Meshchersky's equation
/// m ÿ = −m g + μ u_e.
#[variable_mass_system(file = "models/rocket.vms")]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

/// Acceptance threshold on every relative error below.
const THRESHOLD: f64 = 1e-9;
/// The relative error of a quantity that starts at zero is measured from this time on.
const MEASURED_FROM: f64 = 1.0;

/// Starting mass, dry mass (kg).
const M0: f64 = 1000.0;
const DRY_MASS: f64 = 100.0;

impl Rocket {
    /// (y, v) while burning from rest at y = 0 (docs/mechanics.md#vertical-rocket).
    fn burning(&self, t: f64) -> (f64, f64) {
        let m = M0 - self.mu * t;
        let log_ratio = (M0 / m).ln();
        let v = self.u_e * log_ratio - self.g * t;
        let y = self.u_e * (t - m / self.mu * log_ratio) - 0.5 * self.g * t * t;
        (y, v)
    }
}

fn relative(numeric: f64, exact: f64) -> f64 {
    (numeric - exact).abs() / exact.abs()
}

fn simulate() -> Result<f64, StepError<3>> {
    let engine = Rocket {
        mu: 10.0,
        u_e: 2500.0,
        g: 9.81,
    };
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-13,
        ..AdaptiveControl::default()
    });

    // Phase 1: burn from rest until the dry mass is reached.
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let mut burn = DormandPrince::new(&engine, 0.0, start, control)?;
    let burnout = Event::mass_reaches(0, DRY_MASS);
    let powered = run(&mut burn, &RunConfig::until(1e4), &[burnout])?;
    let mut worst_y: f64 = 0.0;
    let mut worst_v: f64 = 0.0;
    for (&t, state) in powered.times.iter().zip(&powered.states) {
        if t >= MEASURED_FROM {
            let (y, v) = engine.burning(t);
            worst_y = worst_y.max(relative(state[0], y));
            worst_v = worst_v.max(relative(state[1] / state[2], v));
        }
    }
    let (t_b, burnout_state) = powered.last().ok_or_else(|| {
        StepError::invalid_configuration(
            burn.time(),
            *burn.state(),
            "the powered run returned no point",
        )
    })?;
    let burnout_state = *burnout_state;
    let t_burn_exact = (M0 - DRY_MASS) / engine.mu;
    let (y_b, v_b) = engine.burning(t_burn_exact);
    let v_numeric = burnout_state[1] / burnout_state[2];
    let tsiolkovsky = engine.u_e * (M0 / DRY_MASS).ln();
    println!(
        "Vertical rocket: m0 = {M0} kg, dry {DRY_MASS} kg, μ = {} kg/s, u_e = {} m/s, g = {} m/s²",
        engine.mu, engine.u_e, engine.g
    );
    println!(
        "Phase 1, burning (Dormand–Prince, tol 1e-13): {} steps",
        powered.statistics.accepted_steps
    );
    println!(
        "  burnout at t = {t_b:.12} s (exact {t_burn_exact} s), mass {:.12} kg",
        burnout_state[2]
    );
    println!("  v_b = {v_numeric:.9} m/s; Tsiolkovsky u_e ln(m0/m1) − g t_b = {tsiolkovsky:.9} − {:.9} = {v_b:.9} m/s", engine.g * t_burn_exact);
    println!("  max relative error over the burn (t ≥ {MEASURED_FROM} s): y {worst_y:.2e}, v {worst_v:.2e}");
    let burnout_errors = [
        relative(t_b, t_burn_exact),
        relative(burnout_state[0], y_b),
        relative(v_numeric, v_b),
    ];
    println!(
        "  at burnout: t {:.2e}, y {:.2e}, v {:.2e}",
        burnout_errors[0], burnout_errors[1], burnout_errors[2]
    );

    // Phase 2: the same rocket with the engine off (μ = 0), from the burnout state.
    let coasting = Rocket { mu: 0.0, ..engine };
    let mut coast = DormandPrince::new(&coasting, t_b, burnout_state, control)?;
    let apex = Event::state_reaches(1, 0.0, Direction::Falling);
    let ballistic = run(&mut coast, &RunConfig::until(1e4), &[apex])?;
    let (t_apex, apex_state) = ballistic.last().ok_or_else(|| {
        StepError::invalid_configuration(
            coast.time(),
            *coast.state(),
            "the ballistic run returned no point",
        )
    })?;
    let t_apex_exact = t_burn_exact + v_b / engine.g;
    let y_apex_exact = y_b + v_b * v_b / (2.0 * engine.g);
    let apex_errors = [
        relative(t_apex, t_apex_exact),
        relative(apex_state[0], y_apex_exact),
    ];
    println!(
        "Phase 2, ballistic (μ = 0 from the burnout state): {} steps",
        ballistic.statistics.accepted_steps
    );
    println!("  apex at t = {t_apex:.9} s (exact {t_apex_exact:.9} s), y = {:.6} m (exact {y_apex_exact:.6} m)", apex_state[0]);
    println!(
        "  relative error: time {:.2e}, height {:.2e}",
        apex_errors[0], apex_errors[1]
    );

    Ok(burnout_errors
        .iter()
        .chain(&apex_errors)
        .fold(worst_y.max(worst_v), |worst, e| worst.max(*e)))
}

fn main() -> ExitCode {
    println!("{}", Rocket::DERIVATION);
    match simulate() {
        Ok(error) => {
            println!("max relative error vs closed forms: {error:.3e}");
            if error < THRESHOLD {
                ExitCode::SUCCESS
            } else {
                eprintln!("an error is not below {THRESHOLD:e}");
                ExitCode::FAILURE
            }
        }
        Err(error) => {
            eprintln!("a run failed: {error}");
            ExitCode::FAILURE
        }
    }
}
