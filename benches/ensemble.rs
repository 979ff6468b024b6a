//! Ensemble throughput: members per second, and per core, for a vertical rocket with
//! dispersed burn rate, exhaust speed and dry mass flown to its apex (burn to the dry mass,
//! coast until p crosses 0) with Dormand–Prince at tolerance 1e-9, on 1 and 2 threads.
//!
//! First a summary (the fastest of interleaved runs, robust on a shared machine) with the
//! speed-up from 1 to 2 threads, and the members per CPU-second of each (from Linux's
//! per-thread schedstat): on a loaded machine the wall-clock speed-up measures the load,
//! while equal members per CPU-second show that the threads add no work of their own.
//! Then the scalar path against SIMD lanes on one thread (`LaneEnsemble` with
//! `run_lanes`, 4 and 8 members per lane set; bit-identical members, so the same apexes):
//! members per second, fastest of interleaved rounds.
//! Then the same workloads under criterion.
//!
//! ```sh
//! nice -n 10 cargo bench -p varmass-benches --bench ensemble
//! ```

mod common;

use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput};
use varmass::core::ensemble::rand::RngExt;
use varmass::core::ensemble::rayon::{ThreadPool, ThreadPoolBuilder};
use varmass::core::ensemble::{Ensemble, LaneEnsemble, MemberRng};
use varmass::core::lanes::{run_lanes, LaneJob};
use varmass::prelude::*;

use common::generated::Rocket;
use common::timing::fastest_of;

/// Members per timed run.
const MEMBERS: u64 = 2048;
/// Lift-off mass (kg).
const M0: f64 = 1000.0;

/// Burn rate (kg/s), exhaust speed (m/s), dry mass (kg).
fn sample(rng: &mut MemberRng) -> [f64; 3] {
    [
        rng.random_range(9.5..10.5),
        rng.random_range(2400.0..2600.0),
        rng.random_range(380.0..420.0),
    ]
}

fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-9,
        absolute_tolerance: 1e-9,
        ..AdaptiveControl::default()
    })
}

/// Burn to the dry mass, coast to the apex; the apex height.
fn fly(&[mu, u_e, dry_mass]: &[f64; 3]) -> Result<[f64; 1], StepError<3>> {
    let engine = Rocket { mu, u_e, g: 9.81 };
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let mut burn = DormandPrince::new(&engine, 0.0, start, control())?;
    let powered = run(
        &mut burn,
        &RunConfig::until(1e4),
        &[Event::mass_reaches(0, dry_mass)],
    )?;
    let (t_b, state_b) = powered.last().ok_or_else(|| no_point(&burn))?;
    let coasting = Rocket { mu: 0.0, ..engine };
    let mut coast = DormandPrince::new(&coasting, t_b, *state_b, control())?;
    let apex = [Event::state_reaches(1, 0.0, Direction::Falling)];
    let ballistic = run(&mut coast, &RunConfig::until(1e4), &apex)?;
    let (_, state) = ballistic.last().ok_or_else(|| no_point(&coast))?;
    Ok([state[0]])
}

/// The rocket again, with its state rate over lanes too (the same scalar code as
/// `Rocket`'s: both from `models/rocket.vms` without drag).
#[variable_mass_system(file = "../models/rocket.vms", emit = ["lanes"])]
#[derive(Clone, Copy, Debug)]
struct LaneRocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

/// [`fly`] for a chunk of members, W at a time in lanes: every burn to burnout, then every
/// coast to the apex.
fn fly_lanes<const W: usize>(members: &[[f64; 3]]) -> Vec<Result<[f64; 1], StepError<3>>> {
    let config = RunConfig::until(1e4);
    let burnout: Vec<[Event<'_, 3>; 1]> = members
        .iter()
        .map(|&[_, _, dry_mass]| [Event::mass_reaches(0, dry_mass)])
        .collect();
    let start = SVector::<f64, 3>::new(0.0, 0.0, M0);
    let powered: Vec<_> = members
        .iter()
        .zip(&burnout)
        .map(|(&[mu, u_e, _], events)| LaneJob {
            system: LaneRocket { mu, u_e, g: 9.81 },
            time: 0.0,
            state: start,
            events,
        })
        .collect();
    let burnouts = run_lanes::<_, 1, 3, W>(&powered, control(), &config);
    let apex = [Event::state_reaches(1, 0.0, Direction::Falling)];
    let coasting: Vec<_> = powered
        .iter()
        .zip(&burnouts)
        .filter_map(|(job, end)| {
            let end = end.as_ref().ok()?;
            let system = LaneRocket {
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
    let mut apexes = run_lanes::<_, 1, 3, W>(&coasting, control(), &config).into_iter();
    burnouts
        .into_iter()
        .map(|burnout| {
            burnout?;
            let apex = apexes.next().expect("one coast per burnout")?;
            Ok([apex.state[0]])
        })
        .collect()
}

/// Members per timed run of the lanes summary: runs of 0.1–0.3 s, long enough for the
/// CPU time, which Linux counts in scheduler ticks (4 ms here), to be read to a few %.
const LANE_MEMBERS: u64 = 8 * MEMBERS;

/// Runs `LANE_MEMBERS` members in lanes of W on the calling thread; the number completed.
fn run_members_in_lanes<const W: usize>() -> usize {
    let ensemble = LaneEnsemble::new(7, ["apex_height"], sample, fly_lanes::<W>)
        .batch_size(256)
        .serial();
    ensemble.run(0..LANE_MEMBERS).completed().len()
}

/// Runs `LANE_MEMBERS` members on the calling thread on the scalar path.
fn run_members_serial() -> usize {
    let ensemble = Ensemble::new(7, ["apex_height"], sample, fly)
        .batch_size(256)
        .serial();
    ensemble.run(0..LANE_MEMBERS).completed().len()
}

/// A named run of the lanes summary, returning the members completed.
type Workload = (&'static str, fn() -> usize);

/// The scalar path against lanes of 4 and 8 on one thread, interleaved: the fastest of 15
/// runs each in wall-clock time and in CPU time (Linux's schedstat; on a loaded machine the
/// CPU time is the steadier measure of the work itself).
fn lanes_summary() {
    let runs: [Workload; 3] = [
        ("scalar", run_members_serial),
        ("lanes of 4", run_members_in_lanes::<4>),
        ("lanes of 8", run_members_in_lanes::<8>),
    ];
    let mut wall = [Duration::MAX; 3];
    let mut cpu = [u64::MAX; 3];
    for _ in 0..15 {
        for (((_, work), wall), cpu) in runs.iter().zip(&mut wall).zip(&mut cpu) {
            let before = cpu_time();
            let (time, completed) = fastest_of(1, 1, Duration::ZERO, work);
            let spent = before.zip(cpu_time()).map_or(u64::MAX, |(a, b)| b - a);
            assert_eq!(completed, LANE_MEMBERS as usize, "a member failed");
            *wall = (*wall).min(time);
            *cpu = (*cpu).min(spent);
        }
    }
    println!(
        "== ensemble in lanes: {LANE_MEMBERS} rockets to apex on 1 thread, fastest of 15 runs"
    );
    for (((name, _), wall_time), cpu_ns) in runs.iter().zip(wall).zip(cpu) {
        let per_cpu_second = LANE_MEMBERS as f64 / (cpu_ns as f64 * 1e-9);
        println!(
            "{name:>10}: {:.0} members/s ({:.2}× the scalar path), {per_cpu_second:.0} members \
             per CPU-second ({:.2}×)",
            LANE_MEMBERS as f64 / wall_time.as_secs_f64(),
            wall[0].as_secs_f64() / wall_time.as_secs_f64(),
            cpu[0] as f64 / cpu_ns as f64
        );
    }
}

/// The error for a run that returned no point (a run always records its start).
fn no_point(stepper: &impl Stepper<1, 3>) -> StepError<3> {
    StepError::invalid_configuration(stepper.time(), *stepper.state(), "a run returned no point")
}

fn pool(threads: usize) -> ThreadPool {
    ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool")
}

/// Runs `MEMBERS` members on `pool`; the number completed.
fn run_members(pool: &ThreadPool) -> usize {
    let ensemble = Ensemble::new(7, ["apex_height"], sample, fly).batch_size(256);
    pool.install(|| ensemble.run(0..MEMBERS)).completed().len()
}

/// CPU time of every thread of this process so far (ns), where Linux tells it.
fn cpu_time() -> Option<u64> {
    let mut total = 0;
    for task in std::fs::read_dir("/proc/self/task").ok()? {
        let stat = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
        total += stat.split_whitespace().next()?.parse::<u64>().ok()?;
    }
    Some(total)
}

fn summary() {
    let pools = [pool(1), pool(2)];
    let mut best = [Duration::MAX; 2];
    let mut cpu = [Some(0); 2];
    // Interleave the thread counts so that a burst of load on the machine hits both.
    for _ in 0..5 {
        for ((pool, best), cpu) in pools.iter().zip(&mut best).zip(&mut cpu) {
            let before = cpu_time();
            let (time, completed) = fastest_of(3, 3, Duration::ZERO, || run_members(pool));
            assert_eq!(completed, MEMBERS as usize, "a member failed");
            *best = (*best).min(time);
            *cpu = cpu
                .zip(before)
                .zip(cpu_time())
                .map(|((sum, a), b)| sum + (b - a));
        }
    }
    println!("== ensemble: {MEMBERS} rockets to apex, Dormand–Prince tol 1e-9, fastest of 15 runs");
    for ((threads, time), cpu) in [1, 2].into_iter().zip(best).zip(cpu) {
        let rate = MEMBERS as f64 / time.as_secs_f64();
        let per_cpu_second = cpu.map_or(String::from("?"), |ns| {
            format!("{:.0}", 15.0 * MEMBERS as f64 / (ns as f64 * 1e-9))
        });
        println!(
            "{threads} thread(s): {rate:.0} members/s, {:.0} members/s per core, \
             {per_cpu_second} members per CPU-second",
            rate / threads as f64
        );
    }
    println!(
        "speed-up 1 → 2 threads: {:.2}",
        best[0].as_secs_f64() / best[1].as_secs_f64()
    );
}

fn criterion_benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("ensemble_rocket_apex");
    group.throughput(Throughput::Elements(MEMBERS));
    group.sample_size(10);
    for threads in [1, 2] {
        let pool = pool(threads);
        group.bench_function(BenchmarkId::new("threads", threads), |b| {
            b.iter(|| run_members(&pool))
        });
    }
    group.finish();
    let mut group = c.benchmark_group("ensemble_rocket_apex_one_thread");
    group.throughput(Throughput::Elements(LANE_MEMBERS));
    group.sample_size(10);
    group.bench_function("scalar", |b| b.iter(run_members_serial));
    group.bench_function("lanes_4", |b| b.iter(run_members_in_lanes::<4>));
    group.bench_function("lanes_8", |b| b.iter(run_members_in_lanes::<8>));
    group.finish();
}

fn main() {
    // `-- lanes` runs only the lanes summary (and criterion's rows that match it).
    if !std::env::args().any(|a| a == "lanes") {
        summary();
    }
    lanes_summary();
    let mut criterion = Criterion::default().configure_from_args();
    criterion_benches(&mut criterion);
    criterion.final_summary();
}
