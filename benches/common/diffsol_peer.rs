//! The stiff peer: `diffsol` (pure Rust, nalgebra containers) on the same generated state
//! rate and generated Jacobian as ours. diffsol asks for Jacobian–vector products
//! J(y)·v; they are products with [`VariableMassSystem::jacobian`], evaluated once per
//! state (diffsol builds its matrix from several products at one state). Its BDF (variable
//! order, NDF, as Matlab's ode15s) and its ESDIRK34 (Jørgensen, Kristensen & Thomsen 2018,
//! L-stable, order 3 with a fourth-order embedded solution) are the two stiff methods run.

use std::cell::{Cell, RefCell};

use diffsol::{NalgebraLU, NalgebraMat, OdeBuilder, OdeSolverMethod, OdeSolverStopReason};
use diffsol::{OdeEquationsImplicit, OdeSolverProblem, Vector};
use varmass::core::Statistics;
use varmass::prelude::*;

/// A stiff method of diffsol.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiffsolMethod {
    /// Variable-order BDF (NDF formulas).
    Bdf,
    /// ESDIRK34: four stages, order 3, L-stable.
    Esdirk34,
}

/// The work of one run, counted in the closures diffsol calls.
#[derive(Default)]
struct Counts {
    rates: Cell<usize>,
    jacobians: Cell<usize>,
}

/// The generated Jacobian at the last state asked for, so that diffsol's products at one
/// state cost one evaluation.
type JacobianCache<const S: usize> = RefCell<Option<(f64, SVector<f64, S>, SMatrix<f64, S, S>)>>;

/// J(t, y) from the cache or the system (NaN where the system fails, which makes
/// diffsol reject the step).
fn jacobian_at<Sys, const N: usize, const S: usize>(
    system: &Sys,
    cache: &JacobianCache<S>,
    counts: &Counts,
    (t, y): (f64, SVector<f64, S>),
) -> SMatrix<f64, S, S>
where
    Sys: VariableMassSystem<N, S>,
{
    if let Some((time, state, jacobian)) = *cache.borrow() {
        if time == t && state == y {
            return jacobian;
        }
    }
    counts.jacobians.set(counts.jacobians.get() + 1);
    let jacobian = system
        .jacobian(t, &y)
        .unwrap_or(SMatrix::from_element(f64::NAN));
    *cache.borrow_mut() = Some((t, y, jacobian));
    jacobian
}

/// Runs diffsol's `method` at tolerance `tolerance` (relative and absolute) from `y0` at
/// t = 0 to `end`; returns what our runs return: the end time and state, and statistics
/// (steps, rejected steps, Newton iterations from diffsol; rate and Jacobian evaluations
/// counted here).
pub fn run_diffsol<Sys, const N: usize, const S: usize>(
    system: &Sys,
    (y0, end): (SVector<f64, S>, f64),
    method: DiffsolMethod,
    tolerance: f64,
) -> Result<(f64, SVector<f64, S>, Statistics), String>
where
    Sys: VariableMassSystem<N, S>,
{
    let counts = Counts::default();
    let cache: JacobianCache<S> = RefCell::new(None);
    let rhs = |x: &[f64], _p: &[f64], t: f64, y: &mut [f64]| {
        counts.rates.set(counts.rates.get() + 1);
        let state = SVector::<f64, S>::from_column_slice(x);
        let rate = system
            .state_rate(t, &state)
            .unwrap_or(SVector::from_element(f64::NAN));
        y.copy_from_slice(rate.as_slice());
    };
    let product = |x: &[f64], _p: &[f64], t: f64, v: &[f64], y: &mut [f64]| {
        let state = SVector::<f64, S>::from_column_slice(x);
        let jacobian = jacobian_at(system, &cache, &counts, (t, state));
        let product = jacobian * SVector::<f64, S>::from_column_slice(v);
        y.copy_from_slice(product.as_slice());
    };
    let problem = OdeBuilder::<NalgebraMat<f64>>::new()
        .rtol(tolerance)
        .atol([tolerance])
        .rhs_implicit(rhs, product)
        .init(|_p, _t, y| y.copy_from_slice(y0.as_slice()), S)
        .build()
        .map_err(|e| e.to_string())?;
    let (time, state, mut statistics) = match method {
        DiffsolMethod::Bdf => {
            let solver = problem.bdf::<NalgebraLU<f64>>();
            drive::<_, S, _>(&problem, solver.map_err(|e| e.to_string())?, end)?
        }
        DiffsolMethod::Esdirk34 => {
            let solver = problem.esdirk34::<NalgebraLU<f64>>();
            drive::<_, S, _>(&problem, solver.map_err(|e| e.to_string())?, end)?
        }
    };
    statistics.rate_evaluations = counts.rates.get();
    statistics.jacobian_evaluations = counts.jacobians.get();
    Ok((time, state, statistics))
}

/// Steps `solver` to `end` and reads its state and statistics.
fn drive<'a, Eqn, const S: usize, Solver>(
    _problem: &'a OdeSolverProblem<Eqn>,
    mut solver: Solver,
    end: f64,
) -> Result<(f64, SVector<f64, S>, Statistics), String>
where
    Eqn: OdeEquationsImplicit<T = f64> + 'a,
    Solver: OdeSolverMethod<'a, Eqn>,
{
    solver.set_stop_time(end).map_err(|e| e.to_string())?;
    while !matches!(
        solver.step().map_err(|e| e.to_string())?,
        OdeSolverStopReason::TstopReached
    ) {}
    let state = solver.state();
    let y = SVector::<f64, S>::from_fn(|i, _| state.y.get_index(i));
    let work = solver.get_statistics();
    let statistics = Statistics {
        accepted_steps: work.number_of_steps,
        rejected_steps: work.number_of_error_test_failures,
        newton_iterations: work.number_of_nonlinear_solver_iterations,
        ..Statistics::default()
    };
    Ok((state.t, y, statistics))
}
