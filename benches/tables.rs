//! The cost of a table lookup at 1 000 knots: the interval remembered between calls (the
//! table's own hint, or a caller's `Cursor`) against a binary search from scratch, for the
//! linear and the cubic interpolants. The issue's target: ≤ 10 ns a lookup with the interval
//! remembered, the access pattern of an integration (each argument a little past the last).
//!
//! First a summary timed in on-CPU time (Linux's `/proc/thread-self/schedstat`), which a
//! loaded machine does not inflate as it does wall time, then criterion's wall-time figures.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench tables
//! cargo bench -p varmass-benches --bench tables -- remembered   # criterion filter
//! ```

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion};
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

/// On-CPU nanoseconds per lookup of `lookup` over `arguments`, the fastest of 5 rounds of
/// 2²⁴ lookups.
fn on_cpu_per_lookup(arguments: &[f64], mut lookup: impl FnMut(f64) -> f64) -> Option<f64> {
    const LOOKUPS: usize = 1 << 24;
    let mut fastest = f64::INFINITY;
    for _ in 0..5 {
        let start = cpu_time_ns()?;
        let mut sum = 0.0;
        for k in 0..LOOKUPS {
            sum += lookup(black_box(arguments[k & 4095]));
        }
        black_box(sum);
        fastest = fastest.min((cpu_time_ns()? - start) as f64 / LOOKUPS as f64);
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
            figures.push(on_cpu_per_lookup(&arguments, |x| {
                table.value(x).unwrap_or(0.0)
            }));
            let mut cursor = Cursor::default();
            figures.push(on_cpu_per_lookup(&arguments, |x| {
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

fn main() {
    summary();
    let mut criterion = Criterion::default().configure_from_args();
    lookups(&mut criterion);
    criterion.final_summary();
}
