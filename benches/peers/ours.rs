//! Our side of the comparison with heyoka (`benches/peers/heyoka.py` runs this binary and
//! heyoka in one interleaved session and writes the table): the Taylor stepper on the
//! emitted recurrences, and DOP853, on the sled to 50 m, Kepler e = 0.5 over three orbits
//! and the planar 3-link pendulum over 10 s, swept over tolerances; on Kepler also the
//! Taylor stepper with its double-double head (`taylor-head`: `emit = [..., "head"]`,
//! `Taylor::with_head`; the other two problems call sin and cos, which have no head yet). One line per point,
//! tab-separated: problem, method, tolerance, achieved error, fastest seconds per run,
//! steps, the final state's components.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench peers            # the sweep
//! cargo bench -p varmass-benches --bench peers -- rates   # initial states and rates
//! # one point run `runs` times, for `perf stat` (instructions per run do not depend on load)
//! cargo bench -p varmass-benches --bench peers -- only kepler taylor 1e-12 1000
//! ```
//!
//! The pendulum's reference is our own Taylor method at order 30 and step 1/200 s; its
//! distance to the run at step 1/400 s is printed with `rates` (measured 4e-15).

#[path = "../common/mod.rs"]
mod common;

use std::time::Duration;

use common::problems::{KeplerProblem, Problem, SledProblem};
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

fn run<Sys: VariableMassSystem<N, S>, const N: usize, const S: usize>(
    system: &Sys,
    (y0, end): (SVector<f64, S>, f64),
    method: &str,
    tolerance: f64,
) -> (SVector<f64, S>, Statistics) {
    if method == "taylor" || method == "taylor-head" {
        let control = TaylorControl::adaptive(tolerance, tolerance);
        let stepper = Taylor::new(system, 0.0, y0, control).unwrap();
        if method == "taylor-head" {
            integrate(stepper.with_head().expect("the system has a head"), end)
        } else {
            integrate(stepper, end)
        }
    } else {
        let control = StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: tolerance,
            absolute_tolerance: tolerance,
            ..AdaptiveControl::dop853()
        });
        integrate(
            Dop853::new(system, 0.0, y0, control)
                .unwrap()
                .without_dense_output(),
            end,
        )
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

/// The methods every problem is swept with, and the tightest tolerance 10⁻ᵏ of each:
/// DOP853 refuses a relative tolerance below 100 machine epsilons (2.2e-14).
const METHODS: [(&str, i32); 2] = [("taylor", 16), ("dop853", 13)];

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
            let (elapsed, (state, statistics)) =
                fastest_of(3, 1000, Duration::from_millis(150), || {
                    run(system, start, method, tolerance)
                });
            // The final state too, for errors the script measures itself.
            let state_text: Vec<String> = state.iter().map(|x| format!("{x:e}")).collect();
            println!(
                "{name}\t{method}\t{tolerance:e}\t{:e}\t{:e}\t{}\t{}",
                error(&state),
                elapsed.as_secs_f64(),
                statistics.accepted_steps,
                state_text.join("\t")
            );
        }
    }
}

/// `only <problem> <method> <tolerance> <runs>`: that point `runs` times, its error and steps
/// printed once.
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
            "usage: only <sled|kepler|pendulum3> <taylor|taylor-head|dop853> <tolerance> <runs> \
             (taylor-head on kepler only)"
        );
        std::process::exit(2);
    };
    let repeat = |f: &dyn Fn() -> (f64, Statistics)| {
        let mut last = f();
        for _ in 1..runs {
            last = std::hint::black_box(f());
        }
        println!(
            "{problem}\t{method}\t{tolerance:e}\t{:e}\t{} steps\t{} runs",
            last.0, last.1.accepted_steps, runs
        );
    };
    match problem {
        "sled" => {
            let sled = SledProblem::standard();
            let start = (sled.initial_state(), sled.end_time());
            repeat(&|| {
                let (y, s) = run(sled.system(), start, method, tolerance);
                (sled.error(start.1, &y), s)
            })
        }
        "kepler" => {
            let kepler = KeplerProblem::standard();
            let start = (kepler.initial_state(), kepler.end_time());
            repeat(&|| {
                let (y, s) = run(kepler.system(), start, method, tolerance);
                (kepler.error(start.1, &y), s)
            })
        }
        _ => {
            let reference = pendulum_reference(1.0 / 200.0);
            let start = (pendulum_start(), PENDULUM_END);
            repeat(&|| {
                let (y, s) = run(&PENDULUM, start, method, tolerance);
                ((y - reference).amax(), s)
            })
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
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
    let with_head = [METHODS[0], ("taylor-head", 16), METHODS[1]];
    sweep("kepler", kepler.system(), start, &with_head, |y| {
        kepler.error(start.1, y)
    });
    let reference = pendulum_reference(1.0 / 200.0);
    let start = (pendulum_start(), PENDULUM_END);
    sweep("pendulum3", &PENDULUM, start, &METHODS, |y| {
        (y - reference).amax()
    });
}
