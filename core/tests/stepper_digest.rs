//! A digest of everything the steppers produce, for refactors that must not change a bit:
//! every accepted time and state, the dense output at three points of every step, the
//! statistics after every step, every error (kind, time, state) and the outcome of
//! restarts, over runs of every stepper on the four test problems at several tolerances
//! and settings (initial step, maximum step, PI weight, dense output off), with fixed
//! steps, restarts mid-run, the rocket's burn-out, Newton failures, step underflow and
//! refused configurations.
//!
//! The digest depends on the platform's floating point (libm, fused operations), so the
//! test is ignored; run it before and after a change that must be bit-identical and compare:
//!
//! ```text
//! cargo test -p varmass-core --test stepper_digest -- --ignored --nocapture
//! ```
//!
//! The value asserted is the one measured on x86_64 Linux.

mod support;

use std::fmt::Debug;

use nalgebra::SVector;
use support::problems::{KeplerProblem, OscillatorProblem, RocketProblem, SledProblem};
use support::Problem;
use varmass_core::steppers::{
    AdaptiveControl, ClassicalRk4, DirkNewton, Dop853, DormandPrince, Esdirk43, ExplicitEuler,
    FixedStep, ImplicitMidpoint, ImplicitMidpointConfig, Sdirk4, StepControl, Variational,
    VariationalConfig,
};
use varmass_core::{StepError, StepOutcome, Stepper};

/// The digest of the steppers' outputs. It was 0x994b3f834bfe64c1 before the step
/// controller moved to `steppers/control.rs`; commit 4496517 changed it to this value by
/// passing `Tolerance::new`'s own reason through an `InvalidConfiguration` error, whose
/// text the digest hashes (4496517~1 gives the old value, 4496517 this one: no step
/// changed). The shared `Controlled` state of Dormand–Prince and DOP853 left it unchanged.
/// The explicit Runge–Kutta core (`steppers/explicit.rs`) changed it to this value: it
/// accumulates Dormand–Prince's stage states onto y₀ term by term, y + kⱼ·(aⱼh), as DOP853
/// did, where they were summed first; the per-stepper digests printed with the test show
/// that only Dormand–Prince's four runs changed (every other stepper's bits equal), and its
/// errors against the closed forms of the four problems at tolerances 1e-4 … 1e-12 agree to
/// the seven digits printed, with the same steps and evaluations.
/// At 65b9e00 the digest was 0xeaeb0b2eed8bfdb6, no longer the 0x11b1_3033_7152_317a
/// written here before (a commit of that session moved it; not traced). Then the
/// variational stepper's momentum from the impulse, p₁ = p₀ + h(∂*L/∂q + F)(mid) (equal to
/// the old form at the Newton solution; it keeps (q₁ − q₀)/h's rounding out of p₁) changed
/// it to this value: the per-stepper digests printed with the test, compared with
/// 65b9e00's, differ in the variational stepper's four runs only.
const EXPECTED: u64 = 0x2657_b730_ba54_5921;

/// FNV-1a's offset basis.
const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// FNV-1a over the bits of everything fed to it.
struct Digest {
    hash: u64,
    runs: usize,
    steps: usize,
    /// The same bytes hashed by stepper type (and problem), to tell which changed.
    by_stepper: std::collections::BTreeMap<&'static str, u64>,
    current: u64,
}

impl Digest {
    fn bytes(&mut self, bytes: &[u8]) {
        for byte in bytes {
            self.hash ^= u64::from(*byte);
            self.hash = self.hash.wrapping_mul(0x0100_0000_01b3);
            self.current ^= u64::from(*byte);
            self.current = self.current.wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn number(&mut self, x: f64) {
        self.bytes(&x.to_bits().to_le_bytes());
    }
    fn vector<const S: usize>(&mut self, v: &SVector<f64, S>) {
        v.iter().for_each(|x| self.number(*x));
    }
    fn debug(&mut self, value: &impl Debug) {
        self.bytes(format!("{value:?}").as_bytes());
    }
}

/// Steps `stepper` (or the error that refused it) to `stop`, restarting once at the first
/// accepted time past `restart_at` from the state scaled by 1.001.
fn drive<St, const N: usize, const S: usize>(
    digest: &mut Digest,
    stepper: Result<St, StepError<S>>,
    stop: f64,
    restart_at: Option<f64>,
) where
    St: Stepper<N, S>,
{
    let name = std::any::type_name::<St>();
    digest.current = digest.by_stepper.get(name).copied().unwrap_or(OFFSET);
    drive_one(digest, stepper, stop, restart_at);
    digest.by_stepper.insert(name, digest.current);
}

/// [`drive`]'s run.
fn drive_one<St, const N: usize, const S: usize>(
    digest: &mut Digest,
    stepper: Result<St, StepError<S>>,
    stop: f64,
    restart_at: Option<f64>,
) where
    St: Stepper<N, S>,
{
    digest.runs += 1;
    let mut stepper = match stepper {
        Ok(stepper) => stepper,
        Err(error) => return digest.debug(&error),
    };
    if let Err(error) = stepper.set_stop_time(stop) {
        return digest.debug(&error);
    }
    let mut restart_at = restart_at;
    for _ in 0..20_000 {
        match stepper.step() {
            Ok(outcome) => {
                digest.steps += 1;
                let progress = stepper.progress();
                let (t0, t1) = (progress.previous_time(), progress.time());
                digest.number(t1);
                digest.vector(progress.state());
                for theta in [0.25, 0.5, 0.9] {
                    match stepper.dense_output(t0 + theta * (t1 - t0)) {
                        Some(y) => digest.vector(&y),
                        None => digest.bytes(b"none"),
                    }
                }
                digest.debug(stepper.statistics());
                if restart_at.is_some_and(|at| t1 >= at) {
                    restart_at = None;
                    let state = stepper.state() * 1.001;
                    digest.debug(&stepper.restart(t1, state));
                }
                if outcome == StepOutcome::ReachedStopTime {
                    break;
                }
            }
            Err(error) => {
                digest.debug(&error);
                break;
            }
        }
    }
    digest.debug(stepper.statistics());
}

fn adaptive(base: AdaptiveControl, tolerance: f64) -> [StepControl; 4] {
    let at = |control: AdaptiveControl| {
        StepControl::Adaptive(AdaptiveControl {
            relative_tolerance: tolerance,
            absolute_tolerance: tolerance * 1e-3,
            ..control
        })
    };
    [
        at(base),
        at(AdaptiveControl {
            initial_step: Some(0.1),
            ..base
        }),
        at(AdaptiveControl {
            max_step: 0.05,
            ..base
        }),
        at(AdaptiveControl {
            beta: if base.beta == 0.0 { 0.04 } else { 0.0 },
            ..base
        }),
    ]
}

/// Every stepper on `problem` to `stop`.
fn every_stepper<P, const N: usize, const S: usize>(digest: &mut Digest, problem: &P, stop: f64)
where
    P: Problem<N, S>,
{
    let system = problem.system();
    let y0 = problem.initial_state();
    let restart = Some(0.4 * stop);
    for tolerance in [1e-3, 1e-6, 1e-9, 1e-12] {
        for control in adaptive(AdaptiveControl::default(), tolerance) {
            let dp = DormandPrince::new(system, 0.0, y0, control);
            drive(digest, dp, stop, restart);
        }
        for control in adaptive(AdaptiveControl::dop853(), tolerance) {
            drive(digest, Dop853::new(system, 0.0, y0, control), stop, restart);
            let sparse = Dop853::new(system, 0.0, y0, control).map(Dop853::without_dense_output);
            drive(digest, sparse, stop, None);
        }
        for control in adaptive(AdaptiveControl::sdirk4(), tolerance) {
            drive(digest, Sdirk4::new(system, 0.0, y0, control), stop, restart);
            drive(
                digest,
                Esdirk43::new(system, 0.0, y0, control),
                stop,
                restart,
            );
        }
    }
    for steps in [40.0, 400.0] {
        let fixed = FixedStep { step: stop / steps };
        let control = StepControl::Fixed(fixed);
        drive(
            digest,
            DormandPrince::new(system, 0.0, y0, control),
            stop,
            restart,
        );
        drive(digest, Dop853::new(system, 0.0, y0, control), stop, restart);
        drive(digest, Sdirk4::new(system, 0.0, y0, control), stop, restart);
        drive(
            digest,
            Esdirk43::new(system, 0.0, y0, control),
            stop,
            restart,
        );
        drive(
            digest,
            ExplicitEuler::new(system, 0.0, y0, fixed),
            stop,
            restart,
        );
        drive(
            digest,
            ClassicalRk4::new(system, 0.0, y0, fixed),
            stop,
            restart,
        );
        let midpoint = ImplicitMidpointConfig {
            step: fixed.step,
            ..Default::default()
        };
        drive(
            digest,
            ImplicitMidpoint::new(system, 0.0, y0, midpoint),
            stop,
            restart,
        );
        let variational = VariationalConfig {
            step: fixed.step,
            ..Default::default()
        };
        drive(
            digest,
            Variational::new(system, 0.0, y0, variational),
            stop,
            restart,
        );
    }
    failures(digest, problem, stop);
}

/// Newton failures, step underflow far from t = 0, and refused settings.
fn failures<P, const N: usize, const S: usize>(digest: &mut Digest, problem: &P, stop: f64)
where
    P: Problem<N, S>,
{
    let system = problem.system();
    let y0 = problem.initial_state();
    let long = StepControl::Fixed(FixedStep { step: 0.5 * stop });
    let two = DirkNewton {
        max_iterations: 2,
        ..DirkNewton::default()
    };
    let sdirk = Sdirk4::new(system, 0.0, y0, long).and_then(|s| s.with_newton(two));
    drive(digest, sdirk, stop, None);
    let esdirk = Esdirk43::new(system, 0.0, y0, long).and_then(|s| s.with_newton(two));
    drive(digest, esdirk, stop, None);
    let far = 1e20;
    let tiny = |base| {
        StepControl::Adaptive(AdaptiveControl {
            initial_step: Some(1e-3),
            ..base
        })
    };
    let dp = DormandPrince::new(system, far, y0, tiny(AdaptiveControl::default()));
    drive(digest, dp, far + 1e6, None);
    let dop = Dop853::new(system, far, y0, tiny(AdaptiveControl::dop853()));
    drive(digest, dop, far + 1e6, None);
    let sdirk = Sdirk4::new(system, far, y0, tiny(AdaptiveControl::sdirk4()));
    drive(digest, sdirk, far + 1e6, None);
    let refused = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: -1.0,
        ..AdaptiveControl::default()
    });
    drive(
        digest,
        DormandPrince::new(system, 0.0, y0, refused),
        stop,
        None,
    );
    drive(digest, Dop853::new(system, 0.0, y0, refused), stop, None);
    drive(digest, Sdirk4::new(system, 0.0, y0, refused), stop, None);
    let zero = StepControl::Fixed(FixedStep { step: 0.0 });
    drive(digest, Dop853::new(system, 0.0, y0, zero), stop, None);
    drive(digest, Esdirk43::new(system, 0.0, y0, zero), stop, None);
}

#[test]
#[ignore = "platform-dependent digest: run by hand around a refactor (see the module docs)"]
fn stepper_outputs_are_unchanged() {
    let mut digest = Digest {
        hash: OFFSET,
        runs: 0,
        steps: 0,
        by_stepper: std::collections::BTreeMap::new(),
        current: OFFSET,
    };
    let oscillator = OscillatorProblem::standard();
    every_stepper(&mut digest, &oscillator, oscillator.end_time());
    let kepler = KeplerProblem::standard();
    every_stepper(&mut digest, &kepler, kepler.end_time());
    let sled = SledProblem::standard();
    every_stepper(&mut digest, &sled, sled.end_time());
    // Past burn-out at t = 20: every stepper ends in a typed error (or rejects into it).
    let rocket = RocketProblem::standard();
    every_stepper(&mut digest, &rocket, 25.0);
    let (hash, runs, steps) = (digest.hash, digest.runs, digest.steps);
    eprintln!("digest {hash:#018x} over {runs} runs, {steps} accepted steps");
    for (name, hash) in &digest.by_stepper {
        eprintln!("{hash:#018x} {name}");
    }
    assert_eq!(hash, EXPECTED, "{hash:#018x}");
}
