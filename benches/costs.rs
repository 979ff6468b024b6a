//! The cost of generated code, against code written by hand (RK4 runs of the sled, the
//! rocket and Kepler; the state rate of the six-degree-of-freedom rocket) and against run-time
//! interpretation of the same derivation; the cost of the derivation itself (the macro's
//! expansion) for 1 to 6 degrees of freedom; the minimal emission (`emit = []`) against the
//! full one for the model files and the chains; and the two sides of the symbolic-inverse
//! threshold (`SYMBOLIC_INVERSE_MAX_DOF`).
//!
//! First a summary of ratios, timed as the fastest of interleaved runs (robust on a shared
//! machine), then the same workloads under criterion for their statistics.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench costs             # summary + criterion
//! cargo bench -p varmass-benches --bench costs -- overhead # criterion filter
//! cargo bench -p varmass-benches --bench costs -- rocket_6dof
//! ```
//!
//! The expansion rows are what users get only in the dev profile (proc macros run
//! unoptimized); `VARMASS_COSTS=expansion` prints those tables alone, without the rest of
//! the summary, criterion or rewriting `docs/bench/costs.txt`:
//!
//! ```sh
//! VARMASS_COSTS=expansion cargo bench --profile dev -p varmass-benches --bench costs
//! VARMASS_COSTS=expansion:rocket_6dof cargo bench --profile dev -p varmass-benches --bench costs
//! VARMASS_COSTS=rocket_6dof cargo bench -p varmass-benches --bench costs   # the 6-dof row alone
//! ```
//!
//! (the second: the emission rows whose name contains `rocket_6dof`, e.g. to profile one).

mod common;

use std::time::Duration;

use criterion::{BenchmarkId, Criterion};
use varmass::core::nalgebra::SVector;
use varmass::core::VariableMassSystem;
use varmass_symbolic::parse::parse_system;
use varmass_symbolic::{
    derive, derive_source,
    mechanics::{Outputs, Parameters, VelocitySolve},
};

use common::adjugate::closed_velocities;
use common::chain::chain_source;
use common::chains::{Chain1, Chain2, Chain2Numeric, Chain3, Chain3Closed, Chain4, Chain5, Chain6};
use common::emission::{expand_for, formatted_size, Subject};
use common::generated::{Kepler, KeplerPolar, Rocket, Rocket6, Sled};
use common::hand::{HandKepler, HandRocket, HandSled};
use common::interpreted::{Interpreted, Mode};
use common::problems::{KeplerProblem, Problem, RocketProblem, SledProblem};
use common::rocket_6dof::{flight_states, HandRocket6};
use common::workloads::{
    chain, chain_parameters, chain_samples, disagreement, expand, expand_with, generated_rates,
    interpreted_rates, kepler_parameters, pair, pair_rounds, rk4_run, rocket_parameters, samples,
    sled_parameters, ParameterValues, CHAIN_PARAMETERS, STEPS,
};

thread_local! {
    /// The summary as printed, for `docs/bench/costs.txt`.
    static REPORT: std::cell::RefCell<String> = const { std::cell::RefCell::new(String::new()) };
}

/// Prints a line of the summary and keeps it for the report file.
macro_rules! say {
    ($($arg:tt)*) => {{
        let line = format!($($arg)*);
        println!("{line}");
        REPORT.with(|report| {
            let mut report = report.borrow_mut();
            report.push_str(&line);
            report.push('\n');
        });
    }};
}

fn summary() {
    say!("== generated vs hand-written: {STEPS} RK4 steps, fastest of 15 interleaved runs");
    let sled = SledProblem::standard();
    let rocket = RocketProblem::standard();
    let kepler = KeplerProblem::standard();
    let kepler_polar = KeplerPolar {
        m1: kepler.system.m1,
        k: kepler.system.k,
    };
    let rows = [
        (
            "sled",
            pair(
                20,
                || rk4_run(&sled.system, sled.initial_state(), sled.end_time()).sum(),
                || {
                    rk4_run(
                        &HandSled(sled.system),
                        sled.initial_state(),
                        sled.end_time(),
                    )
                    .sum()
                },
            ),
        ),
        (
            "rocket",
            pair(
                20,
                || rk4_run(&rocket.system, rocket.initial_state(), rocket.end_time()).sum(),
                || {
                    rk4_run(
                        &HandRocket(rocket.system),
                        rocket.initial_state(),
                        rocket.end_time(),
                    )
                    .sum()
                },
            ),
        ),
        (
            "Kepler",
            pair(
                20,
                || rk4_run(&kepler.system, kepler.initial_state(), kepler.end_time()).sum(),
                || {
                    rk4_run(
                        &HandKepler(kepler.system),
                        kepler.initial_state(),
                        kepler.end_time(),
                    )
                    .sum()
                },
            ),
        ),
        (
            "Kepler, T in polar form",
            pair(
                20,
                || rk4_run(&kepler_polar, kepler.initial_state(), kepler.end_time()).sum(),
                || {
                    let hand = HandKepler(kepler.system);
                    rk4_run(&hand, kepler.initial_state(), kepler.end_time()).sum()
                },
            ),
        ),
    ];
    say!(
        "{:<24} {:>14} {:>14} {:>8}",
        "system",
        "generated µs",
        "hand µs",
        "ratio"
    );
    for (name, (generated, hand)) in rows {
        say!(
            "{name:<24} {:>14.2} {:>14.2} {:>8.3}",
            generated / 1e3,
            hand / 1e3,
            generated / hand
        );
    }

    rocket_6dof_row();

    say!("\n== generated vs interpreted state rate (ns per call, fastest of 15 interleaved)");
    say!(
        "{:<8} {:>10} {:>10} {:>10} {:>9} {:>9} {:>6} {:>10}",
        "system",
        "generated",
        "tape",
        "tree",
        "tape/gen",
        "tree/gen",
        "instr",
        "max diff"
    );
    let sled_states = samples(&sled);
    let rocket_states = samples(&rocket);
    let kepler_states = samples(&kepler);
    let chain3 = chain(|m0, c, l, g| Chain3 { m0, c, l, g });
    let chain3_states = chain_samples::<6>(3);
    let chain3_source = chain_source(3);
    let cases: [(&str, &str, ParameterValues); 4] = [
        ("sled", Sled::SOURCE, sled_parameters(&sled.system)),
        ("rocket", Rocket::SOURCE, rocket_parameters(&rocket.system)),
        ("Kepler", Kepler::SOURCE, kepler_parameters(&kepler.system)),
        ("chain3", &chain3_source, CHAIN_PARAMETERS.to_vec()),
    ];
    for (name, source, parameters) in cases {
        let (Ok(tape), Ok(tree)) = (
            Interpreted::new(source, &parameters, Mode::Tape),
            Interpreted::new(source, &parameters, Mode::Tree),
        ) else {
            say!("{name}: the interpreter could not derive the system");
            continue;
        };
        let (generated, by_tape, by_tree, difference) = match name {
            "sled" => interpretation_row(&sled.system, &tape, &tree, &sled_states),
            "rocket" => interpretation_row(&rocket.system, &tape, &tree, &rocket_states),
            "Kepler" => interpretation_row(&kepler.system, &tape, &tree, &kepler_states),
            _ => interpretation_row(&chain3, &tape, &tree, &chain3_states),
        };
        say!(
            "{name:<8} {generated:>10.1} {by_tape:>10.1} {by_tree:>10.1} {:>9.1} {:>9.1} {:>6} {difference:>10.1e}",
            by_tape / generated,
            by_tree / generated,
            tape.tape_length(),
        );
    }

    derivation_costs();
    emission_costs("");

    say!("\n== symbolic-inverse threshold: q̇ from p in closed form vs LDLᵀ or Cholesky (fastest of 101 alternating rounds)");
    threshold_row(
        2,
        chain(|m0, c, l, g| Chain2 { m0, c, l, g }),
        chain(|m0, c, l, g| Chain2Numeric { m0, c, l, g }),
        "closed (macro)",
        "Cholesky",
    );
    threshold_row(
        3,
        chain(|m0, c, l, g| Chain3Closed { m0, c, l, g }),
        chain3,
        "closed",
        "LDLᵀ (macro)",
    );
    velocity_tapes(2);
    velocity_tapes(3);
    threshold_expansion();

    say!("\n== generated state rate of the n-link chain (ns per call)");
    chain_rate(1, &chain(|m0, c, l, g| Chain1 { m0, c, l, g }));
    chain_rate(2, &chain(|m0, c, l, g| Chain2 { m0, c, l, g }));
    chain_rate(3, &chain3);
    chain_rate(4, &chain(|m0, c, l, g| Chain4 { m0, c, l, g }));
    chain_rate(5, &chain(|m0, c, l, g| Chain5 { m0, c, l, g }));
    chain_rate(6, &chain(|m0, c, l, g| Chain6 { m0, c, l, g }));
    say!("");
}

/// Parse, derive and emit time of the 1–6-link chains (the macro's work, in steps).
fn derivation_costs() {
    say!("\n== derivation cost (parse + derive + checks + emit), least thread CPU time of 7 to 10 runs");
    say!(
        "{:<6} {:>10} {:>10} {:>10} {:>10} {:>12}",
        "links",
        "parse µs",
        "derive ms",
        "emit ms",
        "total ms",
        "code bytes"
    );
    for links in 1..=6 {
        let source = chain_source(links);
        let budget = Duration::from_secs(2);
        let (parse, ast) = fastest_cpu(budget, || parse_system(&source));
        let Ok(ast) = ast else {
            say!("{links}: does not parse");
            continue;
        };
        let (derive_time, derived) = fastest_cpu(budget, || derive(&ast, chain_parameters()));
        if derived.is_err() {
            say!("{links}: does not derive");
            continue;
        }
        let (total, tokens) = fastest_cpu(budget, || expand(links, &source));
        // Emitting alone cannot be timed apart (a derivation is consumed by `emit_system`
        // and cannot be cloned), so it is the remainder.
        let emit_time = total.saturating_sub(parse + derive_time);
        let code = tokens.to_string().len();
        say!(
            "{links:<6} {:>10.1} {:>10.2} {:>10.2} {:>10.2} {code:>12}",
            parse.as_secs_f64() * 1e6,
            derive_time.as_secs_f64() * 1e3,
            emit_time.as_secs_f64() * 1e3,
            total.as_secs_f64() * 1e3,
        );
    }
}

/// The state rate of the six-degree-of-freedom rocket (`models/rocket_6dof.vms`) generated
/// against written by hand (`common/rocket_6dof.rs`; `tests/rigid_6dof_hand.rs` holds the two
/// equal): issue 22's target is ≤ 1.05×.
fn rocket_6dof_row() {
    let hand = HandRocket6::standard();
    let generated = Rocket6::like(&hand);
    let states = flight_states(1024);
    let (by_macro, by_hand) = pair_rounds(
        51,
        20,
        || rocket_6dof_rates(|s| generated.state_rate(0.5, s), &states),
        || rocket_6dof_rates(|s| hand.state_rate(0.5, s), &states),
    );
    let per_call = |ns: f64| ns / states.len() as f64;
    say!(
        "\n== 6-dof rocket state rate (ns per call, fastest of 51 interleaved rounds): \
         generated {:.1}, hand-written {:.1}, ratio {:.3} (target ≤ 1.05)",
        per_call(by_macro),
        per_call(by_hand),
        by_macro / by_hand
    );
}

/// The sum of every state rate's components over `states` (NaN for a refused state).
fn rocket_6dof_rates<E>(
    rate: impl Fn(&SVector<f64, 13>) -> Result<SVector<f64, 13>, E>,
    states: &[SVector<f64, 13>],
) -> f64 {
    states
        .iter()
        .map(|s| rate(std::hint::black_box(s)).map_or(f64::NAN, |r| r.sum()))
        .sum()
}

/// The systems whose minimal and full emissions are compared: the model files and the
/// 1–6-link chains.
fn emission_subjects() -> Vec<(Subject, Parameters)> {
    let models = [
        ("sled.vms", &["impact"][..]),
        ("sled_paper_form.vms", &[]),
        ("rocket.vms", &[]),
        ("rocket.vms", &["drag"]),
        ("leaking_spring_pendulum.vms", &[]),
        ("leaking_spring_pendulum_cartesian.vms", &[]),
        ("double_pendulum.vms", &[]),
        ("swinging_tank.vms", &[]),
        ("pitching_rocket.vms", &[]),
        ("rocket_6dof.vms", &[]),
        ("spinning_spacecraft.vms", &[]),
    ];
    let mut subjects: Vec<(Subject, Parameters)> = models
        .iter()
        .map(|(file, with)| (Subject::model(file, with), Parameters::Inferred))
        .collect();
    for links in 1..=6 {
        let chain = Subject {
            name: format!("chain, {links} links"),
            source: chain_source(links),
            with: Vec::new(),
        };
        subjects.push((chain, chain_parameters()));
    }
    subjects
}

/// Expansion time and generated code size, `emit = []` against every output.
/// Only the subjects whose name contains `only` (all for `""`).
fn emission_costs(only: &str) {
    say!(
        "\n== minimal (emit = []) vs full emission (and full with the Taylor recurrences): \
         expansion (parse, tags, derive, emit; least thread CPU time of 7 to 10 runs) and code"
    );
    say!(
        "{:<40} {:>9} {:>9} {:>6} {:>10} {:>10} {:>6} {:>10} {:>10}",
        "system",
        "full ms",
        "min ms",
        "ratio",
        "full B",
        "min B",
        "ratio",
        "+taylor ms",
        "+taylor B"
    );
    let budget = Duration::from_secs(2);
    let subjects = emission_subjects().into_iter();
    for (subject, parameters) in subjects.filter(|(s, _)| s.name.contains(only)) {
        let (full_time, full) =
            fastest_cpu(budget, || expand_for(&subject, &parameters, Outputs::FULL));
        let (min_time, minimal) = fastest_cpu(budget, || {
            expand_for(&subject, &parameters, Outputs::MINIMAL)
        });
        // Every output and the opt-in Taylor recurrences (`emit = [..., "taylor"]`).
        let with_taylor = Outputs {
            taylor: true,
            ..Outputs::FULL
        };
        let (taylor_time, taylor) =
            fastest_cpu(budget, || expand_for(&subject, &parameters, with_taylor));
        let (full_size, min_size) = (formatted_size(full), formatted_size(minimal));
        say!(
            "{:<40} {:>9.2} {:>9.2} {:>6.2} {full_size:>10} {min_size:>10} {:>6.2} {:>10.2} {:>10}",
            subject.name,
            full_time.as_secs_f64() * 1e3,
            min_time.as_secs_f64() * 1e3,
            min_time.as_secs_f64() / full_time.as_secs_f64(),
            min_size as f64 / full_size.max(1) as f64,
            taylor_time.as_secs_f64() * 1e3,
            formatted_size(taylor),
        );
    }
}

/// (generated, tape, tree) ns per call and the largest disagreement.
fn interpretation_row<Sys, const N: usize, const S: usize>(
    system: &Sys,
    tape: &Interpreted,
    tree: &Interpreted,
    states: &[SVector<f64, S>],
) -> (f64, f64, f64, f64)
where
    Sys: VariableMassSystem<N, S>,
{
    let per_call = states.len() as f64;
    let (generated, by_tape) = pair(
        200,
        || generated_rates(system, states),
        || interpreted_rates(tape, states),
    );
    let (_, by_tree) = pair(
        20,
        || generated_rates(system, states),
        || interpreted_rates(tree, states),
    );
    (
        generated / per_call,
        by_tape / per_call,
        by_tree / per_call,
        disagreement(system, tape, states),
    )
}

fn threshold_row<A, B, const N: usize, const S: usize>(
    links: usize,
    a: A,
    b: B,
    a_name: &str,
    b_name: &str,
) where
    A: VariableMassSystem<N, S>,
    B: VariableMassSystem<N, S>,
{
    let states = chain_samples::<S>(links);
    // Two rates a few ns apart: many short alternating rounds, so that both meet the same
    // quiet moments of a shared machine.
    let (ta, tb) = pair_rounds(
        101,
        200,
        || generated_rates(&a, &states),
        || generated_rates(&b, &states),
    );
    let calls = states.len() as f64;
    let difference = states
        .iter()
        .filter_map(|s| Some((a.state_rate(0.5, s).ok()?, b.state_rate(0.5, s).ok()?)))
        .map(|(x, y)| (x - y).amax() / (1.0 + x.amax()))
        .fold(0.0, f64::max);
    say!(
        "{links} links: {a_name} {:.1} ns, {b_name} {:.1} ns per state rate (ratio {:.2}; agree to {difference:.0e})",
        ta / calls,
        tb / calls,
        ta / tb,
    );
}

/// The other side of the symbolic-inverse threshold: what the closed-form q̇ costs the
/// macro for the 3-link chain (derive and emit, least thread CPU time of 7 to 10 runs) and the code it generates,
/// against the LDLᵀ the macro emits. Its figures in the dev profile are the ones users get
/// (`cargo bench --profile dev -p varmass-benches --bench costs -- none`).
fn threshold_expansion() {
    let source = chain_source(3);
    let budget = Duration::from_secs(5);
    let (ldlt_time, ldlt) = fastest_cpu(budget, || expand(3, &source));
    let (closed_time, closed) = fastest_cpu(budget, || {
        expand_with(3, &source, |d| {
            d.velocities = VelocitySolve::Symbolic(closed_velocities(d));
        })
    });
    let (ldlt_size, closed_size) = (formatted_size(ldlt), formatted_size(closed));
    say!(
        "3 links, expansion: LDLᵀ {:.2} ms, {ldlt_size} B; q̇ closed form {:.2} ms, \
         {closed_size} B (×{:.2} time, ×{:.2} code)",
        ldlt_time.as_secs_f64() * 1e3,
        closed_time.as_secs_f64() * 1e3,
        closed_time.as_secs_f64() / ldlt_time.as_secs_f64(),
        closed_size as f64 / ldlt_size as f64,
    );
}

/// Instructions to get q̇ from p at run time: closed-form tape vs the M and b entries that a
/// Cholesky solve then consumes.
fn velocity_tapes(links: usize) {
    let Ok(mut d) = derive_source(&chain_source(links), chain_parameters()) else {
        return;
    };
    let mut numeric: Vec<_> = d.mass_matrix.iter().flatten().copied().collect();
    numeric.extend(&d.momentum_offset);
    let numeric = d.pool.compile(&numeric).len();
    let closed = match (&d.velocities, links) {
        (varmass_symbolic::mechanics::VelocitySolve::Symbolic(v), _) => d.pool.compile(v).len(),
        (_, 3) => {
            let v = closed_velocities(&mut d);
            d.pool.compile(&v).len()
        }
        _ => 0,
    };
    say!(
        "{links} links: q̇ closed form {closed} tape instructions; M and b {numeric} instructions + a {links}×{links} Cholesky"
    );
}

fn chain_rate<Sys, const N: usize, const S: usize>(links: usize, system: &Sys)
where
    Sys: VariableMassSystem<N, S>,
{
    let states = chain_samples::<S>(links);
    let (t, _) = pair(
        200,
        || generated_rates(system, &states),
        || generated_rates(system, &states),
    );
    say!("{links} links: {:.1}", t / states.len() as f64);
}

fn criterion_benches(c: &mut Criterion) {
    let sled = SledProblem::standard();
    let rocket = RocketProblem::standard();
    let kepler = KeplerProblem::standard();

    let mut group = c.benchmark_group("overhead_rk4_1000_steps");
    group.bench_function(BenchmarkId::new("sled", "generated"), |b| {
        b.iter(|| rk4_run(&sled.system, sled.initial_state(), sled.end_time()))
    });
    group.bench_function(BenchmarkId::new("sled", "hand"), |b| {
        b.iter(|| {
            rk4_run(
                &HandSled(sled.system),
                sled.initial_state(),
                sled.end_time(),
            )
        })
    });
    group.bench_function(BenchmarkId::new("rocket", "generated"), |b| {
        b.iter(|| rk4_run(&rocket.system, rocket.initial_state(), rocket.end_time()))
    });
    group.bench_function(BenchmarkId::new("rocket", "hand"), |b| {
        b.iter(|| {
            rk4_run(
                &HandRocket(rocket.system),
                rocket.initial_state(),
                rocket.end_time(),
            )
        })
    });
    group.bench_function(BenchmarkId::new("Kepler", "generated"), |b| {
        b.iter(|| rk4_run(&kepler.system, kepler.initial_state(), kepler.end_time()))
    });
    group.bench_function(BenchmarkId::new("Kepler", "hand"), |b| {
        b.iter(|| {
            rk4_run(
                &HandKepler(kepler.system),
                kepler.initial_state(),
                kepler.end_time(),
            )
        })
    });
    group.finish();

    let mut group = c.benchmark_group("state_rate_16_calls");
    let states = samples(&kepler);
    let parameters = kepler_parameters(&kepler.system);
    if let (Ok(tape), Ok(tree)) = (
        Interpreted::new(Kepler::SOURCE, &parameters, Mode::Tape),
        Interpreted::new(Kepler::SOURCE, &parameters, Mode::Tree),
    ) {
        group.bench_function(BenchmarkId::new("Kepler", "generated"), |b| {
            b.iter(|| generated_rates(&kepler.system, &states))
        });
        group.bench_function(BenchmarkId::new("Kepler", "tape"), |b| {
            b.iter(|| interpreted_rates(&tape, &states))
        });
        group.bench_function(BenchmarkId::new("Kepler", "tree"), |b| {
            b.iter(|| interpreted_rates(&tree, &states))
        });
    }
    let states = chain_samples::<6>(3);
    let chain3 = chain(|m0, c, l, g| Chain3 { m0, c, l, g });
    let chain3_closed = chain(|m0, c, l, g| Chain3Closed { m0, c, l, g });
    group.bench_function(BenchmarkId::new("chain3", "generated Cholesky"), |b| {
        b.iter(|| generated_rates(&chain3, &states))
    });
    group.bench_function(BenchmarkId::new("chain3", "generated closed"), |b| {
        b.iter(|| generated_rates(&chain3_closed, &states))
    });
    let states = chain_samples::<4>(2);
    let chain2 = chain(|m0, c, l, g| Chain2 { m0, c, l, g });
    let chain2_numeric = chain(|m0, c, l, g| Chain2Numeric { m0, c, l, g });
    group.bench_function(BenchmarkId::new("chain2", "generated closed"), |b| {
        b.iter(|| generated_rates(&chain2, &states))
    });
    group.bench_function(BenchmarkId::new("chain2", "generated Cholesky"), |b| {
        b.iter(|| generated_rates(&chain2_numeric, &states))
    });
    group.finish();

    let hand = HandRocket6::standard();
    let generated = Rocket6::like(&hand);
    let states = flight_states(1024);
    let mut group = c.benchmark_group("rocket_6dof_state_rate_1024_calls");
    group.bench_function("generated", |b| {
        b.iter(|| rocket_6dof_rates(|s| generated.state_rate(0.5, s), &states))
    });
    group.bench_function("hand", |b| {
        b.iter(|| rocket_6dof_rates(|s| hand.state_rate(0.5, s), &states))
    });
    group.finish();

    let mut group = c.benchmark_group("expansion");
    group.sample_size(10);
    for links in 1..=6 {
        let source = chain_source(links);
        group.bench_function(BenchmarkId::new("chain", links), |b| {
            b.iter(|| expand(links, &source))
        });
    }
    group.finish();

    let mut group = c.benchmark_group("emission");
    group.sample_size(10);
    for (subject, parameters) in emission_subjects() {
        for (label, outputs) in [("full", Outputs::FULL), ("minimal", Outputs::MINIMAL)] {
            group.bench_function(BenchmarkId::new(&subject.name, label), |b| {
                b.iter(|| expand_for(&subject, &parameters, outputs))
            });
        }
    }
    group.finish();
}

/// CPU time of the calling thread: the expansion rows are timed by it, since on a shared
/// machine the wall clock also counts the waits for a core (at load 16 on 2 cores, several
/// times the work). Cache and memory contention still add to it, so the fastest of several
/// runs is taken as well.
fn thread_cpu_time() -> Duration {
    let mut now = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `now` is a valid, writable timespec; the clock id is a constant the platform
    // defines. On failure `now` stays zero and the runs time as 0, which the tables show.
    let status = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut now) };
    if status != 0 {
        return Duration::ZERO;
    }
    Duration::new(now.tv_sec as u64, now.tv_nsec as u32)
}

/// The least thread CPU time of 7 to 10 runs of `work` (at most about `budget` of wall
/// time after the 7th), and the last result.
fn fastest_cpu<T>(budget: Duration, mut work: impl FnMut() -> T) -> (Duration, T) {
    let start = std::time::Instant::now();
    let mut best = Duration::MAX;
    let mut runs = 0;
    loop {
        let begin = thread_cpu_time();
        let result = std::hint::black_box(work());
        best = best.min(thread_cpu_time().saturating_sub(begin));
        runs += 1;
        if runs >= 10 || (runs >= 7 && start.elapsed() >= budget) {
            return (best, result);
        }
    }
}

/// The derivation-cost and emission tables alone (`VARMASS_COSTS=expansion`).
fn expansion_summary(only: &str) {
    if only.is_empty() {
        derivation_costs();
    }
    emission_costs(only);
    if only.is_empty() {
        threshold_expansion();
    }
}

fn main() {
    if let Some(only) = std::env::var("VARMASS_COSTS").ok().and_then(|v| {
        v.strip_prefix("expansion")
            .map(|rest| rest.trim_start_matches(':').to_string())
    }) {
        expansion_summary(&only);
        return;
    }
    if std::env::var("VARMASS_COSTS").as_deref() == Ok("rocket_6dof") {
        // The 6-dof row alone (a minute instead of the whole summary; writes no file).
        rocket_6dof_row();
        return;
    }
    summary();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/bench/costs.txt");
    let written = REPORT.with(|report| {
        let header = "# cargo bench -p varmass-benches --bench costs (summary part)\n";
        std::fs::write(&path, format!("{header}{}", report.borrow()))
    });
    if let Err(error) = written {
        eprintln!("could not write {}: {error}", path.display());
    }
    let mut criterion = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args();
    criterion_benches(&mut criterion);
    criterion.final_summary();
}
