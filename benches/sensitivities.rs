//! The cost of forward sensitivities (issue 37; docs/sensitivities.md): the 6-dof rocket of
//! `models/rocket_6dof.vms` (zyx angles, S = 13) burning for 3.9 s, DOP853 at rtol = atol =
//! 1e-8, plain against `Sensitive` with k = 1, 3 and 6 parameter columns (the error control
//! over the sensitivities too, and without them: `with_error_control(false)`), the fastest of
//! several runs each, the sides interleaved round by round. The issue's target: ≤ 0.6 (1 + k)
//! times the plain run. Then the state rate alone, plain and augmented, and the evaluations
//! of a run: what the rest of a step (the stepper's arithmetic over S (1 + k) entries) costs.
//!
//! ```sh
//! cargo bench -p varmass-benches --bench sensitivities
//! ```

use std::hint::black_box;
use std::time::Instant;

use varmass::core::sensitivity::{Column, Sensitive};
use varmass::core::VariableMassSystem;
use varmass::prelude::*;

#[variable_mass_system(file = "../models/rocket_6dof.vms", emit = ["sensitivities"])]
#[allow(non_snake_case)] // the model's names: A_d, C_d
#[derive(Clone, Copy)]
struct Rocket {
    mu: f64,
    m_d: f64,
    A_d: f64,
    C_d: f64,
    k_a: f64,
    k_c: f64,
    g_c: f64,
    l: f64,
    u_e: f64,
    delta: f64,
    g: f64,
}

const ROCKET: Rocket = Rocket {
    mu: 2.0,
    m_d: 60.0,
    A_d: 20.0,
    C_d: 2.0,
    k_a: 0.8,
    k_c: 0.2,
    g_c: 1.0,
    l: 1.5,
    u_e: 2000.0,
    delta: 0.05,
    g: 9.81,
};

const COLUMNS: [Column; 6] = [
    Column::Parameter("u_e"),
    Column::Parameter("mu"),
    Column::Parameter("delta"),
    Column::Parameter("m_d"),
    Column::Parameter("A_d"),
    Column::Parameter("l"),
];

fn control() -> StepControl {
    StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-8,
        absolute_tolerance: 1e-8,
        ..AdaptiveControl::dop853()
    })
}

/// The start: at rest but for a climb of 10 m/s and a pitch rate of 0.1 rad/s, tilted by
/// 0.2 rad, with 8 kg of propellant (4 s at μ = 2).
fn start() -> SVector<f64, 13> {
    let mut velocity_state = SVector::<f64, 13>::zeros();
    velocity_state[4] = 0.2;
    velocity_state[8] = 10.0;
    velocity_state[10] = 0.1;
    velocity_state[12] = 8.0;
    ROCKET.momentum_state(0.0, &velocity_state)
}

/// One burn of `system` from `state`: its steps and the time taken.
fn fly<Sys: VariableMassSystem<6, SA>, const SA: usize>(
    system: &Sys,
    state: SVector<f64, SA>,
) -> (usize, f64) {
    let begin = Instant::now();
    let mut stepper = Dop853::new(system, 0.0, state, control()).expect("a stepper");
    let solution = run(&mut stepper, &RunConfig::until(3.9), &[]).expect("the burn");
    let seconds = begin.elapsed().as_secs_f64();
    (black_box(solution).statistics.accepted_steps, seconds)
}

/// The fastest of `runs` burns of `system` from `state`.
fn fastest<Sys: VariableMassSystem<6, SA>, const SA: usize>(
    system: &Sys,
    state: SVector<f64, SA>,
    runs: usize,
) -> (usize, f64) {
    (0..runs)
        .map(|_| fly(system, state))
        .fold((0, f64::INFINITY), |(_, best), (steps, t)| {
            (steps, best.min(t))
        })
}

/// The fastest mean time of one state rate of `system` at `state`, in ns.
fn rate_time<Sys: VariableMassSystem<6, SA>, const SA: usize>(
    system: &Sys,
    state: SVector<f64, SA>,
) -> f64 {
    let calls = 100_000;
    (0..5)
        .map(|_| {
            let begin = Instant::now();
            for i in 0..calls {
                let t = black_box(i as f64 * 1e-9);
                black_box(system.state_rate(t, black_box(&state)).expect("a rate"));
            }
            begin.elapsed().as_secs_f64() / calls as f64 * 1e9
        })
        .fold(f64::INFINITY, f64::min)
}

/// The state rate alone, plain and with 1, 3, 6 columns (filled with made-up values), and
/// the evaluations a run takes.
fn rates_alone(
    systems: (
        &Sensitive<Rocket, 13>,
        &Sensitive<Rocket, 13>,
        &Sensitive<Rocket, 13>,
    ),
) {
    let (one, three, six) = systems;
    let mut filled = six.start::<91>(&start());
    for i in 13..91 {
        filled[i] = 0.01 * i as f64;
    }
    let plain = rate_time(&ROCKET, start());
    let k1 = rate_time(one, SVector::<f64, 26>::from_fn(|i, _| filled[i]));
    let k3 = rate_time(three, SVector::<f64, 52>::from_fn(|i, _| filled[i]));
    let k6 = rate_time(six, filled);
    let mut stepper = Dop853::new(&ROCKET, 0.0, start(), control()).expect("a stepper");
    let solution = run(&mut stepper, &RunConfig::until(3.9), &[]).expect("the burn");
    let evaluations = solution.statistics.rate_evaluations;
    println!("the state rate alone: plain {plain:.0} ns, k = 1/3/6 {k1:.0}/{k3:.0}/{k6:.0} ns");
    println!(
        "({:.2}/{:.2}/{:.2} × plain); {evaluations} evaluations in the plain run",
        k1 / plain,
        k3 / plain,
        k6 / plain
    );
}

fn main() {
    let plain_start = start();
    let one: Sensitive<Rocket, 13> = Sensitive::new::<6, 26>(ROCKET, &COLUMNS[..1]).unwrap();
    let three: Sensitive<Rocket, 13> = Sensitive::new::<6, 52>(ROCKET, &COLUMNS[..3]).unwrap();
    let six: Sensitive<Rocket, 13> = Sensitive::new::<6, 91>(ROCKET, &COLUMNS).unwrap();
    // The columns left out of the error control (CVODES's errconS = false).
    let one_free: Sensitive<Rocket, 13> = Sensitive::new::<6, 26>(ROCKET, &COLUMNS[..1])
        .unwrap()
        .with_error_control(false);
    let three_free: Sensitive<Rocket, 13> = Sensitive::new::<6, 52>(ROCKET, &COLUMNS[..3])
        .unwrap()
        .with_error_control(false);
    let six_free: Sensitive<Rocket, 13> = Sensitive::new::<6, 91>(ROCKET, &COLUMNS)
        .unwrap()
        .with_error_control(false);
    rates_alone((&one, &three, &six));
    let starts = (
        one.start::<26>(&plain_start),
        three.start::<52>(&plain_start),
        six.start::<91>(&plain_start),
    );
    let mut best = [(0usize, f64::INFINITY); 7];
    for _ in 0..5 {
        let rounds = [
            fastest(&ROCKET, plain_start, 5),
            fastest(&one, starts.0, 5),
            fastest(&three, starts.1, 5),
            fastest(&six, starts.2, 5),
            fastest(&one_free, starts.0, 5),
            fastest(&three_free, starts.1, 5),
            fastest(&six_free, starts.2, 5),
        ];
        for (b, r) in best.iter_mut().zip(rounds) {
            *b = (r.0, b.1.min(r.1));
        }
    }
    let plain = best[0].1;
    println!("6-dof rocket, 3.9 s burn, DOP853 at 1e-8, the fastest of 25 runs each, interleaved");
    println!("plain: {} steps, {:.3} ms", best[0].0, plain * 1e3);
    let rows = [1usize, 3, 6, 1, 3, 6]
        .into_iter()
        .zip(&best[1..])
        .enumerate();
    for (row, (k, (steps, t))) in rows {
        let columns = if row < 3 {
            "controlled"
        } else {
            "uncontrolled"
        };
        println!(
            "k = {k}, columns {columns}: {steps} steps, {:.3} ms, {:.2} × plain (target ≤ {:.1})",
            t * 1e3,
            t / plain,
            0.6 * (1 + k) as f64
        );
    }
}
