//! The Rust references of `python/bench/bench.py`, written as a Rust user of the run-time
//! interpreter (`varmass::interpret`) would write them:
//!
//! * `sled REPEATS`: the paper's sled from rest to x = 50 m, DOP853 at tolerance 1e-12 —
//!   derive `models/sled.vms [impact]`, compile the tapes with the parameter values, run.
//!   (A `Derivation` is consumed by `Program::new`, so each run derives again, as the
//!   Python package's does.) Prints the fastest run in seconds.
//! * `ensemble MEMBERS`: rockets with μ ~ U(9.5, 10.5) and u_e ~ N(2500, 50) (drawn as the
//!   Python package draws them) burning from rest to the dry mass, Dormand–Prince at 1e-9,
//!   on one thread (the core's serial ensemble). Prints members per second.
//!
//! `cargo run --release --manifest-path python/bench/reference/Cargo.toml -- sled 200`

use std::time::Instant;

use varmass::core::ensemble::rand::distr::{Distribution, Uniform};
use varmass::core::ensemble::{Ensemble, MemberRng};
use varmass::interpret::{Program, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::mechanics::{derive, Parameters};
use varmass::symbolic::parse::{parse_system, select_tags};

const SLED: &str = include_str!("../../../../models/sled.vms");
const ROCKET: &str = include_str!("../../../../models/rocket.vms");

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

/// One sled run; returns x' at 50 m.
fn sled() -> f64 {
    let parameters = [
        ("m0", 10.0),
        ("c", 2.0),
        ("g", 9.81),
        ("theta", 30f64.to_radians()),
        ("f_d", 0.1),
    ];
    let system = TapeSystem::<1, 2>::new(program(SLED, &["impact"], &parameters)).expect("sizes");
    let mut stepper =
        Dop853::new(&system, 0.0, SVector::zeros(), tolerance(1e-12)).expect("starts");
    let at_50 = Event::state_reaches(0, 50.0, Direction::Either);
    let solution = run(&mut stepper, &RunConfig::until(100.0), &[at_50]).expect("runs");
    let (_, state) = solution.last().expect("a point");
    state[1] / (10.0 + 2.0 * state[0])
}

/// One rocket to burnout; its height there.
fn rocket(&[mu, u_e]: &[f64; 2]) -> Result<[f64; 1], StepError<3>> {
    let parameters = [("mu", mu), ("u_e", u_e), ("g", 9.81)];
    let system = TapeSystem::<1, 3>::new(program(ROCKET, &[], &parameters)).expect("sizes");
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-9,
        absolute_tolerance: 1e-9,
        ..AdaptiveControl::default()
    });
    let start = SVector::<f64, 3>::new(0.0, 0.0, 1000.0);
    let mut stepper = DormandPrince::new(&system, 0.0, start, control)?;
    // The state mass is state[2] (`[y, p, m]`).
    let burnout = [Event::state_reaches(2, 400.0, Direction::Falling)];
    let solution = run(&mut stepper, &RunConfig::until(1e4), &burnout)?;
    Ok([solution.last().map_or(f64::NAN, |(_, s)| s[0])])
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

fn main() {
    let mut args = std::env::args().skip(1);
    let what = args.next().unwrap_or_default();
    let count: u64 = args.next().and_then(|n| n.parse().ok()).unwrap_or(100);
    match what.as_str() {
        "sled" => {
            let mut fastest = f64::INFINITY;
            for _ in 0..count {
                let start = Instant::now();
                std::hint::black_box(sled());
                fastest = fastest.min(start.elapsed().as_secs_f64());
            }
            println!("{fastest:e}");
        }
        "ensemble" => {
            let ensemble = Ensemble::new(2015, ["y"], sample, rocket).serial();
            let start = Instant::now();
            let partial = ensemble.run(0..count);
            let seconds = start.elapsed().as_secs_f64();
            if let Some(f) = partial.failures().first() {
                panic!("member {} failed: {}", f.index, f.error);
            }
            println!("{}", count as f64 / seconds);
        }
        _ => {
            eprintln!("usage: reference sled REPEATS | reference ensemble MEMBERS");
            std::process::exit(2);
        }
    }
}
