//! DOP853 at fixed steps on a problem, beside `ode_solvers`' Dop853 (written independently
//! from the same paper) at the same steps: the final errors and the orders observed between
//! successive step counts. Where the two agree digit for digit, an observed order away from
//! 8 is the method's on that problem (not yet asymptotic, or at the rounding floor), not a
//! defect of ours.

use std::fmt::Write as _;

use varmass::core::nalgebra::SVector;
use varmass::core::steppers::{Dop853, FixedStep, StepControl};

use crate::common::problems::Problem;
use crate::{integrate, PeerSystem};

/// Step counts from 40 in factors of √2 (rounded).
const STEPS: [usize; 9] = [40, 57, 80, 113, 160, 226, 320, 453, 640];

/// Our DOP853 in `steps` equal steps: the final error.
fn ours<P: Problem<N, S>, const N: usize, const S: usize>(problem: &P, steps: usize) -> f64 {
    let (y0, end) = (problem.initial_state(), problem.end_time());
    let control = StepControl::Fixed(FixedStep {
        step: end / steps as f64,
    });
    match Dop853::new(problem.system(), 0.0, y0, control).map(|s| integrate(s, end)) {
        Ok(Ok((time, state, _))) => problem.error(time, &state),
        _ => f64::NAN,
    }
}

/// The peer in `steps` equal steps: its first and largest step set to the step, and
/// tolerances so loose that every step is accepted.
fn peer<P: Problem<N, S>, const N: usize, const S: usize>(problem: &P, steps: usize) -> f64 {
    let end = problem.end_time();
    let step = end / steps as f64;
    let y0 = ode_solvers::SVector::<f64, S>::from_column_slice(problem.initial_state().as_slice());
    let system = PeerSystem::<P::System, N, S>(problem.system());
    let (loose, sparse) = (1e3, ode_solvers::OutputType::Sparse);
    let mut solver = ode_solvers::Dop853::from_param(
        system,
        0.0,
        end,
        end,
        y0,
        loose,
        loose,
        0.9,
        0.0,
        1.0 / 3.0,
        6.0,
        step,
        step,
        10_000_000,
        1000,
        sparse,
    );
    match (
        solver.integrate(),
        solver.x_out().last(),
        solver.y_out().last(),
    ) {
        (Ok(stats), Some(&time), Some(y)) if stats.accepted_steps as usize == steps => {
            problem.error(time, &SVector::from_column_slice(y.as_slice()))
        }
        _ => f64::NAN,
    }
}

/// The table: steps, both errors, both observed orders from the previous row.
pub fn table<P: Problem<N, S>, const N: usize, const S: usize>(problem: &P) -> String {
    let mut out = format!(
        "DOP853 at fixed steps on {}: ours and ode_solvers' Dop853\n{:>6} {:>12} {:>12} {:>7} {:>7}\n",
        P::NAME,
        "steps",
        "ours",
        "peer",
        "order",
        "peer's"
    );
    let mut previous: Option<(usize, f64, f64)> = None;
    for steps in STEPS {
        let (error, peer_error) = (ours(problem, steps), peer(problem, steps));
        let order = |a: f64, b: f64, n: usize| (a / b).ln() / (steps as f64 / n as f64).ln();
        let (o, p) = previous.map_or((String::new(), String::new()), |(n, a, b)| {
            (
                format!("{:.2}", order(a, error, n)),
                format!("{:.2}", order(b, peer_error, n)),
            )
        });
        let _ = writeln!(
            out,
            "{steps:>6} {error:>12.4e} {peer_error:>12.4e} {o:>7} {p:>7}"
        );
        previous = Some((steps, error, peer_error));
    }
    out
}
