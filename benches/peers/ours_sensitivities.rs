//! Our side of the comparison of forward sensitivities with heyoka's variational equations
//! (issue 37; `benches/peers/heyoka_sensitivities.py` runs this binary and heyoka and writes
//! docs/bench/heyoka_sensitivities.md): `Sensitive` on the Taylor stepper (the recurrences
//! over tangents, `emit = ["sensitivities", "taylor"]`) and on DOP853, on the paper's sled to
//! the time it reaches 50 m (columns: the scooping rate c and the initial momentum p₀) and
//! Kepler e = 0.5 over three orbits (columns: the four initial entries, the whole
//! state-transition matrix). Points are read from stdin, `<problem> <method> <tolerance>` a
//! line, each answered by a tab-separated line: problem, method, tolerance, end time, fastest
//! seconds per run, steps, then the final state's sensitivities ∂y_i/∂w_j row by row. Timed as
//! `peers` times the plain runs (`benches/peers/ours.rs`): inside Rust, the Taylor stepper
//! made once and restarted, DOP853 made afresh; the fastest of 3 to 1000 runs over about
//! 0.15 s. The script measures the errors against references independent of varmass.
//!
//! ```sh
//! echo "kepler taylor 1e-12" | cargo bench -p varmass-benches --bench peers_sensitivities
//! ```

#[path = "../common/mod.rs"]
mod common;

use std::io::BufRead;
use std::time::Duration;

use common::problems::{KeplerProblem, Problem, SledProblem};
use common::timing::fastest_of;
use varmass::core::nalgebra::SVector;
use varmass::core::sensitivity::{Column, Sensitive};
use varmass::core::steppers::{AdaptiveControl, Dop853, StepControl, Taylor, TaylorControl};
use varmass::core::{StepOutcome, Stepper};
use varmass::prelude::*;

/// The sled of `common::generated` with its sensitivities.
#[variable_mass_system(
    "
    coordinates x
    mass m = m0 + c*x
    body sled: mass m, position [x]
    potential -m*g*x*sin(theta)
    force sled: [-f_d*m*g*cos(theta)]
    inflow sled: velocity [0]
",
    emit = ["sensitivities", "taylor"]
)]
#[derive(Clone, Copy, Debug)]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

/// Kepler of `common::generated` with its sensitivities.
#[variable_mass_system(
    "
    coordinates r, th
    mass m = m1
    body planet: mass m, position [r*cos(th), r*sin(th)]
    potential -k*m/r
",
    emit = ["sensitivities", "taylor"]
)]
#[derive(Clone, Copy, Debug)]
struct Kepler {
    m1: f64,
    k: f64,
}

/// One run of `stepper` restarted at `start` to `end`: the final augmented state and steps.
fn rerun<St: Stepper<N, SA>, const N: usize, const SA: usize>(
    stepper: &mut St,
    (start, end): (SVector<f64, SA>, f64),
) -> (SVector<f64, SA>, usize) {
    stepper.restart(0.0, start).expect("a finite start");
    stepper.set_stop_time(end).expect("a stop time ahead");
    let before = stepper.statistics().accepted_steps;
    while stepper.step().expect("the run succeeds") != StepOutcome::ReachedStopTime {}
    (
        *stepper.state(),
        stepper.statistics().accepted_steps - before,
    )
}

/// The fastest run of `method` at `tolerance` and the last run's final state and steps.
fn timed<Sys: VariableMassSystem<N, SA>, const N: usize, const SA: usize>(
    system: &Sys,
    start: (SVector<f64, SA>, f64),
    (method, tolerance): (&str, f64),
) -> (Duration, (SVector<f64, SA>, usize)) {
    match method {
        "taylor" => {
            let tolerance = Tolerance::for_floor(tolerance, tolerance, Floor::Taylor).unwrap();
            let control = TaylorControl::adaptive(tolerance);
            let mut stepper = Taylor::new(system, 0.0, start.0, control).expect("recurrences");
            fastest_of(3, 1000, Duration::from_millis(150), || {
                rerun(&mut stepper, start)
            })
        }
        _ => {
            let control = StepControl::Adaptive(AdaptiveControl {
                relative_tolerance: tolerance,
                absolute_tolerance: tolerance,
                ..AdaptiveControl::dop853()
            });
            fastest_of(3, 1000, Duration::from_millis(150), || {
                let stepper = Dop853::new(system, 0.0, start.0, control).unwrap();
                rerun(&mut stepper.without_dense_output(), start)
            })
        }
    }
}

/// The answer line of one point: the sensitivities ∂y_i/∂w_j of S entries and K columns,
/// row i by row.
fn line<const SA: usize>(
    (problem, method, tolerance, end): (&str, &str, f64, f64),
    (elapsed, (state, steps)): (Duration, (SVector<f64, SA>, usize)),
    (s, k): (usize, usize),
) -> String {
    let entries = (0..s).flat_map(|i| (0..k).map(move |j| state[s * (1 + j) + i]));
    let entries: Vec<String> = entries.map(|x| format!("{x:e}")).collect();
    format!(
        "{problem}\t{method}\t{tolerance:e}\t{end:e}\t{:e}\t{steps}\t{}",
        elapsed.as_secs_f64(),
        entries.join("\t")
    )
}

fn main() {
    let sled_problem = SledProblem::standard();
    let s = sled_problem.system;
    let sled = Sled {
        m0: s.m0,
        c: s.c,
        g: s.g,
        theta: s.theta,
        f_d: s.f_d,
    };
    let sled_columns = [Column::Parameter("c"), Column::Initial(1)];
    let sled = Sensitive::<Sled, 2>::new::<1, 6>(sled, &sled_columns).unwrap();
    let sled_start = (
        sled.start::<6>(&sled_problem.initial_state()),
        sled_problem.end_time(),
    );
    let kepler_problem = KeplerProblem::standard();
    let kepler = Kepler {
        m1: kepler_problem.system.m1,
        k: kepler_problem.system.k,
    };
    let kepler_columns = [0, 1, 2, 3].map(Column::Initial);
    let kepler = Sensitive::<Kepler, 4>::new::<2, 20>(kepler, &kepler_columns).unwrap();
    let kepler_start = (
        kepler.start::<20>(&kepler_problem.initial_state()),
        kepler_problem.end_time(),
    );
    for request in std::io::stdin().lock().lines() {
        let request = request.expect("a line");
        let words: Vec<&str> = request.split_whitespace().collect();
        let [problem, method, tolerance] = words[..] else {
            eprintln!("usage: <sled|kepler> <taylor|dop853> <tolerance>");
            std::process::exit(2);
        };
        let tolerance: f64 = tolerance.parse().expect("a tolerance");
        let answer = match problem {
            "sled" => line(
                (problem, method, tolerance, sled_start.1),
                timed(&sled, sled_start, (method, tolerance)),
                (2, 2),
            ),
            _ => line(
                (problem, method, tolerance, kepler_start.1),
                timed(&kepler, kepler_start, (method, tolerance)),
                (4, 4),
            ),
        };
        println!("{answer}");
    }
}
