//! The timing rule of the sweeps: the fastest of several runs (SciML's WorkPrecisionSet
//! convention). On a shared machine noise only ever adds time, so the minimum is the best
//! estimate of the cost itself.

use std::hint::black_box;
use std::time::{Duration, Instant};

/// Runs `work` at least `min_runs` times and until about `budget` has been spent (at most
/// `max_runs`), and returns the fastest run and the last result.
pub fn fastest_of<T>(
    min_runs: usize,
    max_runs: usize,
    budget: Duration,
    mut work: impl FnMut() -> T,
) -> (Duration, T) {
    let start = Instant::now();
    let mut best = Duration::MAX;
    let mut runs = 0;
    loop {
        let begin = Instant::now();
        let result = black_box(work());
        best = best.min(begin.elapsed());
        runs += 1;
        if runs >= max_runs || (runs >= min_runs && start.elapsed() >= budget) {
            return (best, result);
        }
    }
}

/// The fastest run of the default sweep rule: 3 to 25 runs, about 0.3 s per point.
pub fn fastest<T>(work: impl FnMut() -> T) -> (Duration, T) {
    fastest_of(3, 25, Duration::from_millis(300), work)
}
