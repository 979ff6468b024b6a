//! The workloads the cost benchmarks time: runs, state-rate sweeps over sample states,
//! the macro's pipeline, and the interleaved fastest-of timing of two workloads.

use std::hint::black_box;
use std::time::Duration;

use proc_macro2::{Ident, Span};
use quote::quote;
use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{ClassicalRk4, FixedStep};
use varmass::core::{StepOutcome, Stepper, VariableMassSystem};
use varmass_symbolic::emit::{emit_system, Target};
use varmass_symbolic::{
    derive_source,
    mechanics::{Derivation, Parameters},
};

use super::generated::{Kepler, Rocket, Sled};
use super::interpreted::Interpreted;
use super::problems::Problem;
use super::timing::fastest_of;

/// RK4 steps per run in the overhead comparison.
pub const STEPS: usize = 1000;

/// `STEPS` RK4 steps from `start` over `[0, end]`; the final state.
pub fn rk4_run<Sys, const N: usize, const S: usize>(
    system: &Sys,
    start: SVector<f64, S>,
    end: f64,
) -> SVector<f64, S>
where
    Sys: VariableMassSystem<N, S>,
{
    let fixed = FixedStep {
        step: end / STEPS as f64,
    };
    let Ok(mut stepper) = ClassicalRk4::new(system, 0.0, start, fixed) else {
        return SVector::from_element(f64::NAN);
    };
    if stepper.set_stop_time(end).is_err() {
        return SVector::from_element(f64::NAN);
    }
    while let Ok(StepOutcome::Advanced) = stepper.step() {}
    *stepper.state()
}

/// States along the reference motion where the state rate is sampled.
pub fn samples<P, const N: usize, const S: usize>(problem: &P) -> Vec<SVector<f64, S>>
where
    P: Problem<N, S>,
{
    let mut states = Vec::new();
    let mut state = problem.initial_state();
    let fixed = FixedStep {
        step: problem.end_time() / 64.0,
    };
    if let Ok(mut stepper) = ClassicalRk4::new(problem.system(), 0.0, state, fixed) {
        for _ in 0..16 {
            for _ in 0..4 {
                if stepper.step().is_err() {
                    break;
                }
            }
            state = *stepper.state();
            states.push(state);
        }
    }
    states
}

/// A deterministic spread of chain states: angles within ±0.6, momenta within ±1.
pub fn chain_samples<const S: usize>(links: usize) -> Vec<SVector<f64, S>> {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    let mut uniform = move |lo: f64, hi: f64| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        lo + (hi - lo) * ((seed >> 11) as f64 / (1u64 << 53) as f64)
    };
    (0..16)
        .map(|_| {
            SVector::<f64, S>::from_fn(|i, _| {
                if i < links {
                    uniform(-0.6, 0.6)
                } else {
                    uniform(-1.0, 1.0)
                }
            })
        })
        .collect()
}

/// The sum of the state rates at every sample (so no evaluation can be optimised away).
pub fn generated_rates<Sys, const N: usize, const S: usize>(
    system: &Sys,
    states: &[SVector<f64, S>],
) -> f64
where
    Sys: VariableMassSystem<N, S>,
{
    states
        .iter()
        .map(|s| {
            system
                .state_rate(0.5, black_box(s))
                .map_or(f64::NAN, |r| r.sum())
        })
        .sum()
}

pub fn interpreted_rates<const S: usize>(program: &Interpreted, states: &[SVector<f64, S>]) -> f64 {
    let mut out = [0.0; S];
    states
        .iter()
        .map(|s| {
            program.state_rate(0.5, black_box(s.as_slice()), &mut out);
            out.iter().sum::<f64>()
        })
        .sum()
}

/// The largest relative difference between the generated and the interpreted state rates.
pub fn disagreement<Sys, const N: usize, const S: usize>(
    system: &Sys,
    program: &Interpreted,
    states: &[SVector<f64, S>],
) -> f64
where
    Sys: VariableMassSystem<N, S>,
{
    let mut out = [0.0; S];
    let mut worst = 0.0f64;
    for s in states {
        program.state_rate(0.5, s.as_slice(), &mut out);
        let Ok(rate) = system.state_rate(0.5, s) else {
            return f64::NAN;
        };
        for (a, b) in rate.iter().zip(out) {
            worst = worst.max((a - b).abs() / (1.0 + a.abs()));
        }
    }
    worst
}

/// Nanoseconds of the fastest of interleaved runs of `a` and `b`, each run `repeat` calls.
pub fn pair(repeat: usize, a: impl FnMut() -> f64, b: impl FnMut() -> f64) -> (f64, f64) {
    pair_rounds(15, repeat, a, b)
}

/// [`pair`] over `rounds` rounds. Interleaving puts both under the same load and the
/// minimum discards the noise; the order alternates from round to round, so neither
/// workload always runs with the caches and the branch predictor left by the other.
pub fn pair_rounds(
    rounds: usize,
    repeat: usize,
    mut a: impl FnMut() -> f64,
    mut b: impl FnMut() -> f64,
) -> (f64, f64) {
    let mut best = (f64::INFINITY, f64::INFINITY);
    let time = |work: &mut dyn FnMut() -> f64| {
        let (t, _) = fastest_of(1, 1, Duration::ZERO, || {
            (0..repeat).map(|_| black_box(work())).sum::<f64>()
        });
        t.as_nanos() as f64 / repeat as f64
    };
    for round in 0..rounds {
        let (ta, tb) = if round % 2 == 0 {
            let ta = time(&mut a);
            (ta, time(&mut b))
        } else {
            let tb = time(&mut b);
            (time(&mut a), tb)
        };
        best.0 = best.0.min(ta);
        best.1 = best.1.min(tb);
    }
    best
}

/// Parameter names and values, as the interpreter takes them.
pub type ParameterValues = Vec<(&'static str, f64)>;

pub fn sled_parameters(s: &Sled) -> ParameterValues {
    vec![
        ("m0", s.m0),
        ("c", s.c),
        ("g", s.g),
        ("theta", s.theta),
        ("f_d", s.f_d),
    ]
}

pub fn rocket_parameters(r: &Rocket) -> ParameterValues {
    vec![("mu", r.mu), ("u_e", r.u_e), ("g", r.g)]
}

pub fn kepler_parameters(k: &Kepler) -> ParameterValues {
    vec![("m1", k.m1), ("k", k.k)]
}

pub const CHAIN_PARAMETERS: [(&str, f64); 4] = [("m0", 1.0), ("c", 0.1), ("l", 1.0), ("g", 9.81)];

pub fn chain<T>(build: impl Fn(f64, f64, f64, f64) -> T) -> T {
    let [(_, m0), (_, c), (_, l), (_, g)] = CHAIN_PARAMETERS;
    build(m0, c, l, g)
}

pub fn chain_parameters() -> Parameters {
    Parameters::Declared(
        CHAIN_PARAMETERS
            .iter()
            .map(|(n, _)| n.to_string())
            .collect(),
    )
}

/// The macro's pipeline on the n-link chain: parse, derive (with checks), emit.
pub fn expand(links: usize, source: &str) -> proc_macro2::TokenStream {
    expand_with(links, source, |_| {})
}

/// [`expand`], `change` applied to the derivation before it is emitted (the closed-form
/// q̇ of the symbolic-inverse threshold's other side, say).
pub fn expand_with(
    links: usize,
    source: &str,
    change: impl Fn(&mut Derivation),
) -> proc_macro2::TokenStream {
    let target = Target {
        name: Ident::new(&format!("Chain{links}"), Span::call_site()),
        runtime: quote!(::varmass::core),
    };
    match derive_source(source, chain_parameters()) {
        Ok(mut d) => {
            change(&mut d);
            emit_system(&mut d, source, &target)
        }
        Err(_) => proc_macro2::TokenStream::new(),
    }
}
