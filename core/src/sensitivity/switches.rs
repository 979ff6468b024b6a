//! Forward sensitivities across the switches of a system's equations
//! (docs/sensitivities.md#switches): `sign`, `abs`, `min`, `max` and the knots of a table of
//! the state, where the state rate jumps or kinks at a time τ that moves with the columns.
//!
//! g(τ(w), y(τ(w); w), w) = 0 differentiated along a column w gives the time's derivative
//!
//! ```text
//! dτ/dw = −(g_y · s + g_w) / ġ,      ġ = g_t + g_y · f⁻,
//! ```
//!
//! with g_y · s read in the velocity state, g_q · s_q + g_q̇ · ∂q̇/∂w + g_m · s_m (∂q̇/∂w from
//! [`Sensitive::velocity_sensitivities`], q̈ from the accelerations before the switch). The
//! state is continuous across the switch but its rate is not: y(τ + δ) before and after
//! differ by (f⁻ − f⁺) δ to first order, so each column jumps by
//!
//! ```text
//! s⁺ = s⁻ + (f⁻ − f⁺) dτ/dw.
//! ```
//!
//! A kink (`abs`, a table's knot where only the slope changes) has f⁻ = f⁺: nothing jumps.

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::SVector;

use super::{column, head, Sensitive};
use crate::system::{SystemError, VariableMassSystem};

impl<Sys, const S: usize> Sensitive<Sys, S> {
    /// The columns of `after` (the far end of the crossing of `crossed`) jumped by
    /// (f⁻ − f⁺) dτ/dw, f⁻ the rate `before` gives (on the side the run comes from), f⁺ the
    /// rate at `after`. At a kink (f⁻ = f⁺ to 10⁻⁸: `abs`, `min`, `max`, a linear table's
    /// knot) nothing jumps whatever dτ/dw, so a tangent crossing or two switches crossing
    /// together there are no error.
    pub(super) fn jump_at_switches<const N: usize, const SA: usize>(
        &self,
        crossed: &[usize],
        before: (f64, &SVector<f64, SA>, &SVector<f64, SA>),
        (t, after): (f64, &mut SVector<f64, SA>),
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let rate_before = head::<S, SA>(before.2);
        let rate_after = self.system.state_rate(t, &head::<S, SA>(after))?;
        let jump = rate_before - rate_after;
        let scale = rate_before.amax().max(rate_after.amax());
        let times = match self.switch_times::<N, SA>(crossed, before) {
            Err(SystemError::TangentSwitch { .. } | SystemError::SwitchesTogether { .. })
                if jump.amax() <= 1e-8 * scale =>
            {
                return Ok(());
            }
            times => times?,
        };
        for (c, dt) in times.iter().enumerate() {
            let mut rows = after.fixed_rows_mut::<S>(S * (1 + c));
            rows += jump * *dt;
        }
        Ok(())
    }

    /// dτ/dw of the crossing of `crossed` for each column, at the point `before` (time,
    /// augmented state, augmented rate) on the side the run comes from. Switches crossed
    /// together must move together (a switch named twice): else which comes first depends
    /// on the column's sign, [`SystemError::SwitchesTogether`].
    fn switch_times<const N: usize, const SA: usize>(
        &self,
        crossed: &[usize],
        (t, state, rate): (f64, &SVector<f64, SA>, &SVector<f64, SA>),
    ) -> Result<Vec<f64>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let velocity_state = self.system.velocity_state(t, &head::<S, SA>(state))?;
        let motion = Motion {
            velocity_state,
            accelerations: self.system.accelerations(t, &velocity_state)?,
            rate: head::<S, SA>(rate),
        };
        let velocities = self.velocity_sensitivities::<N, SA>(t, state)?;
        let mut gradient = vec![0.0; 1 + S + self.system.parameter_names().len()];
        let mut times: Option<(usize, Vec<f64>)> = None;
        for &switch in crossed {
            if !(self.system).switch_gradient(switch, t, &velocity_state, &mut gradient)? {
                return Err(SystemError::NoSwitchGradient { switch });
            }
            let along = motion.along(&gradient);
            if along == 0.0 || !along.is_finite() {
                return Err(SystemError::TangentSwitch { switch });
            }
            let moved = (0..self.columns()).map(|c| {
                let s = column::<S, SA>(state, c);
                let mut dg = velocity_dot::<N, S>(&gradient[1..], &s, &velocities[c]);
                if let Some(j) = self.columns[c].parameter() {
                    dg += gradient[1 + S + j];
                }
                -dg / along
            });
            let moved: Vec<f64> = moved.collect();
            match &times {
                None => times = Some((switch, moved)),
                Some((first, kept)) if !together(kept, &moved) => {
                    let (first, second) = (*first, switch);
                    return Err(SystemError::SwitchesTogether { first, second });
                }
                Some(_) => {}
            }
        }
        Ok(times.map(|(_, times)| times).unwrap_or_default())
    }
}

/// The motion before a switch, in the velocity state.
struct Motion<const N: usize, const S: usize> {
    velocity_state: SVector<f64, S>,
    accelerations: SVector<f64, N>,
    /// The state rate [q̇, ṗ, ṁ_s].
    rate: SVector<f64, S>,
}

impl<const N: usize, const S: usize> Motion<N, S> {
    /// ġ = g_t + g_q · q̇ + g_q̇ · q̈ + g_m · ṁ_s for `gradient` = [g_t, g_q, g_q̇, g_m, …].
    fn along(&self, gradient: &[f64]) -> f64 {
        let mut d = SVector::<f64, S>::zeros();
        d.fixed_rows_mut::<N>(0)
            .copy_from(&self.velocity_state.fixed_rows::<N>(N));
        d.fixed_rows_mut::<N>(N).copy_from(&self.accelerations);
        for k in 2 * N..S {
            d[k] = self.rate[k];
        }
        gradient[0]
            + (gradient[1..=S].iter().zip(&d))
                .map(|(g, d)| g * d)
                .sum::<f64>()
    }
}

/// g_y · s in the velocity state: g_q · s_q + g_q̇ · ∂q̇/∂w + g_m · s_m, `gradient` =
/// [g_q, g_q̇, g_m, …] and `s` a column of [q, p, m_s].
fn velocity_dot<const N: usize, const S: usize>(
    gradient: &[f64],
    s: &SVector<f64, S>,
    velocities: &SVector<f64, N>,
) -> f64 {
    let mut d = *s;
    d.fixed_rows_mut::<N>(N).copy_from(velocities);
    (gradient[..S].iter().zip(&d)).map(|(g, d)| g * d).sum()
}

/// Whether two switches' times move together with every column (to 1e-9 of the larger).
fn together(a: &[f64], b: &[f64]) -> bool {
    (a.iter().zip(b)).all(|(a, b)| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()))
}
