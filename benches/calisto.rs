//! Calisto's full six-degree-of-freedom flight (flights/calisto/calisto_flight.toml: rail,
//! ascent, drogue, main, landing) compiled by the macro from `flights/calisto/calisto.vms`
//! and flown by the core's Rust API at relative tolerance 1e-8 (tests/calisto_support: the
//! driver tests/calisto_compiled.rs checks against the interpreter). Issue 36's speed target:
//! ≤ 1/50 of RocketPy 1.13's `Flight(...)` at its defaults, measured interleaved by
//! `benches/peers/rocketpy/calisto_speed.py`, which runs this binary between RocketPy's
//! flights (docs/bench/calisto.md).
//!
//! ```sh
//! cargo bench -p varmass-benches --bench calisto              # figures, counters, costs
//! cargo bench -p varmass-benches --bench calisto -- time 7    # `min_s median_s` of 7 flights
//! cargo bench -p varmass-benches --bench calisto -- only 100  # 100 flights, for perf
//! ```
//!
//! Timed in-process (`Instant` around one whole flight: the systems made, the phases built,
//! every step, event and switch, the solution recorded).

#![allow(clippy::result_large_err)] // the stepper closure's StepError<15> carries the state

#[path = "../tests/calisto_support/mod.rs"]
mod calisto_support;

use std::hint::black_box;
use std::time::Instant;

use calisto_support::{fly, start, Canopies, Flown, CLOSED};
use varmass::core::VariableMassSystem;
use varmass::prelude::variable_mass_system;

/// The compiled Calisto: the canopies' times are its fields, every other parameter its
/// default in the model file.
#[variable_mass_system(file = "../flights/calisto/calisto.vms")]
#[derive(Clone, Copy, Debug)]
struct Calisto {
    drogue_t_open: f64,
    drogue_t_cut: f64,
    main_t_open: f64,
}

fn compiled(c: Canopies) -> Calisto {
    Calisto {
        drogue_t_open: c.drogue_t_open,
        drogue_t_cut: c.drogue_t_cut,
        main_t_open: c.main_t_open,
    }
}

const TOL: f64 = 1e-8;

fn flight() -> Flown {
    fly(compiled, TOL).expect("the flight lands")
}

/// Seconds of each of `k` flights, sorted.
fn times(k: usize) -> Vec<f64> {
    let mut seconds: Vec<f64> = (0..k)
        .map(|_| {
            let begin = Instant::now();
            black_box(flight());
            begin.elapsed().as_secs_f64()
        })
        .collect();
    seconds.sort_by(f64::total_cmp);
    seconds
}

/// The cost of one state rate and of one `accelerations` (q̈ from [q, q̇, m_s], which the
/// rail's sliding phase calls at each of its rate evaluations), at the start's state.
fn rate_cost() -> (f64, f64) {
    let system = compiled(Canopies {
        drogue_t_open: 20.0,
        ..CLOSED
    });
    let state = start();
    let velocity_state = system
        .velocity_state(30.0, &state)
        .expect("a regular state");
    let mut best = (f64::INFINITY, f64::INFINITY);
    for _ in 0..5 {
        let begin = Instant::now();
        for k in 0..100_000 {
            let t = black_box(30.0 + k as f64 * 1e-6);
            black_box(system.state_rate(t, black_box(&state)).ok());
        }
        best.0 = best.0.min(begin.elapsed().as_secs_f64() / 1e5);
        let begin = Instant::now();
        for k in 0..100_000 {
            let t = black_box(30.0 + k as f64 * 1e-6);
            black_box(system.accelerations(t, black_box(&velocity_state)).ok());
        }
        best.1 = best.1.min(begin.elapsed().as_secs_f64() / 1e5);
    }
    best
}

fn report() {
    let f = flight();
    let (t_a, apogee) = f.end_of(0);
    let (t_c, _) = f.end_of(1);
    let (t_l, landing) = f.end_of(2);
    println!(
        "apogee {:.6} m at {t_a:.6} s; 800 m crossing at {t_c:.6} s",
        apogee[2]
    );
    println!(
        "landing at {t_l:.6} s, x {:.6} m, y {:.6} m",
        landing[0], landing[1]
    );
    let mut total = 0;
    for (name, s) in ["ascent (rail, burn, coast)", "drogue", "main"]
        .iter()
        .zip(f.stages)
    {
        println!(
            "{name}: {} steps accepted, {} rejected, {} rate evaluations",
            s.accepted_steps, s.rejected_steps, s.rate_evaluations
        );
        total += s.rate_evaluations;
    }
    let events = f.phased.solution.events.len();
    println!(
        "points recorded {}, events {events}",
        f.phased.solution.times.len()
    );
    let (rate, accelerations) = rate_cost();
    let t = times(21);
    println!("one accelerations {:.0} ns", accelerations * 1e9);
    println!(
        "one state rate {:.0} ns; {total} of them {:.2} ms; a flight: fastest {:.2} ms, median {:.2} ms",
        rate * 1e9,
        rate * total as f64 * 1e3,
        t[0] * 1e3,
        t[t.len() / 2] * 1e3
    );
}

fn main() {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| a != "--bench")
        .collect();
    match args.first().map(String::as_str) {
        Some("time") => {
            let k = args.get(1).and_then(|k| k.parse().ok()).unwrap_or(7);
            let t = times(k);
            println!("{:.6e} {:.6e}", t[0], t[t.len() / 2]);
        }
        Some("only") => {
            let k: usize = args.get(1).and_then(|k| k.parse().ok()).unwrap_or(100);
            for _ in 0..k {
                black_box(flight());
            }
        }
        _ => report(),
    }
}
