//! A small fixed set of derived systems evaluated at arbitrary times and states taken from
//! the fuzzer's bytes, along two paths:
//!
//! * the generated code (the `#[variable_mass_system]` expansion): every trait method must
//!   return without panicking, and a stepper started there must either take finite steps
//!   with positive masses or fail with a typed `StepError` that carries a finite time and
//!   the state;
//! * the derivation compiled to a tape (`ExprPool::compile`): no panic at any point.
//!
//! With `VARMASS_FUZZ_STRICT=1` the target also requires every trait method that returns
//! `Ok` at a finite state with positive masses to return finite values (the trait methods
//! have no typed error for overflow; this mode finds where they return `Ok(non-finite)`).
#![no_main]

use std::cell::RefCell;

use libfuzzer_sys::fuzz_target;
use varmass::core::steppers::{ImplicitMidpointConfig, VariationalConfig};
use varmass::prelude::*;
use varmass_symbolic::expr::Tape;
use varmass_symbolic::{derive, mechanics::{Derivation, Parameters, VelocitySolve}};
use varmass_symbolic::parse::{parse_system, select_tags};

// The systems are the repository's model files (paths relative to this crate, `fuzz/`),
// so the fuzzer exercises exactly what the examples, tests and command line tool run.

/// The paper's sled in body form (one coordinate, a mass law, an inflow).
#[variable_mass_system(file = "../models/sled.vms", with = ["impact"])]
struct Sled {
    m0: f64,
    c: f64,
    g: f64,
    theta: f64,
    f_d: f64,
}

/// A vertical rocket (a state mass and an outflow), without its optional drag.
#[variable_mass_system(file = "../models/rocket.vms")]
struct Rocket {
    mu: f64,
    u_e: f64,
    g: f64,
}

/// A leaking spring pendulum in polar form (two coordinates, closed-form inverse).
#[variable_mass_system(file = "../models/leaking_spring_pendulum.vms")]
struct Pendulum {
    mu: f64,
    u_e: f64,
    k: f64,
    l0: f64,
    g: f64,
}

/// A tank on a swinging arm (three coordinates: q̇ by an LDLᵀ solve).
#[variable_mass_system(file = "../models/swinging_tank.vms")]
#[allow(non_snake_case)] // the model's names: M0 and K read as in the physics
struct SwingingTank {
    mu: f64,
    M0: f64,
    J0: f64,
    l: f64,
    g: f64,
    K: f64,
    u_e: f64,
}

const SLED: Sled = Sled {
    m0: 10.0,
    c: 2.0,
    g: 9.81,
    theta: 0.5236,
    f_d: 0.1,
};
const ROCKET: Rocket = Rocket {
    mu: 0.05,
    u_e: 300.0,
    g: 9.81,
};
const PENDULUM: Pendulum = Pendulum {
    mu: 0.02,
    u_e: 3.0,
    k: 40.0,
    l0: 1.0,
    g: 9.81,
};
const TANK: SwingingTank = SwingingTank {
    mu: 0.1,
    M0: 5.0,
    J0: 0.3,
    l: 0.7,
    g: 9.81,
    K: 20.0,
    u_e: 12.0,
};

/// The fuzzer's bytes as numbers: raw `f64` bit patterns, small values, and special values
/// (0, ±∞, NaN, the extremes), so both ordinary and hostile states are reached.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    fn value(&mut self) -> f64 {
        const SPECIAL: [f64; 10] = [
            0.0,
            -0.0,
            1e-300,
            1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            f64::MAX,
            -1.0,
        ];
        match self.byte() % 4 {
            0 => f64::from_le_bytes(std::array::from_fn(|_| self.byte())),
            1 => f64::from(i16::from_le_bytes([self.byte(), self.byte()])) / 256.0,
            2 => SPECIAL[usize::from(self.byte()) % SPECIAL.len()],
            _ => f64::from(self.byte() as i8),
        }
    }
}

fn strict() -> bool {
    std::env::var_os("VARMASS_FUZZ_STRICT").is_some()
}

fn all_finite<const D: usize>(v: &SVector<f64, D>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// Every trait method at `(t, state)`: no panic; in strict mode, finite `Ok` values at a
/// finite state with positive masses.
fn evaluate_methods<Sys, const N: usize, const S: usize>(sys: &Sys, t: f64, state: &SVector<f64, S>)
where
    Sys: VariableMassSystem<N, S>,
{
    let rate = sys.state_rate(t, state);
    let hamiltonian = sys.hamiltonian(t, state);
    let power = sys.power(t, state);
    let jacobian = sys.jacobian(t, state);
    let accelerations = sys.accelerations(t, state);
    let canonical = sys.canonical_rates(t, state);
    let lagrangian = sys.lagrangian(t, state);
    let momenta = sys.momenta(t, state);
    for index in 0..Sys::MASSES.len() {
        let _ = (sys.mass(index, t, state), sys.mass_rate(index, t, state));
    }
    let admissible = t.is_finite() && all_finite(state) && sys.check_masses(t, state).is_ok();
    if strict() && admissible {
        let finite = |ok: bool, what: &str| {
            assert!(
                ok,
                "{what} is Ok but not finite at t = {t}, state = {state:?}"
            )
        };
        if let Ok(r) = rate {
            finite(all_finite(&r), "state_rate");
        }
        if let Ok(h) = hamiltonian {
            finite(h.is_finite(), "hamiltonian");
        }
        if let Ok(p) = power {
            finite(p.is_finite(), "power");
        }
        if let Ok(j) = jacobian {
            finite(j.iter().all(|x| x.is_finite()), "jacobian");
        }
        if let Ok(a) = accelerations {
            finite(all_finite(&a), "accelerations");
        }
        if let Ok((v, dp)) = canonical {
            finite(all_finite(&v) && all_finite(&dp), "canonical_rates");
        }
        finite(lagrangian.is_finite(), "lagrangian");
        finite(all_finite(&momenta), "momenta");
    }
}

/// Up to three steps of one stepper: each accepted state finite with positive masses, each
/// failure a typed error at a finite time (it carries the state by construction).
fn take_steps<Sys, St, const N: usize, const S: usize>(sys: &Sys, stepper: Result<St, StepError<S>>)
where
    Sys: VariableMassSystem<N, S>,
    St: Stepper<N, S>,
{
    // Construction fails with a typed error on a non-finite or massless start (checked by
    // the stepper): nothing more to see.
    let Ok(mut stepper) = stepper else { return };
    for _ in 0..3 {
        match stepper.step() {
            Ok(_) => {
                let (time, state) = (stepper.time(), *stepper.state());
                assert!(time.is_finite(), "a step was accepted at t = {time}");
                assert!(
                    all_finite(&state),
                    "a non-finite state was accepted: {state:?}"
                );
                assert!(
                    sys.check_masses(time, &state).is_ok(),
                    "a state with a non-positive mass was accepted: {state:?}"
                );
            }
            Err(error) => {
                assert!(
                    error.time.is_finite(),
                    "a step failed without a finite time: {error:?}"
                );
                return;
            }
        }
    }
}

fn exercise<Sys, const N: usize, const S: usize>(sys: &Sys, bytes: &mut Bytes)
where
    Sys: VariableMassSystem<N, S>,
{
    let t = bytes.value();
    let state = SVector::<f64, S>::from_fn(|_, _| bytes.value());
    evaluate_methods(sys, t, &state);
    let step = bytes.value();
    // Known and reported: a finite start time and a finite step whose sum overflows (t near
    // f64::MAX) give a typed error at t = inf. Times and steps beyond 1e300 are left out so
    // that the search goes on past it; non-finite ones are still tried.
    if [t, step].iter().any(|x| x.is_finite() && x.abs() > 1e300) {
        return;
    }
    match bytes.byte() % 5 {
        0 => take_steps(sys, ExplicitEuler::new(sys, t, state, FixedStep { step })),
        1 => take_steps(sys, ClassicalRk4::new(sys, t, state, FixedStep { step })),
        2 => take_steps(
            sys,
            DormandPrince::new(sys, t, state, StepControl::default()),
        ),
        3 => {
            let config = ImplicitMidpointConfig {
                step,
                ..Default::default()
            };
            take_steps(sys, ImplicitMidpoint::new(sys, t, state, config))
        }
        _ => {
            let config = VariationalConfig {
                step,
                ..Default::default()
            };
            take_steps(sys, Variational::new(sys, t, state, config))
        }
    }
}

/// One derivation's expressions compiled to a tape, with its scratch buffer.
struct Compiled {
    tape: Tape,
    symbols: usize,
    scratch: Vec<f64>,
}

/// The model `source` with the tags `with` selected, as the macro derives it.
fn compile((source, with): (&str, &[&str])) -> Compiled {
    let ast = parse_system(source).expect("a model file parses");
    let with: Vec<String> = with.iter().map(|tag| tag.to_string()).collect();
    let selected = select_tags(&ast, &with).expect("the model has its tags");
    let d: Derivation = derive(&selected, Parameters::Inferred).expect("a model file derives");
    let mut roots = vec![d.lagrangian, d.energy, d.power];
    roots.extend(d.hamiltonian);
    roots.extend(&d.momentum_rate);
    roots.extend(&d.mass_rates);
    roots.extend(&d.flow_rates);
    if let VelocitySolve::Symbolic(v) = &d.velocities {
        roots.extend(v);
    }
    roots.extend(d.accelerations.iter().flatten());
    // The Jacobian is derived unless `emit` leaves it out (derive derives it).
    if let Some(jacobian) = &d.jacobian {
        roots.extend(jacobian.rate_wrt_q.iter().flatten());
    }
    Compiled {
        tape: d.pool.compile(&roots),
        symbols: d.pool.symbols().len(),
        scratch: Vec::new(),
    }
}

thread_local! {
    static TAPES: RefCell<Vec<Compiled>> = RefCell::new(
        [
            (Sled::SOURCE, &["impact"][..]),
            (Rocket::SOURCE, &[]),
            (Pendulum::SOURCE, &[]),
            (SwingingTank::SOURCE, &[]),
        ]
            .into_iter()
            .map(compile)
            .collect(),
    );
}

fn evaluate_tape(index: usize, bytes: &mut Bytes) {
    TAPES.with(|tapes| {
        let mut tapes = tapes.borrow_mut();
        let compiled = &mut tapes[index];
        let env: Vec<f64> = (0..compiled.symbols).map(|_| bytes.value()).collect();
        let mut out = vec![0.0; compiled.tape.outputs()];
        compiled
            .tape
            .eval_with(&env, &mut compiled.scratch, &mut out);
    });
}

fuzz_target!(|data: &[u8]| {
    let mut bytes = Bytes(data);
    let choice = bytes.byte();
    let system = usize::from(choice % 4);
    if choice & 0x80 != 0 {
        evaluate_tape(system, &mut bytes);
        return;
    }
    match system {
        0 => exercise(&SLED, &mut bytes),
        1 => exercise(&ROCKET, &mut bytes),
        2 => exercise(&PENDULUM, &mut bytes),
        _ => exercise(&TANK, &mut bytes),
    }
});
