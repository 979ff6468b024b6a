//! Levenberg–Marquardt for bounded weighted least squares (Moré 1978, "The Levenberg–
//! Marquardt algorithm: implementation and theory", with Marquardt's diagonal scaling):
//! minimise ½‖r(θ)‖² over lo ≤ θ ≤ hi, r already divided by each datum's σ, J = ∂r/∂θ
//! from the run's sensitivities. Each iteration solves
//!
//! ```text
//! (JᵀJ + λ D) δ = −Jᵀ r,     D = diag(JᵀJ) (floored),
//! ```
//!
//! clamps θ + δ into the bounds, and takes the step if it lowers the cost (λ ÷ 3), else
//! grows λ (× 4) and tries again. It stops when the relative change of the cost and of θ
//! fall below `tolerance`, when the gradient vanishes, or after `max_iterations`; a stop of
//! the first kind is converged where the undamped step from θ is short too (else the steps
//! shrank against runs that fail, short of the minimum).
//!
//! Weighed: the `levenberg-marquardt` crate (a port of MINPACK's lmder) is well kept, but
//! its release depends on nalgebra 0.34 beside the workspace's 0.35 (two nalgebras in the
//! tree, types converted through slices); its loop is also the one above without bounds.
//! This one is 100 lines on the workspace's nalgebra.

use varmass::core::nalgebra::{DMatrix, DVector};

/// What [`minimize`] evaluates at θ: the weighted residuals r and their Jacobian J
/// (rows: residuals, columns: θ), or why it could not.
pub type Evaluation = Result<(DVector<f64>, DMatrix<f64>), String>;

/// Settings of [`minimize`].
#[derive(Clone, Copy, Debug)]
pub struct Settings {
    /// The relative change of the cost and of θ below which it has converged.
    pub tolerance: f64,
    /// The most iterations (each one evaluation that is accepted or rejected).
    pub max_iterations: usize,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 100,
        }
    }
}

/// The outcome of [`minimize`].
#[derive(Clone, Debug)]
pub struct Minimum {
    /// θ at the minimum.
    pub theta: DVector<f64>,
    /// r there.
    pub residuals: DVector<f64>,
    /// J there.
    pub jacobian: DMatrix<f64>,
    /// Evaluations made.
    pub evaluations: usize,
    /// Whether it converged (else it ran out of iterations).
    pub converged: bool,
}

/// ½‖r‖².
fn cost(r: &DVector<f64>) -> f64 {
    0.5 * r.norm_squared()
}

/// Minimises ½‖r(θ)‖² from `start` within `[lo, hi]` (per parameter, ±∞ for none).
pub fn minimize(
    mut evaluate: impl FnMut(&DVector<f64>) -> Evaluation,
    start: DVector<f64>,
    (lo, hi): (&DVector<f64>, &DVector<f64>),
    settings: Settings,
) -> Result<Minimum, String> {
    let clamp = |theta: DVector<f64>| theta.zip_zip_map(lo, hi, |x, l, h| x.max(l).min(h));
    let mut theta = clamp(start);
    let (mut r, mut j) = evaluate(&theta)?;
    let mut evaluations = 1;
    let mut lambda = 1e-3;
    while evaluations < settings.max_iterations {
        let jt = j.transpose();
        let (normal, gradient) = (&jt * &j, &jt * &r);
        if gradient.amax() == 0.0 {
            return Ok(done(theta, r, j, evaluations, true));
        }
        let Some(step) = damped_step(&normal, &gradient, lambda, &theta, (lo, hi)) else {
            lambda *= 4.0;
            evaluations += 1;
            continue;
        };
        let trial = clamp(&theta + &step);
        evaluations += 1;
        let moved = (&trial - &theta).norm() / theta.norm().max(1e-300);
        let Ok((tr, tj)) = evaluate(&trial) else {
            // A trial the model cannot run (a mass ≤ 0): a shorter step.
            lambda *= 4.0;
            continue;
        };
        let (before, after) = (cost(&r), cost(&tr));
        if after < before {
            let drop = (before - after) / before.max(1e-300);
            (theta, r, j) = (trial, tr, tj);
            lambda = (lambda / 3.0).max(1e-12);
            if drop < settings.tolerance && moved < settings.tolerance.sqrt() {
                let converged = stationary(&j, &r, &theta, (lo, hi), settings.tolerance);
                return Ok(done(theta, r, j, evaluations, converged));
            }
        } else {
            if moved < settings.tolerance {
                let converged = stationary(&j, &r, &theta, (lo, hi), settings.tolerance);
                return Ok(done(theta, r, j, evaluations, converged));
            }
            lambda *= 4.0;
        }
    }
    Ok(done(theta, r, j, evaluations, false))
}

/// Whether θ, where the steps stopped shrinking the cost, is a minimum: the undamped
/// Gauss–Newton step from it (bounds held as in [`damped_step`]) moves θ by at most
/// √`tolerance` relative. Steps that shrink against runs that fail (a trial the model
/// cannot run) stop short of a minimum, where the Gauss–Newton step is still long: that
/// stop was reported converged. A singular JᵀJ confirms nothing and denies nothing (as
/// before).
fn stationary(
    j: &DMatrix<f64>,
    r: &DVector<f64>,
    theta: &DVector<f64>,
    (lo, hi): (&DVector<f64>, &DVector<f64>),
    tolerance: f64,
) -> bool {
    let jt = j.transpose();
    match damped_step(&(&jt * j), &(&jt * r), 0.0, theta, (lo, hi)) {
        Some(step) => step.norm() <= tolerance.sqrt() * theta.norm().max(1e-300),
        None => true,
    }
}

/// The damped Gauss–Newton step, (JᵀJ + λ D) δ = −Jᵀ r, with the unknowns that sit at a
/// bound and would step out of it held there (their rows and columns removed): projecting a
/// step computed with them free would spoil the others' part of it (Rosenbrock's valley
/// bounded by θ₁ ≤ ½ stopped at θ₂ = 0.2507 instead of 0.25). `None` if the system is
/// singular.
fn damped_step(
    normal: &DMatrix<f64>,
    gradient: &DVector<f64>,
    lambda: f64,
    theta: &DVector<f64>,
    (lo, hi): (&DVector<f64>, &DVector<f64>),
) -> Option<DVector<f64>> {
    let floor = 1e-12 * normal.diagonal().amax();
    let solve = |held: &[bool]| {
        let mut damped = normal.clone();
        let mut rhs = -gradient;
        for i in 0..theta.len() {
            damped[(i, i)] += lambda * normal[(i, i)].max(floor);
            if held[i] {
                damped.row_mut(i).fill(0.0);
                damped.column_mut(i).fill(0.0);
                damped[(i, i)] = 1.0;
                rhs[i] = 0.0;
            }
        }
        damped.cholesky().map(|c| c.solve(&rhs))
    };
    let free = solve(&vec![false; theta.len()])?;
    let held: Vec<bool> = (0..theta.len())
        .map(|i| (theta[i] <= lo[i] && free[i] < 0.0) || (theta[i] >= hi[i] && free[i] > 0.0))
        .collect();
    match held.iter().any(|h| *h) {
        true => solve(&held),
        false => Some(free),
    }
}

fn done(
    theta: DVector<f64>,
    residuals: DVector<f64>,
    jacobian: DMatrix<f64>,
    evaluations: usize,
    converged: bool,
) -> Minimum {
    Minimum {
        theta,
        residuals,
        jacobian,
        evaluations,
        converged,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock's valley as residuals r = (10 (θ₂ − θ₁²), 1 − θ₁), minimum (1, 1) with
    /// r = 0: found from (−1.2, 1) to 1e-9; with the bound θ₁ ≤ 0.5 the constrained
    /// minimum lies on the bound, θ₁ = 0.5, θ₂ = 0.25 (r₁ = 0 there, r₂ fixed by θ₁).
    #[test]
    fn rosenbrock_is_minimised_with_and_without_a_bound() {
        let evaluate = |t: &DVector<f64>| -> Evaluation {
            let r = DVector::from_vec(vec![10.0 * (t[1] - t[0] * t[0]), 1.0 - t[0]]);
            let j = DMatrix::from_row_slice(2, 2, &[-20.0 * t[0], 10.0, -1.0, 0.0]);
            Ok((r, j))
        };
        let free = (
            &DVector::from_element(2, f64::NEG_INFINITY),
            &DVector::from_element(2, f64::INFINITY),
        );
        let start = DVector::from_vec(vec![-1.2, 1.0]);
        let m = minimize(evaluate, start.clone(), free, Settings::default()).unwrap();
        assert!(m.converged);
        assert!(
            (m.theta[0] - 1.0).abs() < 1e-9 && (m.theta[1] - 1.0).abs() < 1e-9,
            "{}",
            m.theta
        );
        let hi = DVector::from_vec(vec![0.5, f64::INFINITY]);
        let bounded = (free.0, &hi);
        let m = minimize(evaluate, start, bounded, Settings::default()).unwrap();
        assert!((m.theta[0] - 0.5).abs() < 1e-12, "{}", m.theta);
        assert!((m.theta[1] - 0.25).abs() < 1e-8, "{}", m.theta);
    }

    /// r = θ − 2 with θ = 2 out of the model's reach: every run with θ > 1 fails. The
    /// steps shrink against θ = 1 and stop there: not converged (it was reported converged
    /// at the edge, r = −1, before this test). With the failures past θ = 3 the minimum is
    /// reached and converged.
    #[test]
    fn a_stop_against_failing_runs_is_no_convergence() {
        let edge = |limit: f64| {
            move |t: &DVector<f64>| -> Evaluation {
                match t[0] > limit {
                    true => Err("the run failed".to_string()),
                    false => Ok((t.add_scalar(-2.0), DMatrix::identity(1, 1))),
                }
            }
        };
        let free = (
            &DVector::from_element(1, f64::NEG_INFINITY),
            &DVector::from_element(1, f64::INFINITY),
        );
        let start = DVector::from_vec(vec![0.0]);
        let m = minimize(edge(1.0), start.clone(), free, Settings::default()).unwrap();
        assert!(!m.converged, "{} after {}", m.theta, m.evaluations);
        assert!((m.theta[0] - 1.0).abs() < 1e-6, "{}", m.theta);
        let m = minimize(edge(3.0), start, free, Settings::default()).unwrap();
        assert!(
            m.converged && (m.theta[0] - 2.0).abs() < 1e-12,
            "{}",
            m.theta
        );
    }
}
