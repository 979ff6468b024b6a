//! Forward sensitivities across a phase change (docs/sensitivities.md#in-a-run-of-phases-a-two-stage-rocket): a phase of
//! system A ends at τ where state entry i crosses a fixed value (a burn-out, an apogee), and
//! system B's phase begins with the motion carried by a rule (`phases.rs`): a separation
//! keeps q and q̇ and recomputes p through B's momentum map; a capture keeps q and p; either
//! may set state masses to constants (a new stage's propellant).
//!
//! The change's time moves with each column w: g = Σ cᵢ yᵢ − value (a state entry, a
//! state mass, a rail's travel) differentiated along the motion gives
//! dτ/dw = −Σ cᵢ sᵢ / Σ cᵢ fᵢ (f = A's state rate). A lift-off, where the rates on both
//! sides agree, carries the columns unchanged (dτ/dw taken 0, `PhaseEnd::Smooth`). The state at the change, followed
//! along the motion, moves by d y(τ)/dw = s + f dτ/dw; in the velocity state x = [q, q̇, m_s]
//! by d x(τ)/dw = σ + ẋ dτ/dw, with σ = ∂x/∂w (q̇'s rows from
//! [`Sensitive::velocity_sensitivities`]) and ẋ = [q̇, q̈, ṁ_s] (A's accelerations).
//!
//! After the change B's state at a fixed time t > τ is y_B(t) = y_B(τ) + ẏ_B (t − τ), so
//! its column is d y_B(τ)/dw − ẏ_B dτ/dw. For a capture y_B(τ) = R y(τ) (R zeroes the
//! entries the phase sets), hence
//!
//! ```text
//! s⁺ = R (s⁻ + f_A dτ/dw) − f_B dτ/dw.
//! ```
//!
//! For a separation y_B(τ) = P_B(τ, R x(τ), θ), whose explicit time derivative cancels
//! against ẏ_B = ∂P_B/∂t + P_B,x ẋ_B, leaving
//!
//! ```text
//! s⁺ = P_B,x u + P_B,θ,    u = R (σ⁻ + ẋ_A dτ/dw) − ẋ_B dτ/dw,
//! ```
//!
//! read through B's velocity map q̇ = V(y, θ), whose derivatives B's Jacobians give:
//! s⁺_q = u_q, s⁺_m = u_m and s⁺_p = M_B (u_q̇ − V_q u_q − V_m u_m − V_θ).

use alloc::vec::Vec;

use nalgebra::SVector;

use super::{column, head, Resolved, Sensitive};
use crate::departure::{Departure, PhaseEnd};
use crate::system::{SystemError, VariableMassSystem};

impl<Sys, const S: usize> Sensitive<Sys, S> {
    /// What the columns carry out of a phase ending at `(t, state)` on `end`
    /// ([`VariableMassSystem::depart`]): where Σ cᵢ yᵢ crosses a fixed value
    /// ([`PhaseEnd::Linear`], the `(i, cᵢ)`; empty: dτ/dw = 0, a fixed time or a smooth
    /// end), or where coordinate k's velocity does ([`PhaseEnd::Velocity`]: dτ/dw =
    /// −(∂q̇_k/∂w)/q̈_k, ∂q̇_k/∂w the column's q̇ row of σ).
    pub(super) fn departure<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
        end: PhaseEnd<'_>,
    ) -> Result<Departure, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let y = head::<S, SA>(state);
        let rate = self.system.state_rate(t, &y)?;
        let motion = self.velocity_rate::<N>(t, &y, &rate)?;
        let velocities = self.velocity_sensitivities::<N, SA>(t, state)?;
        let moves = Moves::of::<N, S>(end, &rate, &motion)?;
        let mut departure = Departure {
            entries: S,
            initial: self.initial_entries(),
            ..Departure::default()
        };
        for (c, velocity) in velocities.iter().enumerate() {
            let s = column::<S, SA>(state, c);
            let dt = moves.time(&s, velocity);
            let mut sigma = s;
            sigma.fixed_rows_mut::<N>(N).copy_from(velocity);
            departure.time.push(dt);
            departure.state.extend((s + rate * dt).iter());
            departure
                .velocity_state
                .extend((sigma + motion * dt).iter());
        }
        Ok(departure)
    }

    /// The columns entering a phase of this system at `(t, state)` from `departure`
    /// ([`VariableMassSystem::arrive`]): a capture's (`keep_momenta`) or a separation's.
    pub(super) fn arrival<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &mut SVector<f64, SA>,
        departure: &Departure,
        keep_momenta: bool,
        reset: &[usize],
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let complete = departure.initial.len() == departure.columns();
        if departure.columns() != self.columns() || departure.entries != S || !complete {
            let (before, after) = (departure.columns(), self.columns());
            return Err(SystemError::PhaseColumns { before, after });
        }
        let initial = self.initial_entries();
        if let Some(column) = (0..initial.len()).find(|&c| initial[c] != departure.initial[c]) {
            return Err(SystemError::PhaseColumnDiffers { column });
        }
        let y = head::<S, SA>(state);
        let rate = self.system.state_rate(t, &y)?;
        let entered = match keep_momenta {
            true => self.captured(departure, &rate, reset),
            false => self.separated::<N, SA>(t, state, departure, &rate, reset)?,
        };
        for (c, column) in entered.iter().enumerate() {
            state.fixed_rows_mut::<S>(S * (1 + c)).copy_from(column);
        }
        Ok(())
    }

    /// s⁺ = R (s⁻ + f_A dτ/dw) − f_B dτ/dw for each column (`rate` = f_B).
    fn captured(
        &self,
        departure: &Departure,
        rate: &SVector<f64, S>,
        reset: &[usize],
    ) -> Vec<SVector<f64, S>> {
        let columns = departure.state.chunks_exact(S).zip(&departure.time);
        let entered = columns.map(|(moved, dt)| {
            let mut u = SVector::<f64, S>::from_column_slice(moved);
            reset_entries(&mut u, reset);
            u - rate * *dt
        });
        entered.collect()
    }

    /// s⁺ = P_B,x u + P_B,θ for each column, u = R (σ⁻ + ẋ_A dτ/dw) − ẋ_B dτ/dw, through
    /// B's velocity map at the entered state (the module's comment).
    fn separated<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
        departure: &Departure,
        rate: &SVector<f64, S>,
        reset: &[usize],
    ) -> Result<Vec<SVector<f64, S>>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let y = head::<S, SA>(state);
        let motion = self.velocity_rate::<N>(t, &y, rate)?;
        let mass = self.system.mass_matrix(t, &y);
        let (jacobian, scratch) = self.jacobians::<N, SA>(t, state)?;
        let velocity_rows = jacobian.fixed_rows::<N>(0);
        let columns = departure
            .velocity_state
            .chunks_exact(S)
            .zip(&departure.time);
        let entered = columns.enumerate().map(|(c, (moved, dt))| {
            let mut u = SVector::<f64, S>::from_column_slice(moved);
            reset_entries(&mut u, reset);
            u -= motion * *dt;
            // V_q u_q + V_m u_m + V_θ: the velocity map's change at a fixed p.
            let mut fixed_momenta = u;
            fixed_momenta.fixed_rows_mut::<N>(N).fill(0.0);
            let mut moved_velocity: SVector<f64, N> = velocity_rows * fixed_momenta;
            self.add_parameter(c, &scratch, moved_velocity.iter_mut());
            let velocity = u.fixed_rows::<N>(N).into_owned();
            let mut entered = u;
            entered
                .fixed_rows_mut::<N>(N)
                .copy_from(&(mass * (velocity - moved_velocity)));
            entered
        });
        Ok(entered.collect())
    }

    /// For each column, its initial entry if it is one's.
    fn initial_entries(&self) -> Vec<Option<usize>> {
        let initial = |c: &Resolved| match *c {
            Resolved::Initial(i) => Some(i),
            Resolved::Parameter(_) | Resolved::Elsewhere => None,
        };
        self.columns.iter().map(initial).collect()
    }

    /// ẋ = [q̇, q̈, ṁ_s], the velocity state's rate at the state `y` whose rate is `rate`.
    fn velocity_rate<const N: usize>(
        &self,
        t: f64,
        y: &SVector<f64, S>,
        rate: &SVector<f64, S>,
    ) -> Result<SVector<f64, S>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let velocity_state = self.system.velocity_state(t, y)?;
        let mut motion = *rate;
        motion
            .fixed_rows_mut::<N>(0)
            .copy_from(&velocity_state.fixed_rows::<N>(N));
        let accelerations = self.system.accelerations(t, &velocity_state)?;
        motion.fixed_rows_mut::<N>(N).copy_from(&accelerations);
        Ok(motion)
    }
}

/// The entries a phase sets to constants do not move with any column.
fn reset_entries<const S: usize>(u: &mut SVector<f64, S>, reset: &[usize]) {
    for &i in reset {
        if i < S {
            u[i] = 0.0;
        }
    }
}

/// How the change's time moves with a column: g's gradient and its rate along the motion.
enum Moves<'a> {
    /// g = Σ cᵢ yᵢ − value, `along` = Σ cᵢ fᵢ (no coefficient: dτ/dw = 0).
    Linear(&'a [(usize, f64)], f64),
    /// g = q̇_k − value, `along` = q̈_k.
    Velocity(usize, f64),
}

impl<'a> Moves<'a> {
    /// The end `end` with its rate along the motion: the state's `rate` and the velocity
    /// state's `motion` ([q̇, q̈, ṁ_s]); an end the motion only touches (its rate 0) has no
    /// derivative.
    fn of<const N: usize, const S: usize>(
        end: PhaseEnd<'a>,
        rate: &SVector<f64, S>,
        motion: &SVector<f64, S>,
    ) -> Result<Self, SystemError> {
        let touched = |along: f64| along == 0.0 || !along.is_finite();
        match end {
            PhaseEnd::Velocity { coordinate } => {
                let along = motion.get(N + coordinate).copied().unwrap_or(f64::NAN);
                match touched(along) {
                    true => Err(SystemError::TangentVelocityEnd { coordinate }),
                    false => Ok(Self::Velocity(coordinate, along)),
                }
            }
            PhaseEnd::Linear(gradient) => {
                let along = gradient.iter().map(|&(i, c)| c * rate[i]).sum::<f64>();
                match !gradient.is_empty() && touched(along) {
                    true => Err(SystemError::TangentPhaseEnd {
                        entry: gradient[0].0,
                    }),
                    false => Ok(Self::Linear(gradient, along)),
                }
            }
            // A support resolves these before a free system sees them (`support.rs`).
            PhaseEnd::Smooth | PhaseEnd::RailTravel => Ok(Self::Linear(&[], 0.0)),
        }
    }

    /// dτ/dw of the column `s` whose velocity rows are `velocity` (∂q̇/∂w).
    fn time<const S: usize, const N: usize>(
        &self,
        s: &SVector<f64, S>,
        velocity: &SVector<f64, N>,
    ) -> f64 {
        match *self {
            Self::Linear([], _) => 0.0,
            Self::Linear(gradient, along) => {
                -gradient.iter().map(|&(i, c)| c * s[i]).sum::<f64>() / along
            }
            Self::Velocity(k, along) => -velocity[k] / along,
        }
    }
}
