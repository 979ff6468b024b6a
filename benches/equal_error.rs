//! The high-order comparison at equal final error: DOP853 against adaptive Dormand–Prince
//! and against `ode_solvers`' Dop853, each method's cost read off its own work-precision
//! curve at exactly the target error.
//!
//! Between the two settings of a sweep whose errors bracket the target (the first such pair
//! as the tolerance tightens), log evaluations and log seconds are interpolated linearly in
//! log error. The seconds of those bracketing settings are measured again, interleaved
//! (every round runs each of them once, in turn) and keeping each one's fastest round, so
//! that a burst of load on a shared machine cannot favour one method over another.

use std::hint::black_box;
use std::time::Instant;

use crate::common::problems::Problem;
use crate::{run_once, Method, Point};

/// Rounds of the interleaved timing, and runs per round of each setting.
const ROUNDS: usize = 30;
const RUNS_PER_ROUND: usize = 10;

/// The methods compared and the one each ratio is taken against.
const OURS: Method = Method::Dop853;
const AGAINST: [Method; 2] = [Method::DormandPrinceAdaptive, Method::PeerDop853];
/// Taylor's method, read off its curve as the others and compared with DOP853 (its
/// "evaluations" are expansions, one per step, so only its time is compared).
const TAYLOR: Method = Method::Taylor;

/// One method's cost at the target error.
#[derive(Clone, Copy, Debug)]
pub struct Cost {
    /// State-rate evaluations, interpolated.
    pub evaluations: f64,
    /// Seconds per run, interpolated from the interleaved timings.
    pub seconds: f64,
}

/// The two settings of `method`'s sweep on `problem` whose errors bracket `target`, with
/// the weight of the second in the log-log interpolation.
fn bracket<'a>(
    points: &'a [Point],
    problem: &str,
    method: Method,
    target: f64,
) -> Option<(&'a Point, &'a Point, f64)> {
    let curve: Vec<&Point> = points
        .iter()
        .filter(|p| p.problem == problem && p.method == method)
        .collect();
    curve.windows(2).find_map(|pair| {
        let (a, b) = (pair[0], pair[1]);
        let (low, high) = (a.error.min(b.error), a.error.max(b.error));
        if !(low <= target && target <= high) || low <= 0.0 {
            return None;
        }
        let weight = if high > low {
            (target.ln() - a.error.ln()) / (b.error.ln() - a.error.ln())
        } else {
            0.0
        };
        Some((a, b, weight))
    })
}

/// The fastest of the interleaved rounds for each of `settings` (method, setting).
fn interleaved_seconds<P, const N: usize, const S: usize>(
    problem: &P,
    settings: &[(Method, f64)],
) -> Vec<f64>
where
    P: Problem<N, S>,
{
    let mut best = vec![f64::INFINITY; settings.len()];
    for _ in 0..ROUNDS {
        for (slot, &(method, setting)) in best.iter_mut().zip(settings) {
            let start = Instant::now();
            for _ in 0..RUNS_PER_ROUND {
                let _ = black_box(run_once(problem, method, black_box(setting)));
            }
            let seconds = start.elapsed().as_secs_f64() / RUNS_PER_ROUND as f64;
            *slot = slot.min(seconds);
        }
    }
    best
}

/// Log-linear interpolation between `a` and `b` with weight `w` on `b`.
fn between(a: f64, b: f64, w: f64) -> f64 {
    (a.ln() + w * (b.ln() - a.ln())).exp()
}

/// The cost of DOP853 and of the methods it is compared with at `target` on `problem`,
/// or `None` for a method whose sweep does not reach the target.
pub fn costs<P, const N: usize, const S: usize>(
    problem: &P,
    points: &[Point],
    target: f64,
) -> Vec<(Method, Option<Cost>)>
where
    P: Problem<N, S>,
{
    let methods = [OURS, AGAINST[0], AGAINST[1], TAYLOR];
    let brackets: Vec<_> = methods
        .iter()
        .map(|&m| bracket(points, P::NAME, m, target))
        .collect();
    let settings: Vec<(Method, f64)> = brackets
        .iter()
        .flatten()
        .flat_map(|(a, b, _)| [(a.method, a.setting), (b.method, b.setting)])
        .collect();
    let seconds = interleaved_seconds(problem, &settings);
    let mut timed = seconds.chunks(2);
    methods
        .iter()
        .zip(brackets)
        .map(|(&method, found)| {
            let cost = found.map(|(a, b, w)| {
                let pair = timed.next().expect("two timings per bracket");
                let evaluations = |p: &Point| p.statistics.rate_evaluations as f64;
                Cost {
                    evaluations: between(evaluations(a), evaluations(b), w),
                    seconds: between(pair[0], pair[1], w),
                }
            });
            (method, cost)
        })
        .collect()
}

/// The table header of [`row`].
pub fn header() -> String {
    format!(
        "{:<24} {:>7} {:>20} {:>9} {:>9} {:>10} {:>10} {:>10} {:>10}",
        "problem",
        "error",
        "method",
        "evals",
        "time µs",
        "evals/DP5",
        "time/DP5",
        "evals/peer",
        "time/peer"
    )
}

/// The rows of one problem: each method's cost, DOP853's ratios to the others and whether
/// they meet the high-order end's criteria (evaluations at most 40 % of Dormand–Prince's,
/// at most 5 % more than the peer's, in less time than the peer) when `judged`.
pub fn rows(
    problem: &str,
    target: f64,
    costs: &[(Method, Option<Cost>)],
    judged: bool,
) -> Vec<String> {
    let cost = |method: Method| costs.iter().find(|(m, _)| *m == method).and_then(|c| c.1);
    let ratio = |against: Method, of: fn(&Cost) -> f64| -> Option<f64> {
        Some(of(&cost(OURS)?) / of(&cost(against)?))
    };
    let show = |ratio: Option<f64>| ratio.map_or("–".into(), |r| format!("{r:.3}"));
    let ratios = [
        ratio(AGAINST[0], |c| c.evaluations),
        ratio(AGAINST[0], |c| c.seconds),
        ratio(AGAINST[1], |c| c.evaluations),
        ratio(AGAINST[1], |c| c.seconds),
    ];
    let mut rows: Vec<String> = costs
        .iter()
        .map(|(method, cost)| match cost {
            Some(c) => format!(
                "{problem:<24} {target:>7.0e} {:>20} {:>9.0} {:>9.2}",
                method.name(),
                c.evaluations,
                c.seconds * 1e6
            ),
            None => format!(
                "{problem:<24} {target:>7.0e} {:>20}  (target not bracketed)",
                method.name()
            ),
        })
        .collect();
    let met = match ratios {
        [Some(dp), _, Some(peer), Some(time)] if judged => {
            if dp <= 0.40 && peer <= 1.05 && time < 1.0 {
                "criteria met"
            } else {
                "criteria NOT met"
            }
        }
        _ => "",
    };
    let taylor = cost(TAYLOR)
        .zip(cost(OURS))
        .map(|(t, d)| format!("{:.3}", t.seconds / d.seconds));
    rows.push(format!(
        "{problem:<24} {target:>7.0e} {:>20} {:>9} {:>9}",
        "Taylor time/DOP853",
        "",
        taylor.unwrap_or("–".into())
    ));
    rows.push(format!(
        "{problem:<24} {target:>7.0e} {:>20} {:>9} {:>9} {:>10} {:>10} {:>10} {:>10}  {met}",
        "DOP853 ratios",
        "",
        "",
        show(ratios[0]),
        show(ratios[1]),
        show(ratios[2]),
        show(ratios[3]),
    ));
    rows
}
