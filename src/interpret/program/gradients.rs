//! The derivatives of recorded quantities along the sensitivities (docs/sensitivities.md):
//! an expression X(t, q, q̇, m, θ) — a quantity's entry, a law mass — moved by a direction
//! (dt, dq, dq̇, dm_s, dθ) changes by
//!
//! ```text
//! dX = X_t dt + X_q·dq + X_q̇·dq̇ + X_m·dm_s + X_θ·dθ,
//! ```
//!
//! its gradient (`mechanics::gradient`: total derivatives with the mass laws followed)
//! compiled into one tape per expression, when a run asks for it. The switching functions'
//! gradients, which move a switch's time with the sensitivities
//! (`varmass_core::sensitivity`), are one tape compiled with the Jacobians.

use varmass_core::SystemError;
use varmass_symbolic::expr::Id;
use varmass_symbolic::mechanics::{gradient, Derivation};

use super::{Program, Stage};

/// A direction in [t, q, q̇, m_s, θ]: how a recorded point moves with one sensitivity
/// column.
#[derive(Clone, Debug, PartialEq)]
pub struct Direction {
    /// dt: 0 at a fixed output time, dτ/dw at an event's.
    pub time: f64,
    /// d[q, q̇, m_s] (a velocity state's length, held inputs and padding past it ignored).
    pub velocity_state: Vec<f64>,
    /// dθ, in [`Program::parameter_names`] order (e_j for parameter j, 0 for an initial
    /// entry).
    pub parameters: Vec<f64>,
}

impl Program {
    /// Compiles the gradient of `root` (an expression of the derivation's pool) for
    /// [`Program::derivative_along`], once.
    pub fn prepare_derivative(&mut self, root: Id) {
        if self.gradients.iter().any(|(r, _)| *r == root) {
            return;
        }
        let roots = gradient(&mut self.d, root);
        let tape = self.d.pool.compile(&roots);
        self.gradients.push((root, Stage { roots, tape }));
    }

    /// dX of `root` at the velocity state `(t, velocity_state)` along `direction`; `None`
    /// when its gradient was not prepared ([`Program::prepare_derivative`]).
    pub fn derivative_along(
        &self,
        root: Id,
        t: f64,
        velocity_state: &[f64],
        direction: &Direction,
    ) -> Option<Result<f64, SystemError>> {
        let (_, stage) = self.gradients.iter().find(|(r, _)| *r == root)?;
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_velocity_state(scratch, t, velocity_state);
        self.run(stage, scratch);
        if let Some(error) = scratch.outside.take() {
            return Some(Err(error));
        }
        let n = self.coordinate_count();
        let moved = 2 * n + self.state_mass_count();
        let components = std::iter::once(&direction.time)
            .chain(direction.velocity_state.iter().take(moved))
            .chain(&direction.parameters);
        let sum = (scratch.values.iter()).zip(components).map(|(g, d)| g * d);
        Some(Ok(sum.sum()))
    }
}

/// The gradients of the switching functions `roots`, one after the other, in one stage.
pub(super) fn switch_gradients(d: &mut Derivation, roots: &[Id]) -> Stage {
    let roots: Vec<Id> = (roots.iter()).flat_map(|&g| gradient(d, g)).collect();
    Stage {
        tape: d.pool.compile(&roots),
        roots,
    }
}

impl Program {
    /// Whether [`Program::switch_gradient`] gives the switches' gradients (a model derived
    /// with `Outputs::sensitivities`).
    pub fn has_switch_gradients(&self) -> bool {
        self.switch_gradients.is_some()
    }

    /// The gradient of switching function `index` at the velocity state
    /// `(t, velocity_state)`: [g_t, g_q, g_q̇, g_{m_s}, g_θ] (θ in
    /// [`Program::parameter_names`] order) into `out`. A switch at the knots of a table of
    /// the state gives its argument's (g = ±(argument − knot) near the knot). `Ok(false)`
    /// without the gradients or past the switches.
    pub fn switch_gradient(
        &self,
        index: usize,
        t: f64,
        velocity_state: &[f64],
        out: &mut [f64],
    ) -> Result<bool, SystemError> {
        let Some(stage) = &self.switch_gradients else {
            return Ok(false);
        };
        let width = stage.roots.len() / self.switch_count().max(1);
        if index >= self.switch_count() {
            return Ok(false);
        }
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_velocity_state(scratch, t, velocity_state);
        self.run(stage, scratch);
        if let Some(error) = scratch.outside.take() {
            return Err(error);
        }
        let values = &scratch.values[index * width..(index + 1) * width];
        out.iter_mut().zip(values).for_each(|(o, v)| *o = *v);
        Ok(true)
    }
}
