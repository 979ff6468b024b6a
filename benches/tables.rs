//! The cost of a table lookup at 1 000 knots: the interval remembered between calls (the
//! table's own hint, or a caller's `Cursor`) against a binary search from scratch, for the
//! linear and the cubic interpolants. The issue's target: ≤ 10 ns a lookup with the interval
//! remembered, the access pattern of an integration (each argument a little past the last).
//! Then the state rate of the M1670 rocket written by hand (`common/motor_rocket.rs`): the
//! figure the generated one is to stay within 1.3× of.
//!
//! First a summary timed in on-CPU time (Linux's `/proc/thread-self/schedstat`), which a
//! loaded machine does not inflate as it does wall time, then criterion's wall-time figures.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench tables
//! cargo bench -p varmass-benches --bench tables -- remembered   # criterion filter
//! ```

#[path = "common/motor_rocket.rs"]
mod motor_rocket;

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion};
use motor_rocket::MotorRocket;
use varmass::core::nalgebra::Vector3;
use varmass::core::VariableMassSystem;
use varmass_table::{Cursor, Interpolation, Outside, Points, Table};

const KNOTS: usize = 1_000;

/// 1 000 unevenly spaced knots on [0, ~1000] with a smooth, turning curve through them.
fn points() -> Points {
    let x: Vec<f64> = (0..KNOTS)
        .map(|i| i as f64 + 0.3 * (i as f64 * 0.7).sin())
        .collect();
    let y = x.iter().map(|x| (0.05 * x).sin() * 1e3 + x).collect();
    Points::new(x, y).expect("increasing: the wobble is below half a spacing")
}

/// Arguments an integration would ask for: 0.37 of a knot spacing apart, wrapping around.
fn stepping() -> Vec<f64> {
    let last = KNOTS as f64 - 2.0;
    (0..4096).map(|k| (k as f64 * 0.37) % last).collect()
}

/// The same arguments in a scrambled order: every lookup is a binary search.
fn scattered() -> Vec<f64> {
    let mut arguments = stepping();
    // A fixed permutation (multiplicative, 4096 = 2¹², 1029 odd): no RNG dependency.
    let n = arguments.len();
    let original = arguments.clone();
    for (k, argument) in arguments.iter_mut().enumerate() {
        *argument = original[(k * 1029) % n];
    }
    arguments
}

fn lookups(c: &mut Criterion) {
    let mut group = c.benchmark_group("table lookup, 1000 knots");
    for interpolation in [Interpolation::Linear, Interpolation::Pchip] {
        let table = Table::new(&points(), interpolation, Outside::Error);
        let name = format!("{interpolation:?}").to_lowercase();
        for (pattern, arguments) in [("remembered", stepping()), ("searched", scattered())] {
            group.bench_function(BenchmarkId::new(format!("{pattern}, hint"), &name), |b| {
                let mut k = 0;
                b.iter(|| {
                    k = (k + 1) & 4095;
                    table.value(black_box(arguments[k]))
                })
            });
            group.bench_function(BenchmarkId::new(format!("{pattern}, cursor"), &name), |b| {
                let mut k = 0;
                let mut cursor = Cursor::default();
                b.iter(|| {
                    k = (k + 1) & 4095;
                    table.value_at(black_box(arguments[k]), &mut cursor)
                })
            });
        }
    }
    group.finish();
}

/// Nanoseconds this thread has run on a CPU, if the kernel says (Linux).
fn cpu_time_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

/// On-CPU nanoseconds per call of `call` over `arguments` (4096 of them, cycled), the
/// fastest of 5 rounds of 2²⁴ calls.
fn on_cpu_per_call(arguments: &[f64], mut call: impl FnMut(f64) -> f64) -> Option<f64> {
    const CALLS: usize = 1 << 24;
    let mut fastest = f64::INFINITY;
    for _ in 0..5 {
        let start = cpu_time_ns()?;
        let mut sum = 0.0;
        for k in 0..CALLS {
            sum += call(black_box(arguments[k & 4095]));
        }
        black_box(sum);
        fastest = fastest.min((cpu_time_ns()? - start) as f64 / CALLS as f64);
    }
    Some(fastest)
}

fn summary() {
    println!("== table lookup at {KNOTS} knots, on-CPU ns per lookup (fastest of 5 × 2^24)");
    println!(
        "{:<8} {:>12} {:>12} {:>12} {:>12}",
        "", "remembered", "  (cursor)", "searched", "  (cursor)"
    );
    for interpolation in [
        Interpolation::Linear,
        Interpolation::Pchip,
        Interpolation::Spline,
    ] {
        let table = Table::new(&points(), interpolation, Outside::Error);
        let mut figures = Vec::new();
        for arguments in [stepping(), scattered()] {
            figures.push(on_cpu_per_call(&arguments, |x| {
                table.value(x).unwrap_or(0.0)
            }));
            let mut cursor = Cursor::default();
            figures.push(on_cpu_per_call(&arguments, |x| {
                table.value_at(x, &mut cursor).unwrap_or(0.0)
            }));
        }
        let cells: Vec<String> = figures
            .iter()
            .map(|f| f.map_or("n/a".into(), |ns| format!("{ns:.2}")))
            .collect();
        let name = format!("{interpolation:?}").to_lowercase();
        println!(
            "{name:<8} {:>12} {:>12} {:>12} {:>12}",
            cells[0], cells[1], cells[2], cells[3]
        );
    }
}

/// (t, state) along a plausible M1670 flight, 4096 times in its first 6 s: the mass burning
/// linearly to burnout at 3.9 s, the speed a parabola.
fn rocket_samples(rocket: &MotorRocket) -> Vec<(f64, Vector3<f64>)> {
    let lift_off = rocket.initial_state();
    (0..4096)
        .map(|k| {
            let t = k as f64 * 6.0 / 4096.0;
            let m = rocket.lift_off_mass - 3.101 * (t / 3.9).min(1.0);
            let v = 80.0 * t - 4.0 * t * t;
            (
                t,
                lift_off + Vector3::new(v * t / 2.0, m * v, m - rocket.lift_off_mass),
            )
        })
        .collect()
}

fn rocket_summary() {
    let rocket = MotorRocket::m1670();
    let samples = rocket_samples(&rocket);
    let times: Vec<f64> = (0..4096).map(|k| k as f64).collect();
    let per_call = on_cpu_per_call(&times, |k| {
        let (t, state) = samples[k as usize];
        rocket.state_rate(t, &state).map_or(0.0, |rate| rate[1])
    });
    let figure = per_call.map_or("n/a".into(), |ns| format!("{ns:.2}"));
    println!("== M1670 rocket, hand-written state rate: {figure} ns on-CPU per call");
}

fn rocket(c: &mut Criterion) {
    let rocket = MotorRocket::m1670();
    let samples = rocket_samples(&rocket);
    c.bench_function("M1670 rocket state rate, hand-written", |b| {
        let mut k = 0;
        b.iter(|| {
            k = (k + 1) & 4095;
            let (t, state) = samples[k];
            rocket.state_rate(black_box(t), black_box(&state))
        })
    });
}

fn main() {
    summary();
    rocket_summary();
    let mut criterion = Criterion::default().configure_from_args();
    lookups(&mut criterion);
    rocket(&mut criterion);
    criterion.final_summary();
}
