//! A launch dispersion study: 10⁵ vertical rockets (flat Earth, no drag) whose burn rate,
//! exhaust speed and dry mass are dispersed, each flown with Dormand–Prince (tolerance 1e-9)
//! to burnout and then coasting to its apex, as one reproducible ensemble over all cores.
//! It prints the apex height's statistics, a text histogram, and the members per second.
//!
//! Every member is also checked against its closed form (burning from rest, m = m0 − μ t:
//! v = u_e ln(m0/m) − g t, y = u_e (t − (m/μ) ln(m0/m)) − ½ g t²; then apex at
//! y_b + v_b²/(2g)); the example exits non-zero if a member misses by more than 1e-7 or fails.
//!
//! Run with `cargo run --release --example dispersion [members] [seed] [--lanes]`
//! (`RAYON_NUM_THREADS=1` for one core). With `--lanes` the members are flown 8 at a time
//! in SIMD lanes (`LaneEnsemble` and `run_lanes`), bit-identical member by member to the
//! scalar path, so the study prints the same figures, sooner.

use std::process::ExitCode;
use std::time::Instant;

use varmass::core::ensemble::rand::RngExt;
use varmass::core::ensemble::{Ensemble, LaneEnsemble, MemberRng, Partial, Summary, SummaryConfig};
use varmass::core::lanes::{run_lanes, LaneJob};
use varmass::prelude::*;

#[variable_mass_system(file = "models/rocket.vms", emit = ["lanes"])]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

/// Lift-off mass (kg) and gravity (m/s²).
const M0: f64 = 1000.0;
const G: f64 = 9.81;
/// A member whose apex misses its closed form by more than this (relative) fails the example.
const THRESHOLD: f64 = 1e-7;

/// One member's dispersed parameters.
#[derive(Clone, Copy, Debug)]
struct Dispersion {
    /// Burn rate μ (kg/s), uniform in 10 ± 0.5.
    burn_rate: f64,
    /// Exhaust speed u_e (m/s), uniform in 2500 ± 100.
    exhaust_speed: f64,
    /// Dry mass (kg), uniform in 400 ± 20.
    dry_mass: f64,
}

fn sample(rng: &mut MemberRng) -> Dispersion {
    Dispersion {
        burn_rate: rng.random_range(9.5..10.5),
        exhaust_speed: rng.random_range(2400.0..2600.0),
        dry_mass: rng.random_range(380.0..420.0),
    }
}

fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-9,
        absolute_tolerance: 1e-9,
        ..AdaptiveControl::default()
    })
}

/// Flies one rocket to its apex: [apex height, apex time, relative error of the height
/// against the closed form].
fn fly(d: &Dispersion) -> Result<[f64; 3], StepError<3>> {
    let engine = Rocket {
        mu: d.burn_rate,
        u_e: d.exhaust_speed,
        g: G,
    };
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let mut burn = DormandPrince::new(&engine, 0.0, start, control())?;
    let burnout = [Event::mass_reaches(0, d.dry_mass)];
    let powered = run(&mut burn, &RunConfig::until(1e4), &burnout)?;
    let (t_b, state_b) = powered.last().ok_or_else(|| no_point(&burn))?;
    let coasting = Rocket { mu: 0.0, ..engine };
    let mut coast = DormandPrince::new(&coasting, t_b, *state_b, control())?;
    let apex = [Event::state_reaches(1, 0.0, Direction::Falling)];
    let ballistic = run(&mut coast, &RunConfig::until(1e4), &apex)?;
    let (t_apex, state_apex) = ballistic.last().ok_or_else(|| no_point(&coast))?;
    let exact = exact_apex_height(d);
    Ok([state_apex[0], t_apex, (state_apex[0] - exact).abs() / exact])
}

/// Members in a lane set of `--lanes`.
const LANES: usize = 8;

/// [`fly`] for a chunk of members, [`LANES`] at a time in SIMD lanes: every burn to its
/// burnout, then every coast to its apex.
fn fly_lanes(members: &[Dispersion]) -> Vec<Result<[f64; 3], StepError<3>>> {
    let config = RunConfig::until(1e4);
    let burnout: Vec<[Event<'_, 3>; 1]> = members
        .iter()
        .map(|d| [Event::mass_reaches(0, d.dry_mass)])
        .collect();
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let powered: Vec<_> = members
        .iter()
        .zip(&burnout)
        .map(|(d, events)| LaneJob {
            system: Rocket {
                mu: d.burn_rate,
                u_e: d.exhaust_speed,
                g: G,
            },
            time: 0.0,
            state: start,
            events,
        })
        .collect();
    let burnouts = run_lanes::<_, 1, 3, LANES>(&powered, control(), &config);
    let apex = [Event::state_reaches(1, 0.0, Direction::Falling)];
    let coasting: Vec<_> = powered
        .iter()
        .zip(&burnouts)
        .filter_map(|(job, end)| {
            let end = end.as_ref().ok()?;
            let system = Rocket {
                mu: 0.0,
                ..job.system
            };
            let (time, state, events) = (end.time, end.state, &apex[..]);
            Some(LaneJob {
                system,
                time,
                state,
                events,
            })
        })
        .collect();
    let mut apexes = run_lanes::<_, 1, 3, LANES>(&coasting, control(), &config).into_iter();
    members
        .iter()
        .zip(burnouts)
        .map(|(d, burnout)| {
            burnout?;
            let apex = apexes.next().ok_or_else(|| lost(d))??;
            let exact = exact_apex_height(d);
            let height = apex.state[0];
            Ok([height, apex.time, (height - exact).abs() / exact])
        })
        .collect()
}

/// The error for a coast that has no result (it cannot happen: every burnout has a coast).
fn lost(d: &Dispersion) -> StepError<3> {
    let state = SVector::<f64, 3>::new(0.0, 0.0, d.dry_mass);
    StepError::invalid_configuration(f64::NAN, state, "a coast in lanes went missing")
}

/// The error for a run that returned no point (a run always records its start).
fn no_point(stepper: &impl Stepper<1, 3>) -> StepError<3> {
    StepError::invalid_configuration(stepper.time(), *stepper.state(), "a run returned no point")
}

/// The apex height in closed form (module docs).
fn exact_apex_height(d: &Dispersion) -> f64 {
    let t_b = (M0 - d.dry_mass) / d.burn_rate;
    let log_ratio = (M0 / d.dry_mass).ln();
    let v_b = d.exhaust_speed * log_ratio - G * t_b;
    let y_b = d.exhaust_speed * (t_b - d.dry_mass / d.burn_rate * log_ratio) - 0.5 * G * t_b * t_b;
    y_b + v_b * v_b / (2.0 * G)
}

fn print_summary(name: &str, unit: &str, s: &Summary) {
    println!(
        "{name}: mean {:.1} {unit} (95 % CI {:.1} .. {:.1}), sd {:.1}, min {:.1}, max {:.1}",
        s.mean,
        s.confidence_interval.0,
        s.confidence_interval.1,
        s.standard_deviation,
        s.min,
        s.max
    );
    let quantiles: Vec<String> = s
        .quantiles
        .iter()
        .map(|(p, q)| format!("{:.0} %: {q:.1}", 100.0 * p))
        .collect();
    println!("  quantiles {}", quantiles.join(", "));
}

/// A text histogram of `values` in `bins` bins, bars scaled to 60 characters.
fn print_histogram(values: &[f64], bins: usize, scale: f64, unit: &str) {
    let (min, max) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let width = (max - min) / bins as f64;
    let mut counts = vec![0usize; bins];
    for &v in values {
        counts[(((v - min) / width) as usize).min(bins - 1)] += 1;
    }
    let largest = counts.iter().copied().max().unwrap_or(1).max(1);
    for (bin, &count) in counts.iter().enumerate() {
        let low = (min + width * bin as f64) / scale;
        let bar = "#".repeat((60 * count).div_ceil(largest));
        println!("  {low:>8.2} {unit} | {bar} {count}");
    }
}

/// Prints the study; returns whether every member completed within the threshold.
fn report(partial: &Partial<Dispersion, StepError<3>>, seconds: f64) -> bool {
    let config = SummaryConfig::default();
    let (Ok(height), Ok(time), Some(errors)) = (
        partial.summary("apex_height", &config),
        partial.summary("apex_time", &config),
        partial.values(2),
    ) else {
        eprintln!("too few members completed for statistics");
        return false;
    };
    print_summary("apex height", "m", &height);
    print_summary("apex time", "s", &time);
    println!("apex height histogram:");
    print_histogram(partial.values(0).unwrap_or(&[]), 24, 1e3, "km");
    let worst = errors.iter().fold(0.0_f64, |worst, &e| worst.max(e));
    println!("worst relative error of an apex height vs its closed form: {worst:.2e}");
    for failure in partial.failures() {
        eprintln!(
            "member {} failed with {:?}: {}",
            failure.index, failure.params, failure.error
        );
    }
    let members = partial.member_count();
    println!(
        "{members} members ({} failed) in {seconds:.2} s: {:.0} members/s on {} threads",
        partial.failures().len(),
        members as f64 / seconds,
        varmass::core::ensemble::rayon::current_num_threads()
    );
    partial.failures().is_empty() && worst < THRESHOLD
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let lanes = args.iter().any(|a| a == "--lanes");
    let mut numbers = args
        .iter()
        .filter(|a| *a != "--lanes")
        .map(|a| a.parse::<u64>());
    let members = numbers.next().unwrap_or(Ok(100_000));
    let seed = numbers.next().unwrap_or(Ok(2015));
    let (Ok(members), Ok(seed)) = (members, seed) else {
        eprintln!("usage: dispersion [members] [seed] [--lanes]");
        return ExitCode::FAILURE;
    };
    let names = ["apex_height", "apex_time", "apex_height_error"];
    println!("{members} vertical rockets, seed {seed}: μ ~ U(9.5, 10.5) kg/s, u_e ~ U(2400, 2600) m/s, dry mass ~ U(380, 420) kg, m0 = {M0} kg");
    let start = Instant::now();
    let partial = if lanes {
        println!("flown {LANES} at a time in SIMD lanes");
        LaneEnsemble::new(seed, names, sample, fly_lanes).run(0..members)
    } else {
        Ensemble::new(seed, names, sample, fly).run(0..members)
    };
    let seconds = start.elapsed().as_secs_f64();
    if report(&partial, seconds) {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
