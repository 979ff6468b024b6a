//! A spacecraft spinning at 2 rad/s about its axis of symmetry fires a thruster mounted
//! off the axis (`models/spinning_spacecraft.vms`): the thrust's torque about a transverse
//! body axis turns with the spin, so the spin axis cones and drifts instead of tipping over,
//! while the exhaust's jet damping and the shrinking inertias change the rates. Every term
//! comes from the outflow at the thruster's point (docs/mechanics.md#flows-at-points).
//!
//! Prints the spin rate, the tilt of the spin axis from its start and the energy budget
//! every 10 s of a 60 s burn. Run with `cargo run --release --example spinning_spacecraft`;
//! it exits non-zero if the energy budget (∫ power dt − (H − H₀), relative) exceeds 1e-9.

use std::process::ExitCode;

use varmass::core::Record;
use varmass::prelude::*;

#[variable_mass_system(file = "models/spinning_spacecraft.vms")]
#[allow(non_snake_case)] // the model's names
struct Spacecraft {
    mu: f64,
    m_s: f64,
    A_s: f64,
    C_s: f64,
    k: f64,
    r: f64,
    h: f64,
    u_e: f64,
}

/// The energy budget's acceptance threshold (relative to the range of H).
const THRESHOLD: f64 = 1e-9;

fn main() -> ExitCode {
    let craft = Spacecraft {
        mu: 0.02,
        m_s: 500.0,
        A_s: 300.0,
        C_s: 600.0,
        k: 0.5,
        r: 1.2,
        h: 0.8,
        u_e: 2200.0,
    };
    // At rest but for the spin psi' = 2 rad/s about the body axis; 50 kg of propellant.
    let mut velocity_state = SVector::<f64, 13>::zeros();
    velocity_state[9] = 2.0;
    velocity_state[12] = 50.0;
    let start = craft.momentum_state(0.0, &velocity_state);
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::default()
    });
    let record = Record {
        hamiltonian: true,
        energy_residual: true,
        ..Record::default()
    };
    let config = RunConfig::until(60.0).recording(record);
    let outcome = match DormandPrince::new(&craft, 0.0, start, control) {
        Ok(mut stepper) => run(&mut stepper, &config, &[]).map_err(|e| e.into_step_error()),
        Err(error) => Err(error),
    };
    let solution = match outcome {
        Ok(solution) => solution,
        Err(error) => {
            eprintln!("the run failed: {error}");
            return ExitCode::FAILURE;
        }
    };
    println!("    t      spin (rad/s)   axis tilt (deg)   m_p (kg)");
    let mut next = 0.0;
    for (&t, state) in solution.times.iter().zip(&solution.states) {
        if t < next {
            continue;
        }
        next += 10.0;
        let rates = craft.velocities(t, state).unwrap_or_default();
        let (th, phi) = (state[4], state[5]);
        // The body axis in world axes has z component cos th cos phi (zyx).
        let tilt = (th.cos() * phi.cos()).clamp(-1.0, 1.0).acos().to_degrees();
        let spin = rates[3] * th.cos() * phi.cos() - rates[4] * phi.sin();
        println!("{t:6.1}   {spin:12.6}   {tilt:15.6}   {:8.3}", state[12]);
    }
    let first = solution.hamiltonian[0];
    let scale = solution
        .hamiltonian
        .iter()
        .fold(0.0f64, |s, h| s.max(h.abs()).max((h - first).abs()));
    let worst = solution
        .energy_residual
        .iter()
        .fold(0.0f64, |w, r| w.max(r.abs()));
    let relative = worst / scale;
    println!("energy budget: worst residual {relative:.2e} of the range of H");
    if relative > THRESHOLD {
        eprintln!("the energy budget does not close to {THRESHOLD:e}");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
