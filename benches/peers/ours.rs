//! Our side of the comparison with heyoka (`benches/peers/heyoka.py` runs this binary and
//! heyoka in one session, the points in a shuffled order, and writes the table): the Taylor
//! stepper on the emitted recurrences, and DOP853, on the sled to 50 m, Kepler e = 0.5 over
//! three orbits and the planar 3-link pendulum over 10 s, swept over tolerances; on Kepler
//! also the Taylor stepper with its double-double head (`taylor-head`: `emit = [..., "head"]`,
//! `Taylor::with_head`; the other two problems call sin and cos, which have no head yet).
//! One line per point, tab-separated: problem, method, tolerance, achieved error, fastest
//! seconds per run, steps, the final state's components. Each point's Taylor stepper is made
//! once and restarted before every run, as the script resets heyoka's integrator: what is
//! timed (inside Rust, `Instant` around one run) is the integration alone (DOP853, which
//! allocates nothing, is made afresh). The script measures every error itself, from the
//! final states, against references independent of varmass.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench peers            # the sweep
//! cargo bench -p varmass-benches --bench peers -- rates   # initial states and rates
//! # points read from stdin, `<problem> <method> <tolerance>` a line, each answered by its line
//! echo "kepler taylor 1e-12" | cargo bench -p varmass-benches --bench peers -- serve
//! # one point run `runs` times, for `perf stat` (instructions per run do not depend on load)
//! cargo bench -p varmass-benches --bench peers -- only kepler taylor 1e-12 1000
//! ```
//!
//! The pendulum's error printed here is against our own Taylor method at order 30 and step
//! 1/200 s (its distance to the run at step 1/400 s is printed with `rates`: 1.3e-14); the
//! script measures it against an independent reference instead (`pendulum3_reference.py`),
//! from which ours is 1.07e-14 off.

#[path = "../common/mod.rs"]
mod common;

use std::time::Duration;

use common::problems::{KeplerProblem, Problem, RocketProblem, SledProblem};
use common::timing::fastest_of;
use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{AdaptiveControl, Dop853, StepControl, Taylor, TaylorControl};
use varmass::core::{Statistics, StepOutcome, Stepper};
use varmass::prelude::*;

/// The planar 3-link pendulum: equal bobs m on massless links l, angles from the downward
/// vertical, constant masses.
#[variable_mass_system(
    "
    coordinates a1, a2, a3
    mass m1 = m
    mass m2 = m
    mass m3 = m
    body bob1: mass m1, position [l*sin(a1), -l*cos(a1)]
    body bob2: mass m2, position [l*sin(a1) + l*sin(a2), -l*cos(a1) - l*cos(a2)]
    body bob3: mass m3, position [l*sin(a1) + l*sin(a2) + l*sin(a3), -l*cos(a1) - l*cos(a2) - l*cos(a3)]
    potential -m*g*l*(3*cos(a1) + 2*cos(a2) + cos(a3))
",
    emit = ["taylor"]
)]
#[derive(Clone, Copy, Debug)]
struct Pendulum3 {
    m: f64,
    l: f64,
    g: f64,
}

const PENDULUM: Pendulum3 = Pendulum3 {
    m: 1.0,
    l: 1.0,
    g: 9.81,
};
const PENDULUM_END: f64 = 10.0;

fn pendulum_start() -> SVector<f64, 6> {
    SVector::<f64, 6>::from_column_slice(&[0.6, -0.4, 0.3, 0.0, 0.0, 0.0])
}

/// Steps to `end`; the final state and counters.
fn integrate<St: Stepper<N, S>, const N: usize, const S: usize>(
    mut stepper: St,
    end: f64,
) -> (SVector<f64, S>, Statistics) {
    stepper.set_stop_time(end).expect("a stop time ahead");
    while stepper.step().expect("the run succeeds") != StepOutcome::ReachedStopTime {}
    (*stepper.state(), *stepper.statistics())
}

/// One run of `stepper` from `y0` at t = 0 to `end`, restarted there first. The Taylor
/// stepper is timed as heyoka's runs are: made once, before the timing, and restarted by
/// each run (heyoka's script makes its integrator once and resets its time and state), so
/// that its scratch is sized once; its steps depend on the state alone, so a restarted
/// run is the run a new stepper takes (same steps, same final state). The final state and
/// the steps of this run.
fn rerun<St: Stepper<N, S>, const N: usize, const S: usize>(
    stepper: &mut St,
    (y0, end): (SVector<f64, S>, f64),
) -> (SVector<f64, S>, usize) {
    stepper.restart(0.0, y0).expect("a finite start");
    stepper.set_stop_time(end).expect("a stop time ahead");
    let before = stepper.statistics().accepted_steps;
    while stepper.step().expect("the run succeeds") != StepOutcome::ReachedStopTime {}
    let steps = stepper.statistics().accepted_steps - before;
    (*stepper.state(), steps)
}

/// The fastest of `timing`'s runs of `method` at `tolerance` (see [`rerun`]), and the last
/// run's final state and steps.
fn run<Sys: VariableMassSystem<N, S>, const N: usize, const S: usize>(
    system: &Sys,
    start: (SVector<f64, S>, f64),
    (method, tolerance): (&str, f64),
    timing: Timing,
) -> (Duration, (SVector<f64, S>, usize)) {
    let y0 = start.0;
    if method == "taylor" || method == "taylor-head" {
        let head = method == "taylor-head";
        let floor = if head {
            Floor::TaylorHead
        } else {
            Floor::Taylor
        };
        let control =
            TaylorControl::adaptive(Tolerance::for_floor(tolerance, tolerance, floor).unwrap());
        let mut stepper = if head {
            Taylor::with_head(system, 0.0, y0, control).expect("the system has a head")
        } else {
            Taylor::new(system, 0.0, y0, control).unwrap()
        };
        timing.fastest(|| rerun(&mut stepper, start))
    } else {
        let control = StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: tolerance,
            absolute_tolerance: tolerance,
            ..AdaptiveControl::dop853()
        });
        // Made afresh for every run (it allocates nothing): a restarted DOP853 would start
        // from the last run's final step, not from its initial step guess.
        timing.fastest(|| {
            let stepper = Dop853::new(system, 0.0, y0, control).unwrap();
            rerun(&mut stepper.without_dense_output(), start)
        })
    }
}

/// How many runs a point is timed over.
#[derive(Clone, Copy)]
enum Timing {
    /// The sweep's rule: 3 to 1000 runs, about 0.15 s.
    Sweep,
    /// Exactly this many runs.
    Runs(usize),
}

impl Timing {
    fn fastest<T>(self, work: impl FnMut() -> T) -> (Duration, T) {
        match self {
            Timing::Sweep => fastest_of(3, 1000, Duration::from_millis(150), work),
            Timing::Runs(runs) => fastest_of(runs, runs, Duration::ZERO, work),
        }
    }
}

/// The pendulum at 10 s by Taylor at order 30 and `step`.
fn pendulum_reference(step: f64) -> SVector<f64, 6> {
    let control = TaylorControl::Fixed { order: 30, step };
    integrate(
        Taylor::new(&PENDULUM, 0.0, pendulum_start(), control).unwrap(),
        PENDULUM_END,
    )
    .0
}

/// The methods every problem is swept with, and the tightest tolerance 10⁻ᵏ of each, at
/// or above its floor (`Floor`): Taylor refuses a relative tolerance below 1e-15, DOP853
/// below 100 machine epsilons (2.2e-14).
const METHODS: [(&str, i32); 2] = [("taylor", 15), ("dop853", 13)];

fn sweep<Sys: VariableMassSystem<N, S>, const N: usize, const S: usize>(
    name: &str,
    system: &Sys,
    start: (SVector<f64, S>, f64),
    methods: &[(&str, i32)],
    error: impl Fn(&SVector<f64, S>) -> f64,
) {
    for &(method, tightest) in methods {
        for k in 6..=tightest {
            let tolerance = 10f64.powi(-k);
            println!(
                "{}",
                point(name, system, start, (method, tolerance), &error)
            );
        }
    }
}

/// One point of the sweep, timed by the sweep's rule, as a tab-separated line: problem,
/// method, tolerance, error, fastest seconds per run, steps, the final state's components
/// (for errors the script measures itself).
fn point<Sys: VariableMassSystem<N, S>, const N: usize, const S: usize>(
    name: &str,
    system: &Sys,
    start: (SVector<f64, S>, f64),
    (method, tolerance): (&str, f64),
    error: impl Fn(&SVector<f64, S>) -> f64,
) -> String {
    let (elapsed, (state, steps)) = run(system, start, (method, tolerance), Timing::Sweep);
    let state_text: Vec<String> = state.iter().map(|x| format!("{x:e}")).collect();
    format!(
        "{name}\t{method}\t{tolerance:e}\t{:e}\t{:e}\t{}\t{}",
        error(&state),
        elapsed.as_secs_f64(),
        steps,
        state_text.join("\t")
    )
}

/// `serve`: reads points `<problem> <method> <tolerance>` from stdin, one a line, and
/// answers each with its sweep line (flushed), so that the script interleaves our points
/// with heyoka's in the order it shuffled; an unknown point is answered `?`.
fn serve() {
    use std::io::{BufRead, Write};
    let sled = SledProblem::standard();
    let kepler = KeplerProblem::standard();
    let rocket = RocketProblem::standard();
    let reference = pendulum_reference(1.0 / 200.0);
    let stdout = std::io::stdout();
    for line in std::io::stdin().lock().lines() {
        let Ok(line) = line else { break };
        let words: Vec<&str> = line.split_whitespace().collect();
        let parsed = match words[..] {
            [problem, method, tolerance] => {
                tolerance.parse::<f64>().ok().map(|t| (problem, method, t))
            }
            _ => None,
        };
        let answer = match parsed {
            Some(("sled", method, t)) => {
                let start = (sled.initial_state(), sled.end_time());
                point("sled", sled.system(), start, (method, t), |y| {
                    sled.error(start.1, y)
                })
            }
            Some(("kepler", method, t)) => {
                let start = (kepler.initial_state(), kepler.end_time());
                point("kepler", kepler.system(), start, (method, t), |y| {
                    kepler.error(start.1, y)
                })
            }
            Some(("rocket", method, t)) => {
                let start = (rocket.initial_state(), rocket.end_time());
                point("rocket", rocket.system(), start, (method, t), |y| {
                    rocket.error(start.1, y)
                })
            }
            Some(("pendulum3", method, t)) => {
                let start = (pendulum_start(), PENDULUM_END);
                point("pendulum3", &PENDULUM, start, (method, t), |y| {
                    (y - reference).amax()
                })
            }
            _ => "?".to_string(),
        };
        let mut out = stdout.lock();
        if writeln!(out, "{answer}")
            .and_then(|()| out.flush())
            .is_err()
        {
            break;
        }
    }
}

/// `only <problem> <method> <tolerance> <runs>`: that point `runs` times, its error and
/// steps printed once with the fastest run.
fn only(args: &[String]) {
    let parsed = match args {
        [problem, method, tolerance, runs, ..] => tolerance
            .parse::<f64>()
            .ok()
            .zip(runs.parse::<usize>().ok())
            .map(|(t, r)| (problem.as_str(), method.as_str(), t, r.max(1))),
        _ => None,
    };
    let Some((problem, method, tolerance, runs)) = parsed else {
        eprintln!(
            "usage: only <sled|kepler|rocket|pendulum3> <taylor|taylor-head|dop853> <tolerance> <runs> \
             (taylor-head on kepler only)"
        );
        std::process::exit(2);
    };
    let point = (method, tolerance);
    let show = |(elapsed, (error, steps)): (Duration, (f64, usize))| {
        println!(
            "{problem}\t{method}\t{tolerance:e}\t{error:e}\t{steps} steps\t{runs} runs\tfastest {:.2} µs",
            elapsed.as_secs_f64() * 1e6
        );
    };
    let timing = Timing::Runs(runs);
    match problem {
        "sled" => {
            let sled = SledProblem::standard();
            let start = (sled.initial_state(), sled.end_time());
            let (elapsed, (y, steps)) = run(sled.system(), start, point, timing);
            show((elapsed, (sled.error(start.1, &y), steps)))
        }
        "kepler" => {
            let kepler = KeplerProblem::standard();
            let start = (kepler.initial_state(), kepler.end_time());
            let (elapsed, (y, steps)) = run(kepler.system(), start, point, timing);
            show((elapsed, (kepler.error(start.1, &y), steps)))
        }
        "rocket" => {
            let rocket = RocketProblem::standard();
            let start = (rocket.initial_state(), rocket.end_time());
            let (elapsed, (y, steps)) = run(rocket.system(), start, point, timing);
            show((elapsed, (rocket.error(start.1, &y), steps)))
        }
        _ => {
            let reference = pendulum_reference(1.0 / 200.0);
            let start = (pendulum_start(), PENDULUM_END);
            let (elapsed, (y, steps)) = run(&PENDULUM, start, point, timing);
            show((elapsed, ((y - reference).amax(), steps)))
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.iter().any(|a| a == "serve") {
        serve();
        return;
    }
    if let Some(at) = args.iter().position(|a| a == "only") {
        only(&args[at + 1..]);
        return;
    }
    let sled = SledProblem::standard();
    let kepler = KeplerProblem::standard();
    if std::env::args().any(|a| a == "rates") {
        let show = |name: &str, y: &[f64], f: &[f64]| {
            let text = |v: &[f64]| v.iter().map(|x| format!("{x:e}")).collect::<Vec<_>>();
            println!("{name}\tstate\t{}", text(y).join("\t"));
            println!("{name}\trate\t{}", text(f).join("\t"));
        };
        let y = sled.initial_state() + SVector::<f64, 2>::new(10.0, 60.0);
        show(
            "sled",
            y.as_slice(),
            sled.system().state_rate(0.0, &y).unwrap().as_slice(),
        );
        let y = kepler.initial_state();
        show(
            "kepler",
            y.as_slice(),
            kepler.system().state_rate(0.0, &y).unwrap().as_slice(),
        );
        let rocket = RocketProblem::standard();
        let y = rocket.initial_state() + SVector::<f64, 3>::new(100.0, 30.0, -0.2);
        show(
            "rocket",
            y.as_slice(),
            rocket.system().state_rate(1.0, &y).unwrap().as_slice(),
        );
        let y = pendulum_start()
            + SVector::<f64, 6>::from_column_slice(&[0.0, 0.0, 0.0, 0.3, -0.2, 0.1]);
        show(
            "pendulum3",
            y.as_slice(),
            PENDULUM.state_rate(0.0, &y).unwrap().as_slice(),
        );
        let (a, b) = (
            pendulum_reference(1.0 / 200.0),
            pendulum_reference(1.0 / 400.0),
        );
        let reference: Vec<String> = a.iter().map(|x| format!("{x:e}")).collect();
        println!("pendulum3\treference\t{}", reference.join("\t"));
        println!("pendulum3\treference_gap\t{:e}", (a - b).amax());
        return;
    }
    let start = (sled.initial_state(), sled.end_time());
    sweep("sled", sled.system(), start, &METHODS, |y| {
        sled.error(start.1, y)
    });
    let start = (kepler.initial_state(), kepler.end_time());
    let with_head = [METHODS[0], ("taylor-head", 15), METHODS[1]];
    sweep("kepler", kepler.system(), start, &with_head, |y| {
        kepler.error(start.1, y)
    });
    let reference = pendulum_reference(1.0 / 200.0);
    let start = (pendulum_start(), PENDULUM_END);
    sweep("pendulum3", &PENDULUM, start, &METHODS, |y| {
        (y - reference).amax()
    });
}
