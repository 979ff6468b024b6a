//! The Rust references of `python/bench/bench.py`, written as a Rust user of the run-time
//! interpreter (`varmass::interpret`) would write them:
//!
//! * `sled REPEATS`: the paper's sled from rest to x = 50 m, DOP853 at tolerance 1e-12.
//!   `models/sled.vms [impact]` is derived and compiled once, untimed (as a Python `Model`
//!   is when made and at its first run); each timed run gives the program its parameter
//!   values (`Program::set_parameters`), integrates with every accepted step kept, and
//!   takes the program back. Prints the fastest run in seconds.
//! * `ensemble MEMBERS`: rockets with μ ~ U(9.5, 10.5) and u_e ~ N(2500, 50) (drawn as the
//!   Python package draws them) burning from rest to the dry mass, Dormand–Prince at 1e-9,
//!   on one thread (the core's serial ensemble), the model derived and compiled once and
//!   each member's values given to that program. Prints members per second.
//!
//! * `sled-recorded REPEATS`: the same, with x' evaluated at every accepted point (the
//!   program's velocities from `[x, p]`), as a run recording x and x' must.
//! * `tool-sled REPEATS`: the same sled run through the command line tool's code as the
//!   Python package reaches it (`varmass_cli::run::Compiled::run`: the tool's checks, kept
//!   plan, run, recorded x and x' at every point and the summary's values, its text not
//!   made), from Rust: Python's `run` less this is the boundary's cost, this less `sled`
//!   the tool's own work.
//!
//! `cargo run --release --manifest-path python/bench/reference/Cargo.toml -- sled 200`

use std::sync::Mutex;
use std::time::Instant;

use varmass::core::ensemble::rand::distr::{Distribution, Uniform};
use varmass::core::ensemble::{Ensemble, MemberRng};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::{derive, mechanics::Parameters};

const SLED: &str = include_str!("../../../../models/sled.vms");
const ROCKET: &str = include_str!("../../../../models/rocket.vms");

/// Derives and compiles once: what a Rust user of the interpreter does before a sweep.
fn program(source: &str, with: &[&str], parameters: &[(&str, f64)]) -> Program {
    let ast = parse_system(source).expect("parses");
    let with: Vec<String> = with.iter().map(|t| t.to_string()).collect();
    let ast = select_tags(&ast, &with).expect("tags");
    let derivation = derive(&ast, Parameters::Inferred).expect("derives");
    Program::new(derivation, parameters).expect("parameters fit")
}

fn tolerance(tol: f64) -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tol,
        absolute_tolerance: tol,
        ..AdaptiveControl::dop853()
    })
}

const SLED_VALUES: [(&str, f64); 5] = [
    ("m0", 10.0),
    ("c", 2.0),
    ("g", 9.81),
    ("theta", 0.523_598_775_598_298_8), // 30° in radians
    ("f_d", 0.1),
];

/// One sled run on the compiled `program` (given back); returns x' at 50 m. With
/// `recorded`, x' is also evaluated at every point, as the tool (and so Python) records it:
/// the program's velocities from the state `[x, p]`.
fn sled(program: &mut Option<Program>, recorded: bool) -> f64 {
    let mut compiled = program.take().expect("a program");
    compiled
        .set_parameters(&SLED_VALUES)
        .expect("parameters fit");
    let system = TapeSystem::<1, 2>::new(compiled).expect("sizes");
    let mut stepper =
        Dop853::new(&system, 0.0, SVector::zeros(), tolerance(1e-12)).expect("starts");
    let at_50 = Event::state_reaches(0, 50.0, Direction::Either);
    let solution = run(&mut stepper, &RunConfig::until(100.0), &[at_50]).expect("runs");
    let (_, state) = solution.last().expect("a point");
    let mut velocity = state[1] / (10.0 + 2.0 * state[0]);
    if recorded {
        let mut column = Vec::with_capacity(solution.times.len());
        for (t, state) in solution.times.iter().zip(&solution.states) {
            let mut v = [0.0];
            system
                .program()
                .velocities(*t, state.as_slice(), &mut v)
                .expect("velocities");
            column.push(v[0]);
        }
        velocity = *std::hint::black_box(column).last().expect("a point");
    }
    *program = Some(system.into_program());
    velocity
}

/// One rocket to burnout on the compiled `program` (taken and given back); its height there.
fn rocket(
    program: &Mutex<Option<Program>>,
    &[mu, u_e]: &[f64; 2],
) -> Result<[f64; 1], StepError<3>> {
    let mut compiled = program.lock().expect("no panic").take().expect("a program");
    compiled
        .set_parameters(&[("mu", mu), ("u_e", u_e), ("g", 9.81)])
        .expect("parameters fit");
    let system = TapeSystem::<1, 3>::new(compiled).expect("sizes");
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-9,
        absolute_tolerance: 1e-9,
        ..AdaptiveControl::default()
    });
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1000.0);
    // The state mass is state[2] (`[y, p, m]`).
    let burnout = [Event::state_reaches(2, 400.0, Direction::Falling)];
    let height = DormandPrince::new(&system, 0.0, start, control)
        .and_then(|mut stepper| Ok(run(&mut stepper, &RunConfig::until(1e4), &burnout)?))
        .map(|solution| solution.last().map_or(f64::NAN, |(_, s)| s[0]));
    *program.lock().expect("no panic") = Some(system.into_program());
    Ok([height?])
}

fn sample(rng: &mut MemberRng) -> [f64; 2] {
    let mu = Uniform::new(9.5, 10.5).expect("a range").sample(rng);
    let u_e = 2500.0 + 50.0 * standard_normal(rng);
    [mu, u_e]
}

/// A standard normal draw (Box–Muller: the reference needs the work of a draw, not the
/// Python package's exact stream).
fn standard_normal(rng: &mut MemberRng) -> f64 {
    let unit = Uniform::new(f64::EPSILON, 1.0).expect("a range");
    let (u, v) = (unit.sample(rng), unit.sample(rng));
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// The tool's run of the sled, as `Model.run` makes it: the flags parsed by the tool's own
/// parser once, the model loaded once, each timed run `Compiled::run` with the values.
fn tool_sled(count: u64) -> f64 {
    use varmass_cli::args::{Cli, Command};
    let argv = [
        "varmass",
        "run",
        "models/sled.vms",
        "--with=impact",
        "--from=0.0",
        "--until=100.0",
        "--init=x=0.0",
        "--stop-when=x = 50",
        "--method=dop853",
        "--tol=1e-12",
        "--record=x",
        "--record=x'",
    ];
    let cli = <Cli as clap::Parser>::try_parse_from(argv).expect("the flags parse");
    let Command::Run(args) = cli.command else {
        unreachable!("a run")
    };
    let path = std::path::Path::new("models/sled.vms");
    let with = ["impact".to_string()];
    let model = varmass_cli::model::load_source(SLED, path, &with).expect("derives");
    let mut compiled = varmass_cli::run::Compiled::new(model);
    let mut fastest = f64::INFINITY;
    for _ in 0..count {
        let start = Instant::now();
        let done = compiled.run(&SLED_VALUES, &args);
        std::hint::black_box(done.ok().expect("runs").table.len());
        fastest = fastest.min(start.elapsed().as_secs_f64());
    }
    fastest
}

fn main() {
    let mut args = std::env::args().skip(1);
    let what = args.next().unwrap_or_default();
    let count: u64 = args.next().and_then(|n| n.parse().ok()).unwrap_or(100);
    match what.as_str() {
        "sled" | "sled-recorded" => {
            let recorded = what == "sled-recorded";
            let mut program = Some(program(SLED, &["impact"], &SLED_VALUES));
            let mut fastest = f64::INFINITY;
            for _ in 0..count {
                let start = Instant::now();
                std::hint::black_box(sled(&mut program, recorded));
                fastest = fastest.min(start.elapsed().as_secs_f64());
            }
            println!("{fastest:e}");
        }
        "tool-sled" => println!("{:e}", tool_sled(count)),
        "ensemble" => {
            let values = [("mu", 10.0), ("u_e", 2500.0), ("g", 9.81)];
            let program = Mutex::new(Some(program(ROCKET, &[], &values)));
            let member = |drawn: &[f64; 2]| rocket(&program, drawn);
            let ensemble = Ensemble::new(2015, ["y"], sample, member).serial();
            let start = Instant::now();
            let partial = ensemble.run(0..count);
            let seconds = start.elapsed().as_secs_f64();
            if let Some(f) = partial.failures().first() {
                panic!("member {} failed: {}", f.index, f.error);
            }
            println!("{}", count as f64 / seconds);
        }
        _ => {
            eprintln!(
                "usage: reference sled|sled-recorded|tool-sled REPEATS | \
                 reference ensemble MEMBERS"
            );
            std::process::exit(2);
        }
    }
}
