//! Taylor's method in lanes (`run_lanes` with a `TaylorControl`) against Dormand–Prince in
//! lanes and the scalar Taylor stepper, per member, on issue 38's ensemble: 512 vertical
//! rockets (m = m0 − μt, m0 = 1 kg) with μ in 0.045–0.055 kg/s and u_e in 270–330 m/s,
//! flown from rest to 15 s, at tolerances 1e-6, 1e-9 and 1e-12 (relative = absolute), in
//! lanes of 4 and 8. Each configuration is timed as the fastest of up to 25 runs
//! (`common/timing.rs`), the configurations interleaved round after round so that a
//! machine's load falls on all of them; the error is the worst member's largest relative
//! error of height, speed and mass against the closed form.
//!
//! `cargo bench -p varmass-benches --bench taylor_lanes [-- FILTER]` (FILTER: only the
//! configurations whose name holds it, e.g. `"1e-9 taylor lanes 8"`, for a profile).

#[path = "common/timing.rs"]
#[allow(dead_code)]
mod timing;

use std::time::Duration;

use varmass::core::ensemble::member_rng;
use varmass::core::ensemble::rand::RngExt;
use varmass::core::lanes::{run_lanes, LaneEnd, LaneJob};
use varmass::prelude::*;

#[variable_mass_system(file = "../models/rocket.vms", emit = ["taylor", "lanes"])]
#[derive(Clone, Copy)]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

const MEMBERS: u64 = 512;
const M0: f64 = 1.0;
const G: f64 = 9.81;
const END: f64 = 15.0;

fn members() -> Vec<Rocket> {
    (0..MEMBERS)
        .map(|index| {
            let mut rng = member_rng(38, index);
            Rocket {
                mu: rng.random_range(0.045..0.055),
                u_e: rng.random_range(270.0..330.0),
                g: G,
            }
        })
        .collect()
}

/// The worst relative error of (y, v, m) at 15 s over the ends, against the closed form
/// v = u_e ln(m0/m) − g t, y = u_e (t − (m/μ) ln(m0/m)) − ½ g t².
fn worst(rockets: &[Rocket], ends: &[(f64, SVector<f64, 3>)]) -> f64 {
    let mut worst = 0.0_f64;
    for (r, (t, y)) in rockets.iter().zip(ends) {
        let m = M0 - r.mu * t;
        let log_ratio = (M0 / m).ln();
        let exact = [
            r.u_e * (t - m / r.mu * log_ratio) - 0.5 * G * t * t,
            r.u_e * log_ratio - G * t,
            m,
        ];
        let numerical = [y[0], y[1] / y[2], y[2]];
        for i in 0..3 {
            worst = worst.max((numerical[i] - exact[i]).abs() / exact[i].abs());
        }
    }
    worst
}

fn tolerance(tol: f64) -> Tolerance {
    Tolerance::new(tol, tol).expect("a usable tolerance")
}

fn dormand_prince(tol: f64) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tol,
        absolute_tolerance: tol,
        ..AdaptiveControl::default()
    })
}

fn ends(results: Vec<Result<LaneEnd<3>, StepError<3>>>) -> Vec<(f64, SVector<f64, 3>)> {
    results
        .into_iter()
        .map(|end| {
            let end = end.expect("every rocket reaches 15 s");
            (end.time, end.state)
        })
        .collect()
}

fn jobs(rockets: &[Rocket]) -> Vec<LaneJob<'static, Rocket, 3>> {
    rockets
        .iter()
        .map(|&system| LaneJob {
            system,
            time: 0.0,
            state: SVector::<f64, 3>::new(0.0, 0.0, M0),
            events: &[],
        })
        .collect()
}

/// One configuration: its name and the ensemble's ends.
type Config<'a> = (String, Box<dyn Fn() -> Vec<(f64, SVector<f64, 3>)> + 'a>);

fn configs<'a>(
    rockets: &'a [Rocket],
    jobs: &'a [LaneJob<'static, Rocket, 3>],
    tol: f64,
) -> Vec<Config<'a>> {
    let config = RunConfig::until(END);
    let taylor = TaylorControl::adaptive(tolerance(tol));
    let scalar = move || {
        rockets
            .iter()
            .map(|system| {
                let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
                let mut stepper = Taylor::new(system, 0.0, start, taylor).expect("valid");
                let solution = run(&mut stepper, &config, &[]).expect("a run to 15 s");
                let (t, y) = solution.last().expect("a point");
                (t, *y)
            })
            .collect()
    };
    vec![
        (format!("{tol:e} taylor scalar"), Box::new(scalar)),
        (
            format!("{tol:e} taylor lanes 4"),
            Box::new(move || ends(run_lanes::<_, 1, 3, 4>(jobs, taylor, &config))),
        ),
        (
            format!("{tol:e} taylor lanes 8"),
            Box::new(move || ends(run_lanes::<_, 1, 3, 8>(jobs, taylor, &config))),
        ),
        (
            format!("{tol:e} dopri lanes 4"),
            Box::new(move || ends(run_lanes::<_, 1, 3, 4>(jobs, dormand_prince(tol), &config))),
        ),
        (
            format!("{tol:e} dopri lanes 8"),
            Box::new(move || ends(run_lanes::<_, 1, 3, 8>(jobs, dormand_prince(tol), &config))),
        ),
    ]
}

fn main() {
    let rockets = members();
    let jobs = jobs(&rockets);
    let filter = std::env::args()
        .skip(1)
        .find(|a| !a.starts_with("--"))
        .unwrap_or_default();
    let all: Vec<Config<'_>> = [1e-6, 1e-9, 1e-12]
        .into_iter()
        .flat_map(|tol| configs(&rockets, &jobs, tol))
        .filter(|(name, _)| name.contains(&filter))
        .collect();
    let mut best = vec![Duration::MAX; all.len()];
    let mut errors = vec![0.0; all.len()];
    // Interleaved: round r times every configuration once, 25 rounds.
    for _ in 0..25 {
        for (i, (_, work)) in all.iter().enumerate() {
            let (elapsed, result) = timing::fastest_of(1, 1, Duration::ZERO, work);
            best[i] = best[i].min(elapsed);
            errors[i] = worst(&rockets, &result);
        }
    }
    println!("== {MEMBERS} rockets to 15 s, per member, fastest of 25 interleaved runs");
    println!(
        "{:<26} {:>12} {:>12}",
        "configuration", "µs/member", "worst error"
    );
    for (i, (name, _)) in all.iter().enumerate() {
        let per_member = best[i].as_secs_f64() * 1e6 / MEMBERS as f64;
        println!("{name:<26} {per_member:>12.3} {:>12.1e}", errors[i]);
    }
}
