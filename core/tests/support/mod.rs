//! Hand-written systems for the tests, each paired with its reference solution, and a
//! harness that runs any stepper on any of them.
#![allow(dead_code)] // each test binary uses part of the support

pub mod closed_forms;
pub mod problems;
pub mod systems;
pub mod taylor;

use nalgebra::SVector;
use varmass_core::steppers::{
    ClassicalRk4, DormandPrince, ExplicitEuler, FixedStep, ImplicitMidpoint,
    ImplicitMidpointConfig, Principle, StepControl, Taylor, TaylorControl, Variational,
    VariationalConfig,
};
use varmass_core::{StepError, StepOutcome, Stepper, VariableMassSystem};

/// A test problem: a system, an initial value, an end time, and a measure of the error of
/// a numerical state against the reference solution (zero on the exact solution).
pub trait Problem<const N: usize, const S: usize> {
    /// The system.
    type System: VariableMassSystem<N, S>;
    /// For messages.
    const NAME: &'static str;
    fn system(&self) -> &Self::System;
    fn initial_state(&self) -> SVector<f64, S>;
    fn end_time(&self) -> f64;
    /// The error of `state` at `time` against the reference.
    fn error(&self, time: f64, state: &SVector<f64, S>) -> f64;
}

/// Every stepper, by name, so one harness can run each on each problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Euler,
    Rk4,
    DormandPrinceFixed,
    ImplicitMidpoint,
    Variational,
    VariationalLiteralEq19,
    /// Taylor's method of this fixed order (systems that provide Taylor coefficients).
    Taylor(usize),
}

impl Method {
    pub const ALL: [Method; 5] = [
        Method::Euler,
        Method::Rk4,
        Method::DormandPrinceFixed,
        Method::ImplicitMidpoint,
        Method::Variational,
    ];
}

/// Steps `stepper` to `end_time` and returns the final time and state.
pub fn integrate<St, const N: usize, const S: usize>(
    mut stepper: St,
    end_time: f64,
) -> Result<(f64, SVector<f64, S>), StepError<S>>
where
    St: Stepper<N, S>,
{
    stepper.set_stop_time(end_time)?;
    while stepper.step()? != StepOutcome::ReachedStopTime {}
    Ok((stepper.time(), *stepper.state()))
}

/// Integrates `problem` with `method` in `steps` equal steps and returns the final time
/// and state.
pub fn solve<P, const N: usize, const S: usize>(
    problem: &P,
    method: Method,
    steps: usize,
) -> Result<(f64, SVector<f64, S>), StepError<S>>
where
    P: Problem<N, S>,
{
    let system = problem.system();
    let y0 = problem.initial_state();
    let end = problem.end_time();
    let step = end / steps as f64;
    let fixed = FixedStep { step };
    match method {
        Method::Euler => integrate(ExplicitEuler::new(system, 0.0, y0, fixed)?, end),
        Method::Rk4 => integrate(ClassicalRk4::new(system, 0.0, y0, fixed)?, end),
        Method::DormandPrinceFixed => integrate(
            DormandPrince::new(system, 0.0, y0, StepControl::Fixed(fixed))?,
            end,
        ),
        Method::ImplicitMidpoint => integrate(
            ImplicitMidpoint::new(
                system,
                0.0,
                y0,
                ImplicitMidpointConfig {
                    step,
                    ..Default::default()
                },
            )?,
            end,
        ),
        Method::Taylor(order) => integrate(
            Taylor::new(system, 0.0, y0, TaylorControl::Fixed { order, step })?,
            end,
        ),
        Method::Variational | Method::VariationalLiteralEq19 => integrate(
            Variational::new(
                system,
                0.0,
                y0,
                VariationalConfig {
                    step,
                    principle: if method == Method::Variational {
                        Principle::Corrected
                    } else {
                        Principle::LiteralEq19
                    },
                    ..Default::default()
                },
            )?,
            end,
        ),
    }
}

/// The error at the end of the problem's interval with `steps` equal steps.
pub fn final_error<P, const N: usize, const S: usize>(
    problem: &P,
    method: Method,
    steps: usize,
) -> f64
where
    P: Problem<N, S>,
{
    match solve(problem, method, steps) {
        Ok((time, state)) => problem.error(time, &state),
        Err(error) => panic!("{} with {method:?}, {steps} steps: {error}", P::NAME),
    }
}

/// Observed orders of convergence from step halving: log₂(e(n)/e(2n)) for n, 2n, 4n, … .
pub fn observed_orders<P, const N: usize, const S: usize>(
    problem: &P,
    method: Method,
    coarsest_steps: usize,
    halvings: usize,
) -> Vec<f64>
where
    P: Problem<N, S>,
{
    let errors: Vec<f64> = (0..=halvings)
        .map(|k| final_error(problem, method, coarsest_steps << k))
        .collect();
    errors
        .windows(2)
        .map(|pair| (pair[0] / pair[1]).log2())
        .collect()
}
