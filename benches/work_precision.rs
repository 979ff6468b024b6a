//! Work-precision: every stepper on every system with a closed-form reference (the paper's
//! sled to 50 m, the vertical rocket, a Kepler orbit), swept over step sizes (fixed-step
//! methods) or tolerances (adaptive Dormand–Prince, DOP853 and SDIRK4, and the `ode_solvers`
//! crate's Dopri5 and Dop853 as peers on the same right-hand side). One point per setting: the relative error at the end
//! against the reference, the fastest of several runs, and the work counters.
//!
//! Then the stiff scene (`common/stiff.rs`: the leaking spring pendulum, k = 1e2…1e8) for
//! Dormand–Prince, DOP853 and SDIRK4, the error being that of the angle at 10 s against a
//! tight explicit run.
//!
//! Then the high-order end at equal final error (`equal_error.rs`): DOP853's evaluations
//! and time against adaptive Dormand–Prince and `ode_solvers`' Dop853, each read off its
//! curve at the sled's 1e-12, the rocket's 1e-11 and the Kepler orbit's 1e-10.
//!
//! And DOP853's fixed-step errors and observed orders on the Kepler orbit beside those of
//! `ode_solvers`' Dop853 at the same steps (`fixed_orders.rs`).
//!
//! Writes a table to stdout, `docs/bench/work_precision.{csv,svg}`,
//! `docs/bench/equal_error.txt` and `docs/bench/stiff.{csv,svg}`.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench work_precision
//! ```

mod common;
mod equal_error;
mod fixed_orders;
mod plot;

use std::fmt::Write as _;
use std::path::PathBuf;

use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{
    AdaptiveControl, ClassicalRk4, Dop853, DormandPrince, ExplicitEuler, FixedStep,
    ImplicitMidpoint, ImplicitMidpointConfig, Sdirk4, StepControl, Taylor, TaylorControl,
    Variational, VariationalConfig,
};
use varmass::core::tolerance::{Floor, Tolerance};
use varmass::core::{Statistics, StepOutcome, Stepper, VariableMassSystem};

use common::diffsol_peer::{run_diffsol, DiffsolMethod};
use common::problems::{KeplerProblem, Problem, RocketProblem, SledProblem};
use common::stiff::{self, StiffScene};
use common::timing::fastest;

/// A stepper and how it is configured.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Explicit Euler, fixed step.
    Euler,
    /// Classical RK4, fixed step.
    Rk4,
    /// Dormand–Prince 5(4), fixed step.
    DormandPrinceFixed,
    /// Dormand–Prince 5(4), adaptive (PI control).
    DormandPrinceAdaptive,
    /// Implicit midpoint (Newton on the generated Jacobian), fixed step.
    ImplicitMidpoint,
    /// The variational integrator of the corrected principle, fixed step.
    Variational,
    /// `ode_solvers::Dopri5` on the same state rate: the peer.
    PeerDopri5,
    /// DOP853, adaptive, without dense output (as the peer's sparse output).
    Dop853,
    /// `ode_solvers::Dop853` on the same state rate: the high-order peer.
    PeerDop853,
    /// SDIRK4, adaptive, L-stable (Newton on the generated Jacobian).
    Sdirk4,
    /// ESDIRK4(3)6L[2]SA, adaptive, L-stable, explicit first stage (stiff scene only).
    Esdirk43,
    /// diffsol's BDF on the same state rate and Jacobian: the stiff peer (stiff scene only).
    PeerDiffsolBdf,
    /// diffsol's ESDIRK34 on the same state rate and Jacobian (stiff scene only).
    PeerDiffsolEsdirk34,
    /// Taylor's method on the emitted recurrences, order and step from the tolerance.
    Taylor,
}

impl Method {
    const ALL: [Method; 11] = [
        Method::Euler,
        Method::Rk4,
        Method::DormandPrinceFixed,
        Method::DormandPrinceAdaptive,
        Method::ImplicitMidpoint,
        Method::Variational,
        Method::PeerDopri5,
        Method::Dop853,
        Method::PeerDop853,
        Method::Sdirk4,
        Method::Taylor,
    ];

    /// The methods run on the stiff scene only (after [`Method::ALL`] in the plots).
    const STIFF_ONLY: [Method; 3] = [
        Method::Esdirk43,
        Method::PeerDiffsolBdf,
        Method::PeerDiffsolEsdirk34,
    ];

    /// The name in tables, the CSV and the plot legend.
    pub fn name(self) -> &'static str {
        match self {
            Method::Euler => "Euler",
            Method::Rk4 => "RK4",
            Method::DormandPrinceFixed => "DP5 fixed",
            Method::DormandPrinceAdaptive => "DP5 adaptive",
            Method::ImplicitMidpoint => "implicit midpoint",
            Method::Variational => "variational",
            Method::PeerDopri5 => "ode_solvers Dopri5",
            Method::Dop853 => "DOP853",
            Method::PeerDop853 => "ode_solvers Dop853",
            Method::Sdirk4 => "SDIRK4",
            Method::Esdirk43 => "ESDIRK4(3)",
            Method::PeerDiffsolBdf => "diffsol BDF",
            Method::PeerDiffsolEsdirk34 => "diffsol ESDIRK34",
            Method::Taylor => "Taylor",
        }
    }

    fn adaptive(self) -> bool {
        matches!(
            self,
            Method::DormandPrinceAdaptive
                | Method::PeerDopri5
                | Method::Dop853
                | Method::PeerDop853
                | Method::Sdirk4
                | Method::Esdirk43
                | Method::PeerDiffsolBdf
                | Method::PeerDiffsolEsdirk34
                | Method::Taylor
        )
    }

    /// The sweep: tolerances 1e-3…1e-13 for adaptive methods, step counts 2^k otherwise,
    /// ranges chosen per order so that each method spans its useful accuracies without
    /// spending minutes on Euler at 1e-9.
    fn settings(self) -> Vec<f64> {
        let powers = |from: i32, to: i32, by: usize| -> Vec<f64> {
            (from..=to).step_by(by).map(|k| 2f64.powi(k)).collect()
        };
        match self {
            Method::DormandPrinceAdaptive
            | Method::PeerDopri5
            | Method::Dop853
            | Method::PeerDop853 => (3..=13).map(|k| 10f64.powi(-k)).collect(),
            // Down to the method's floor, `Floor::Taylor`.
            Method::Taylor => (3..=15).map(|k| 10f64.powi(-k)).collect(),
            Method::Sdirk4
            | Method::Esdirk43
            | Method::PeerDiffsolBdf
            | Method::PeerDiffsolEsdirk34 => (3..=11).map(|k| 10f64.powi(-k)).collect(),
            Method::Euler => powers(8, 20, 2),
            Method::Rk4 => powers(5, 16, 1),
            Method::DormandPrinceFixed => powers(4, 13, 1),
            Method::ImplicitMidpoint | Method::Variational => powers(6, 18, 2),
        }
    }
}

/// One point of the sweep.
#[derive(Clone, Debug)]
pub struct Point {
    /// The problem's name.
    pub problem: &'static str,
    /// The method.
    pub method: Method,
    /// The tolerance (adaptive) or the number of steps (fixed).
    pub setting: f64,
    /// Relative error at the end against the closed form.
    pub error: f64,
    /// Fastest wall time of one whole run, in seconds.
    pub seconds: f64,
    /// The work counters of the run.
    pub statistics: Statistics,
}

/// Steps to `end` and returns the final time, state and counters.
fn integrate<St, const N: usize, const S: usize>(
    mut stepper: St,
    end: f64,
) -> Result<(f64, SVector<f64, S>, Statistics), String>
where
    St: Stepper<N, S>,
{
    stepper.set_stop_time(end).map_err(|e| e.to_string())?;
    loop {
        match stepper.step() {
            Ok(StepOutcome::ReachedStopTime) => break,
            Ok(StepOutcome::Advanced) => {}
            Err(error) => return Err(error.to_string()),
        }
    }
    Ok((stepper.time(), *stepper.state(), *stepper.statistics()))
}

/// The peer's view of a system: `ode_solvers` needs its own nalgebra's vector type; the
/// copies in and out are a few floats per call, negligible next to the state rate. (`N` is
/// named so that the trait impl can name the system's trait.)
struct PeerSystem<'a, Sys, const N: usize, const S: usize>(&'a Sys);

impl<Sys, const N: usize, const S: usize> ode_solvers::System<f64, ode_solvers::SVector<f64, S>>
    for PeerSystem<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    fn system(
        &self,
        t: f64,
        y: &ode_solvers::SVector<f64, S>,
        dy: &mut ode_solvers::SVector<f64, S>,
    ) {
        let state = SVector::<f64, S>::from_column_slice(y.as_slice());
        // A failed evaluation becomes NaN, which makes the peer's error test reject the step.
        let rate = self
            .0
            .state_rate(t, &state)
            .unwrap_or(SVector::from_element(f64::NAN));
        dy.as_mut_slice().copy_from_slice(rate.as_slice());
    }
}

/// Runs one of the `ode_solvers` peers (same constructor for both) and returns what
/// `integrate` returns for ours.
macro_rules! run_peer {
    ($solver:ty, $system:expr, $start:expr, $end:expr, $tolerance:expr, $controller:expr) => {{
        let (safety, beta, fac_min, fac_max) = $controller;
        let y0 = ode_solvers::SVector::<f64, S>::from_column_slice($start.as_slice());
        // Sparse output: the state at every accepted step, of which the last is at `end`.
        // (Dense output at `dx = end` returned a wrong final state in ode_solvers 0.6.2,
        // see the README.)
        let mut solver = <$solver>::from_param(
            PeerSystem::<Sys, N, S>($system),
            0.0,
            $end,
            $end,
            y0,
            $tolerance,
            $tolerance,
            safety,
            beta,
            fac_min,
            fac_max,
            $end,
            0.0,
            10_000_000,
            1000,
            ode_solvers::OutputType::Sparse,
        );
        let stats = solver.integrate().map_err(|e| e.to_string())?;
        let (Some(t), Some(y)) = (solver.x_out().last(), solver.y_out().last()) else {
            return Err("the peer returned no output".into());
        };
        let statistics = Statistics {
            accepted_steps: stats.accepted_steps as usize,
            rejected_steps: stats.rejected_steps as usize,
            rate_evaluations: stats.num_eval as usize,
            ..Statistics::default()
        };
        Ok((*t, SVector::from_column_slice(y.as_slice()), statistics))
    }};
}

/// `ode_solvers::Dopri5` with Hairer's `dopri5` defaults (as ours).
fn run_peer_dopri5<Sys, const N: usize, const S: usize>(
    system: &Sys,
    start: SVector<f64, S>,
    end: f64,
    tolerance: f64,
) -> Result<(f64, SVector<f64, S>, Statistics), String>
where
    Sys: VariableMassSystem<N, S>,
{
    let controller = (0.9, 0.04, 0.2, 10.0);
    run_peer!(ode_solvers::Dopri5<_, _, _>, system, start, end, tolerance, controller)
}

/// `ode_solvers::Dop853` with Hairer's `dop853` defaults (as [`AdaptiveControl::dop853`]).
fn run_peer_dop853<Sys, const N: usize, const S: usize>(
    system: &Sys,
    start: SVector<f64, S>,
    end: f64,
    tolerance: f64,
) -> Result<(f64, SVector<f64, S>, Statistics), String>
where
    Sys: VariableMassSystem<N, S>,
{
    let controller = (0.9, 0.0, 1.0 / 3.0, 6.0);
    run_peer!(ode_solvers::Dop853<_, _, _>, system, start, end, tolerance, controller)
}

/// One run of `method` at `setting` on `problem`.
fn run_once<P, const N: usize, const S: usize>(
    problem: &P,
    method: Method,
    setting: f64,
) -> Result<(f64, SVector<f64, S>, Statistics), String>
where
    P: Problem<N, S>,
{
    let (y0, end) = (problem.initial_state(), problem.end_time());
    run_method(problem.system(), (y0, end), method, setting)
}

/// One run of `method` at `setting` on `system` from `y0` at t = 0 to `end`.
fn run_method<Sys, const N: usize, const S: usize>(
    system: &Sys,
    (y0, end): (SVector<f64, S>, f64),
    method: Method,
    setting: f64,
) -> Result<(f64, SVector<f64, S>, Statistics), String>
where
    Sys: VariableMassSystem<N, S>,
{
    let step = end / setting;
    let fixed = FixedStep { step };
    let started = |e: varmass::core::StepError<S>| e.to_string();
    match method {
        Method::Euler => integrate(
            ExplicitEuler::new(system, 0.0, y0, fixed).map_err(started)?,
            end,
        ),
        Method::Rk4 => integrate(
            ClassicalRk4::new(system, 0.0, y0, fixed).map_err(started)?,
            end,
        ),
        Method::DormandPrinceFixed => integrate(
            DormandPrince::new(system, 0.0, y0, StepControl::Fixed(fixed)).map_err(started)?,
            end,
        ),
        Method::DormandPrinceAdaptive => {
            let control = AdaptiveControl {
                relative_tolerance: setting,
                absolute_tolerance: setting,
                ..AdaptiveControl::default()
            };
            integrate(
                DormandPrince::new(system, 0.0, y0, StepControl::Adaptive(control))
                    .map_err(started)?,
                end,
            )
        }
        Method::ImplicitMidpoint => {
            let config = ImplicitMidpointConfig {
                step,
                ..ImplicitMidpointConfig::default()
            };
            integrate(
                ImplicitMidpoint::new(system, 0.0, y0, config).map_err(started)?,
                end,
            )
        }
        Method::Variational => {
            let config = VariationalConfig {
                step,
                ..VariationalConfig::default()
            };
            integrate(
                Variational::new(system, 0.0, y0, config).map_err(started)?,
                end,
            )
        }
        Method::Taylor => {
            let tolerance =
                Tolerance::for_floor(setting, setting, Floor::Taylor).map_err(|e| e.to_string())?;
            let control = TaylorControl::adaptive(tolerance);
            integrate(Taylor::new(system, 0.0, y0, control).map_err(started)?, end)
        }
        Method::PeerDopri5 => run_peer_dopri5(system, y0, end, setting),
        Method::PeerDop853 => run_peer_dop853(system, y0, end, setting),
        Method::Dop853 => {
            let control = AdaptiveControl {
                relative_tolerance: setting,
                absolute_tolerance: setting,
                ..AdaptiveControl::dop853()
            };
            let stepper = Dop853::new(system, 0.0, y0, StepControl::Adaptive(control));
            integrate(stepper.map_err(started)?.without_dense_output(), end)
        }
        Method::Sdirk4 => {
            let control = AdaptiveControl {
                relative_tolerance: setting,
                absolute_tolerance: setting,
                ..AdaptiveControl::sdirk4()
            };
            integrate(
                Sdirk4::new(system, 0.0, y0, StepControl::Adaptive(control)).map_err(started)?,
                end,
            )
        }
        Method::Esdirk43 => {
            let control = AdaptiveControl {
                relative_tolerance: setting,
                absolute_tolerance: setting,
                ..AdaptiveControl::sdirk4()
            };
            integrate(
                varmass::core::steppers::Esdirk43::new(
                    system,
                    0.0,
                    y0,
                    StepControl::Adaptive(control),
                )
                .map_err(started)?,
                end,
            )
        }
        Method::PeerDiffsolBdf => run_diffsol(system, (y0, end), DiffsolMethod::Bdf, setting),
        Method::PeerDiffsolEsdirk34 => {
            run_diffsol(system, (y0, end), DiffsolMethod::Esdirk34, setting)
        }
    }
}

/// The sweep of every method on `problem`.
fn sweep<P, const N: usize, const S: usize>(problem: &P, points: &mut Vec<Point>)
where
    P: Problem<N, S>,
{
    for method in Method::ALL {
        for setting in method.settings() {
            let (elapsed, outcome) = fastest(|| run_once(problem, method, setting));
            let (time, state, statistics) = match outcome {
                Ok(result) => result,
                Err(error) => {
                    println!(
                        "{:<24} {:<20} {setting:>9.1e}  failed: {error}",
                        P::NAME,
                        method.name()
                    );
                    continue;
                }
            };
            let error = problem.error(time, &state);
            let point = Point {
                problem: P::NAME,
                method,
                setting,
                error,
                seconds: elapsed.as_secs_f64(),
                statistics,
            };
            println!("{}", row(&point));
            points.push(point);
            // Past the rounding floor a finer setting only costs time.
            if error < 1e-13 {
                break;
            }
        }
    }
}

/// The stiff scene: Dormand–Prince, DOP853, SDIRK4, ESDIRK4(3) and diffsol's BDF and
/// ESDIRK34 on the leaking spring pendulum for each stiffness, the error being that of
/// θ(10), at tolerances 1e-4…1e-11, every decade: the methods map a tolerance to quite
/// different errors, so they are compared at equal error.
fn stiff_sweep(points: &mut Vec<Point>) -> Result<(), Box<dyn std::error::Error>> {
    for (k, name) in stiff::SCENES {
        let scene = StiffScene::new(k, name)?;
        for method in [
            Method::DormandPrinceAdaptive,
            Method::Dop853,
            Method::Sdirk4,
            Method::Esdirk43,
            Method::PeerDiffsolBdf,
            Method::PeerDiffsolEsdirk34,
        ] {
            for exponent in 4..=11 {
                let setting = 10f64.powi(-exponent);
                let start = (scene.start(), stiff::END);
                let (elapsed, outcome) =
                    fastest(|| run_method(&scene.system, start, method, setting));
                let (_, state, statistics) = match outcome {
                    Ok(result) => result,
                    Err(error) => {
                        println!(
                            "{name:<24} {:<20} {setting:>9.1e}  failed: {error}",
                            method.name()
                        );
                        continue;
                    }
                };
                let point = Point {
                    problem: name,
                    method,
                    setting,
                    error: scene.error(&state),
                    seconds: elapsed.as_secs_f64(),
                    statistics,
                };
                println!("{}", row(&point));
                points.push(point);
            }
        }
    }
    Ok(())
}

fn row(point: &Point) -> String {
    let setting = if point.method.adaptive() {
        format!("tol {:.0e}", point.setting)
    } else {
        format!("{} steps", point.setting)
    };
    format!(
        "{:<24} {:<20} {:>14} {:>10.2e} {:>12.1} {:>10} {:>8} {:>8} {:>6}",
        point.problem,
        point.method.name(),
        setting,
        point.error,
        point.seconds * 1e6,
        point.statistics.rate_evaluations,
        point.statistics.jacobian_evaluations,
        point.statistics.accepted_steps,
        if point.statistics.stiffness_detected {
            "stiff"
        } else {
            ""
        },
    )
}

fn csv(points: &[Point]) -> String {
    let mut out = String::from(
        "problem,method,setting,error,seconds,rate_evaluations,jacobian_evaluations,newton_iterations,accepted_steps,rejected_steps,stiffness_detected\n",
    );
    for p in points {
        let s = &p.statistics;
        let _ = writeln!(
            out,
            "\"{}\",\"{}\",{:e},{:e},{:e},{},{},{},{},{},{}",
            p.problem,
            p.method.name(),
            p.setting,
            p.error,
            p.seconds,
            s.rate_evaluations,
            s.jacobian_evaluations,
            s.newton_iterations,
            s.accepted_steps,
            s.rejected_steps,
            s.stiffness_detected
        );
    }
    out
}

/// The equal-error table of the high-order end (see `equal_error.rs`) at the errors the
/// comparison is made at: the sled's 1e-12, the rocket's 1e-11, the Kepler orbit's 1e-10
/// (the criteria are judged on the sled and the orbit; the rocket is shown for reference).
fn equal_error_summary(points: &[Point]) -> String {
    let mut lines = vec![equal_error::header()];
    let sled = SledProblem::standard();
    let costs = equal_error::costs(&sled, points, 1e-12);
    lines.extend(equal_error::rows(SledProblem::NAME, 1e-12, &costs, true));
    let rocket = RocketProblem::standard();
    let costs = equal_error::costs(&rocket, points, 1e-11);
    lines.extend(equal_error::rows(RocketProblem::NAME, 1e-11, &costs, false));
    let kepler = KeplerProblem::standard();
    let costs = equal_error::costs(&kepler, points, 1e-10);
    lines.extend(equal_error::rows(KeplerProblem::NAME, 1e-10, &costs, true));
    lines.join("\n") + "\n"
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!(
        "{:<24} {:<20} {:>14} {:>10} {:>12} {:>10} {:>8} {:>8}",
        "problem",
        "method",
        "setting",
        "rel. error",
        "time (µs)",
        "rate evals",
        "Jacobians",
        "steps"
    );
    let mut points = Vec::new();
    sweep(&SledProblem::standard(), &mut points);
    sweep(&RocketProblem::standard(), &mut points);
    sweep(&KeplerProblem::standard(), &mut points);

    let folder = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../docs/bench");
    std::fs::create_dir_all(&folder)?;
    std::fs::write(folder.join("work_precision.csv"), csv(&points))?;
    let problems = [SledProblem::NAME, RocketProblem::NAME, KeplerProblem::NAME];
    plot::work_precision(&folder.join("work_precision.svg"), &problems, &points)?;
    println!(
        "wrote {}",
        folder.join("work_precision.{csv,svg}").display()
    );
    let summary =
        equal_error_summary(&points) + "\n" + &fixed_orders::table(&KeplerProblem::standard());
    println!("{summary}");
    std::fs::write(folder.join("equal_error.txt"), summary)?;

    let mut stiff_points = Vec::new();
    stiff_sweep(&mut stiff_points)?;
    std::fs::write(folder.join("stiff.csv"), csv(&stiff_points))?;
    let scenes = stiff::SCENES.map(|(_, name)| name);
    plot::work_precision(&folder.join("stiff.svg"), &scenes, &stiff_points)?;
    println!("wrote {}", folder.join("stiff.{csv,svg}").display());
    Ok(())
}
