//! Forward sensitivities of a held body and of one on a rail
//! (docs/sensitivities.md#on-a-pad-and-a-rail): the columns s = ∂y/∂w of a
//! [`Sensitive`](crate::sensitivity::Sensitive) system, which the support wraps, move as
//! the constrained motion does.
//!
//! Each constraint's state rate is a fixed linear projection P of the free one, f_c = P f:
//! a held coordinate's rows of q_k and p_k set to 0 (uncoupled, checked at every
//! evaluation), a rail's bottom every row of q and p set to 0, and a rail whose direction b
//! does not couple with the other coordinates (M b = μ b, [`SystemError::RailCoupled`]
//! otherwise) the rows of q and of p each projected on b, q̇ = b bᵀ q̇_free and
//! ṗ = b bᵀ ṗ_free (the momentum p = μ b ṡ stays along b, and bᵀ Q_c = 0). So the columns'
//! rate is P (J s + ∂f/∂w), the free columns' rate projected block by block.
//!
//! At the phase's end the columns jump by (f⁻ − f⁺) dτ/dw (`sensitivity/phases.rs`), with
//! f⁻ the constrained rate: the departure the free system gives (with its own f) gains
//! (f_c − f) dτ/dw, in the velocity state (q̈_c − q̈) dτ/dw; an arrival into a constrained
//! phase (f⁺ constrained) gains (f − f_c) dτ/dw. A lift-off is smooth (the rates agree
//! there: the net force along the support is 0 and the body at rest along it), and a rail's
//! exit moves with its travel, g = dᵀ(r − r₀) − L. A switch crossed while constrained
//! whose rate jumps is refused ([`SystemError::SupportedSwitch`]): its time would need the
//! constrained accelerations; one whose rate only kinks jumps nothing.

use nalgebra::SVector;

use super::Supported;
use crate::departure::{Departure, PhaseEnd};
use crate::rail::Rail;
use crate::system::{SystemError, VariableMassSystem};

/// How far M b may stray from along b, relative to the largest diagonal entry of M, before
/// a rail with sensitivities is refused (as [`super::HELD_COUPLING`] for a hold).
const RAIL_COUPLING: f64 = 1e-12;

/// How far a column's velocity ∂q̇/∂w may stray from along the rail, relative to its
/// largest entry, before the rail is refused (rounding leaves far less where the columns
/// stay along it) …
const COLUMN_ACROSS: f64 = 1e-9;

/// … beyond an absolute floor in the velocity's units per the column's (m/s per unit of
/// w): a column that does not move the body along the rail (an attitude's start value, an
/// inertia, a drag area of the held phase) has a velocity of rounding alone, 1e-16 … 1e-15
/// on models/rocket_on_rail.toml, which the relative test alone refused (the review of this
/// change).
const COLUMN_ACROSS_FLOOR: f64 = 1e-10;

impl<Sys> Supported<Sys> {
    /// Whether the body is held or on a rail (its rates constrained).
    pub(super) fn constrained(&self) -> bool {
        self.held.is_some() || self.rail.is_some()
    }

    /// Whether the body rests on a support or on the rail's bottom, where a lift-off ends
    /// the phase smoothly.
    fn resting(&self) -> bool {
        self.held.is_some() || self.rail.is_some_and(|rail| rail.on_pad)
    }

    /// The constraint's projection P of one block `[q, p, m_s]` (the state's or a column's).
    fn project<const N: usize>(&self, block: &mut [f64]) {
        if let Some(k) = self.held.filter(|&k| k < N) {
            block[k] = 0.0;
            block[N + k] = 0.0;
        }
        let Some(rail) = &self.rail else { return };
        if rail.on_pad {
            block[..2 * N].fill(0.0);
            return;
        }
        let b = rail.along::<N>();
        for rows in [0, N] {
            let along: f64 = (0..N).map(|i| b[i] * block[rows + i]).sum();
            (0..N).for_each(|i| block[rows + i] = b[i] * along);
        }
    }

    /// The columns' blocks of the rate `rate` (each after the first block of
    /// [`VariableMassSystem::measured_block`] entries) projected, while constrained; the
    /// mechanics' block is the constraint's own business. With `check`, sliding on a rail,
    /// each column's free rate's q rows — its velocity ∂q̇/∂w — must lie along the rail
    /// first ([`SystemError::RailColumnAcross`], [`Self::check_rail_coupling`]).
    pub(super) fn project_columns<const N: usize, const S: usize>(
        &self,
        rate: &mut SVector<f64, S>,
        check: bool,
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let block = self.system.measured_block();
        if !self.constrained() || !self.system.has_rate_only_state() || block >= S {
            return Ok(());
        }
        let sliding = self.rail.filter(|rail| check && !rail.on_pad);
        for (column, chunk) in rate.as_mut_slice()[block..]
            .chunks_exact_mut(block)
            .enumerate()
        {
            if let Some(rail) = &sliding {
                across::<N>(&rail.along::<N>(), &chunk[..N], column)?;
            }
            self.project::<N>(chunk);
        }
        Ok(())
    }

    /// [`SystemError::RailCoupled`] for a body with sensitivities on a rail (its bottom or
    /// sliding) whose direction couples with other coordinates at `(t, state)`; the columns'
    /// velocities ∂q̇/∂w, which must stay along it while it slides, are checked where the
    /// rate has them ([`Self::project_columns`]).
    ///
    /// The projection of the momentum rows on b is exact only while the columns' momenta
    /// keep no part across b, which holds exactly when their velocities stay along b (q̇ =
    /// b ṡ for every value of w, and M⁻¹ keeps the parts across b apart where M b = μ b). A
    /// momentum at rest that grows across b as the body slides (a turning launch frame), or
    /// a coupling that is 0 at the nominal values only (m l θ̇ ż at l = 0, ∂/∂l), shows as a
    /// column's velocity across b and is refused, at the first rate it appears in
    /// ([`SystemError::RailColumnAcross`]; the review of this change measured 1–14 % and 2.8
    /// wrong, silently, before).
    pub(super) fn check_rail_coupling<const N: usize, const S: usize>(
        &self,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let Some(rail) = self.rail.filter(|_| self.system.has_rate_only_state()) else {
            return Ok(());
        };
        let m = self.system.mass_matrix(t, state);
        let b = rail.along::<N>();
        let mb = m * b;
        let scale = (0..N).map(|i| m[(i, i)].abs()).fold(0.0, f64::max);
        if (mb - b * b.dot(&mb)).amax() > RAIL_COUPLING * scale {
            return Err(SystemError::RailCoupled);
        }
        Ok(())
    }

    /// The end `end` as the free system takes it: a rail's travel as its gradient (into
    /// `gradient`), a lift-off from a resting body as smooth; `None` where this system
    /// cannot end so.
    pub(super) fn resolved_end<'a>(
        &self,
        end: &PhaseEnd<'a>,
        gradient: &'a mut [(usize, f64); 3],
    ) -> Option<PhaseEnd<'a>> {
        match *end {
            PhaseEnd::RailTravel => {
                let rail: &Rail = self.rail.as_ref()?;
                for (g, (&i, d)) in gradient
                    .iter_mut()
                    .zip(rail.position.iter().zip(rail.direction))
                {
                    *g = (i, d);
                }
                Some(PhaseEnd::Linear(&gradient[..]))
            }
            PhaseEnd::Smooth => self.resting().then_some(PhaseEnd::Linear(&[])),
            PhaseEnd::Linear(gradient) => Some(PhaseEnd::Linear(gradient)),
            // A velocity held or guided by the constraint: not followed there.
            PhaseEnd::Velocity { .. } => (!self.constrained()).then_some(*end),
        }
    }

    /// The free system's `departure` at `(t, state)`, an end whose event has the linear
    /// `gradient`, made the constrained motion's. The free system took dτ/dw = −g·s / g·f
    /// and moved each column by f dτ/dw (in the velocity state by ẋ dτ/dw); the constrained
    /// motion's time moves by dτ_c/dw = dτ/dw · (g·f)/(g·f_c) (g·f_c ≠ g·f for an event on
    /// a momentum while sliding), and its columns by f_c dτ_c/dw (ẋ_c: q̈_c in the q̇ rows).
    pub(super) fn constrain_departure<const N: usize, const S: usize>(
        &self,
        (t, state): (f64, &SVector<f64, S>),
        gradient: &[(usize, f64)],
        departure: &mut Departure,
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if !self.constrained() || departure.time.iter().all(|&dt| dt == 0.0) {
            return Ok(());
        }
        let free = self.system.state_rate(t, state)?;
        let constrained = self.constrained_rate(t, state, false)?;
        let along = |f: &SVector<f64, S>| gradient.iter().map(|&(i, c)| c * f[i]).sum::<f64>();
        let ratio = along(&free) / along(&constrained);
        if !ratio.is_finite() || ratio == 0.0 {
            let entry = gradient.first().map_or(0, |g| g.0);
            return Err(SystemError::TangentPhaseEnd { entry });
        }
        let velocity_state = self.system.velocity_state(t, state)?;
        // ẋ = [q̇, q̈, ṁ_s], free and constrained: the state rate's q and m rows, q̈ between.
        let (mut free_motion, mut motion) = (free, constrained);
        let accelerations = self.system.accelerations(t, &velocity_state)?;
        free_motion.fixed_rows_mut::<N>(N).copy_from(&accelerations);
        let accelerations = self.constrained_accelerations(t, &velocity_state)?;
        motion.fixed_rows_mut::<N>(N).copy_from(&accelerations);
        let e = departure.entries;
        for (c, dt) in departure.time.iter_mut().enumerate() {
            let moved = &mut departure.state[c * e..(c + 1) * e];
            for (i, s) in moved.iter_mut().enumerate() {
                *s += constrained[i] * *dt * ratio - free[i] * *dt;
            }
            let moved = &mut departure.velocity_state[c * e..(c + 1) * e];
            for (i, s) in moved.iter_mut().enumerate() {
                *s += motion[i] * *dt * ratio - free_motion[i] * *dt;
            }
            *dt *= ratio;
        }
        Ok(())
    }

    /// The columns the free system entered into `state` at `t` made the constrained
    /// motion's: each gains (f − f_c) dτ/dw.
    pub(super) fn constrain_arrival<const N: usize, const S: usize>(
        &self,
        t: f64,
        state: &mut SVector<f64, S>,
        departure: &Departure,
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if !self.constrained() || departure.time.iter().all(|&dt| dt == 0.0) {
            return Ok(());
        }
        // The constrained rate without the checks of `state_rate`: the columns are half
        // entered here, not yet a state to check.
        let rate = self.system.state_rate(t, state)? - self.constrained_rate(t, state, false)?;
        let e = departure.entries;
        for (c, &dt) in departure.time.iter().enumerate() {
            let start = e * (1 + c);
            for i in 0..e {
                state[start + i] += rate[i] * dt;
            }
        }
        Ok(())
    }

    /// A crossing of `crossed` while constrained, with sensitivities: nothing jumps where
    /// the constrained rate only kinks (to 10⁻⁸, as `sensitivity/switches.rs` takes it);
    /// a jump is refused ([`SystemError::SupportedSwitch`]).
    pub(super) fn constrained_crossing<const N: usize, const S: usize>(
        &self,
        crossed: &[usize],
        before: &SVector<f64, S>,
        (t, after): (f64, &SVector<f64, S>),
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let block = self.system.measured_block().min(S);
        let rate_after = self.state_rate(t, after)?;
        let (before, after) = (&before.as_slice()[..block], &rate_after.as_slice()[..block]);
        let largest = |v: &[f64]| v.iter().fold(0.0, |m: f64, x| m.max(x.abs()));
        let jump = before
            .iter()
            .zip(after)
            .fold(0.0, |m: f64, (a, b)| m.max((a - b).abs()));
        match jump <= 1e-8 * largest(before).max(largest(after)) {
            true => Ok(()),
            false => Err(SystemError::SupportedSwitch {
                switch: crossed.first().copied().unwrap_or(0),
            }),
        }
    }
}

/// [`SystemError::RailColumnAcross`] for column `column` whose velocity ∂q̇/∂w `velocity`
/// (its free rate's q rows) leaves the rail's direction `b`.
fn across<const N: usize>(
    b: &SVector<f64, N>,
    velocity: &[f64],
    column: usize,
) -> Result<(), SystemError> {
    let along: f64 = (0..N).map(|i| b[i] * velocity[i]).sum();
    let off = (0..N).fold(0.0_f64, |m, i| m.max((velocity[i] - b[i] * along).abs()));
    let size = velocity.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    match off > COLUMN_ACROSS * size + COLUMN_ACROSS_FLOOR {
        true => Err(SystemError::RailColumnAcross { column }),
        false => Ok(()),
    }
}
