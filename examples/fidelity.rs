//! Model only what a scene requires: two scenes, each run with its full model and with
//! reduced ones, compared on named observables at the same output times, with the cost of
//! each run (`varmass::core::fidelity`).
//!
//! * The vertical rocket of `models/rocket.vms` (m0 = 1000 kg, dry 100 kg, μ = 10 kg/s,
//!   u_e = 2500 m/s) burning for 90 s, then coasting to t = 600 s. The full model has its
//!   `[drag]` (k_d = 1e-3 kg/m); reduced: without drag, and a constant-mass approximation
//!   (`models/rocket_constant_mass.vms`: the mean mass 550 kg pushed by f_t = μ u_e).
//! * The paper's sled of `models/sled.vms` from rest for 4 s, with its `[impact]` (the
//!   momentum exchange with the snow) and without it.
//!
//! Run with `cargo run --release --example fidelity`.

use std::process::ExitCode;

use varmass::core::fidelity::{compare, measure, ModelRun};
use varmass::core::{observe, Observable, Recording};
use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket.vms", with = ["drag"])]
struct DraggedRocket {
    mu: f64,
    u_e: f64,
    g: f64,
    k_d: f64,
}

#[variable_mass_system(file = "models/rocket.vms")]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

#[variable_mass_system(file = "models/rocket_constant_mass.vms")]
struct ConstantMassRocket {
    m_c: f64,
    f_t: f64,
    g: f64,
}

#[variable_mass_system(file = "models/sled.vms", with = ["impact"])]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

#[variable_mass_system(file = "models/sled.vms")]
struct SledWithoutImpact {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

const M0: f64 = 1000.0;
const DRY: f64 = 100.0;
const MU: f64 = 10.0;
const U_E: f64 = 2500.0;
const G: f64 = 9.81;
const K_D: f64 = 1e-3;
/// Burnout: the propellant (900 kg) at 10 kg/s.
const BURNOUT: f64 = (M0 - DRY) / MU;
const END: f64 = 600.0;

/// Tight tolerances, so that the differences are the models', not the integration's.
fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-12,
        absolute_tolerance: 1e-12,
        ..AdaptiveControl::default()
    })
}

/// Every 10 s from 0 to the end, and burnout (90 s) among them.
fn rocket_times() -> Vec<f64> {
    (0..=60).map(|k| 10.0 * k as f64).collect()
}

/// Altitude and speed of a rocket whose state is [y, p, m].
fn burn_then_coast<A, B>(burning: &A, coasting: &B) -> Result<Recording, StepError<3>>
where
    A: VariableMassSystem<1, 3>,
    B: VariableMassSystem<1, 3>,
{
    let altitude = |_t: f64, s: &SVector<f64, 3>| s[0];
    let speed = |_t: f64, s: &SVector<f64, 3>| s[1] / s[2];
    let observables = [
        Observable::function("altitude (m)", &altitude),
        Observable::function("speed (m/s)", &speed),
    ];
    let times = rocket_times();
    let (burn_times, coast_times) = times.split_at(times.partition_point(|&t| t <= BURNOUT));
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let mut burn = DormandPrince::new(burning, 0.0, start, control())?;
    let mut recording = observe(&mut burn, burn_times, &observables)?;
    let mut coast = DormandPrince::new(coasting, BURNOUT, *burn.state(), control())?;
    recording.append(observe(&mut coast, coast_times, &observables)?);
    Ok(recording)
}

/// The constant-mass approximation: state [y, p], mass M throughout, thrust F while burning.
fn constant_mass(mass: f64) -> Result<Recording, StepError<2>> {
    let altitude = |_t: f64, s: &SVector<f64, 2>| s[0];
    let speed = |_t: f64, s: &SVector<f64, 2>| s[1] / mass;
    let observables = [
        Observable::function("altitude (m)", &altitude),
        Observable::function("speed (m/s)", &speed),
    ];
    let times = rocket_times();
    let (burn_times, coast_times) = times.split_at(times.partition_point(|&t| t <= BURNOUT));
    let burning = ConstantMassRocket {
        m_c: mass,
        f_t: MU * U_E,
        g: G,
    };
    let coasting = ConstantMassRocket {
        f_t: 0.0,
        ..burning
    };
    let mut burn = DormandPrince::new(&burning, 0.0, SVector::zeros(), control())?;
    let mut recording = observe(&mut burn, burn_times, &observables)?;
    let mut coast = DormandPrince::new(&coasting, BURNOUT, *burn.state(), control())?;
    recording.append(observe(&mut coast, coast_times, &observables)?);
    Ok(recording)
}

fn rocket_scene() -> Result<Vec<ModelRun>, String> {
    let full = measure("rocket with drag", || {
        let burning = DraggedRocket {
            mu: MU,
            u_e: U_E,
            g: G,
            k_d: K_D,
        };
        burn_then_coast(&burning, &DraggedRocket { mu: 0.0, ..burning })
    });
    let no_drag = measure("rocket without drag", || {
        let burning = Rocket {
            mu: MU,
            u_e: U_E,
            g: G,
        };
        burn_then_coast(&burning, &Rocket { mu: 0.0, ..burning })
    });
    let mean_mass = 0.5 * (M0 + DRY);
    let constant =
        measure("constant mass 550 kg", || constant_mass(mean_mass)).map_err(|e| e.to_string())?;
    let full = full.map_err(|e| e.to_string())?;
    let no_drag = no_drag.map_err(|e| e.to_string())?;
    Ok(vec![full, no_drag, constant])
}

fn sled_run<Sys: VariableMassSystem<1, 2>>(sled: &Sys) -> Result<Recording, StepError<2>> {
    let distance = |_t: f64, s: &SVector<f64, 2>| s[0];
    let speed = |t: f64, s: &SVector<f64, 2>| sled.velocities(t, s).map_or(f64::NAN, |v| v[0]);
    let observables = [
        Observable::function("distance (m)", &distance),
        Observable::function("speed (m/s)", &speed),
    ];
    let times: Vec<f64> = (0..=8).map(|k| 0.5 * k as f64).collect();
    let mut stepper = DormandPrince::new(sled, 0.0, SVector::zeros(), control())?;
    observe(&mut stepper, &times, &observables)
}

fn sled_scene() -> Result<Vec<ModelRun>, String> {
    let theta = 30f64.to_radians();
    let full = measure("sled with its impact force", || {
        sled_run(&Sled {
            m0: 10.0,
            c: 2.0,
            g: G,
            theta,
            f_d: 0.1,
        })
    });
    let reduced = measure("sled without it", || {
        sled_run(&SledWithoutImpact {
            m0: 10.0,
            c: 2.0,
            g: G,
            theta,
            f_d: 0.1,
        })
    });
    Ok(vec![
        full.map_err(|e| e.to_string())?,
        reduced.map_err(|e| e.to_string())?,
    ])
}

/// Prints every reduced model against the first (the full) one.
fn report(runs: &[ModelRun]) -> Result<(), String> {
    let (full, reduced) = runs.split_first().ok_or("no run")?;
    for run in reduced {
        let comparison = compare(full, run).map_err(|e| e.to_string())?;
        println!("{comparison}");
    }
    Ok(())
}

fn main() -> ExitCode {
    println!("== Scene 1: the vertical rocket, 90 s burn then coast to {END} s (every 10 s)\n");
    let rocket = rocket_scene().and_then(|runs| report(&runs));
    println!("== Scene 2: the paper's sled from rest, 4 s (every 0.5 s)\n");
    let sled = sled_scene().and_then(|runs| report(&runs));
    match rocket.and(sled) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("a run failed: {error}");
            ExitCode::FAILURE
        }
    }
}
