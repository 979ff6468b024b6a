//! A support that holds until lifted (docs/mechanics.md#a-support-that-holds-until-lifted):
//! a body resting on its pad (or a rail's end) along one coordinate q_k, held there until
//! the net generalized force along the support would lift it.
//!
//! While held the constraint q_k = const, q̇_k = 0 acts through a constraint force N along
//! q_k alone (its gradient is the unit vector e_k), N = −ṗ_k^free ≥ 0, where ṗ_k^free is the
//! momentum rate the free equations give at the held state: the held state rate is the
//! free one with the rows of q_k and p_k set to 0. Everything else runs as in the free
//! system: the other coordinates, and the masses (a motor burns on its pad). The support
//! is unilateral: it pushes, never pulls, so the body lifts off where N would turn
//! negative, i.e. where ṗ_k^free changes sign from ≤ 0 to > 0 — an event of the held phase
//! ([`EventCondition::LiftOff`]), located on the dense output like any other. After it the
//! support is gone (the body does not land on it again): the run goes on in the free system
//! with the state unchanged (q̇_k = 0 there, so nothing jumps).
//!
//! The hold is a phase: [`phases`] returns the held phase, ended by the lift-off, and the
//! free one, both of the one wrapper type [`Supported`] (so one stepper closure builds
//! both), to run with [`run_phases`](crate::phases::run_phases); [`lift_off_time`] reads the
//! lift-off time from the result. A body whose free ṗ_k is already ≥ 0 at the start lifts
//! at once: [`phases`] then returns the free phase alone.

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::{SMatrix, SVector};

use crate::error::{StepError, StepErrorKind};
use crate::events::{Direction, Event, EventAction, EventCondition};
use crate::phases::{Carry, Phase, PhasedSolution};
use crate::rail::Rail;
use crate::system::{SystemError, VariableMassSystem};

mod columns;

/// The error of a support on an index past the coordinates.
pub const NO_SUCH_COORDINATE: &str = "a support names a coordinate the system does not have";

/// The error of a body that does not start at rest along its support (q̇_k ≠ 0).
pub const NOT_AT_REST: &str =
    "a body held on its support must start at rest along it (its velocity there is not 0)";

/// The error of a supported coordinate that couples with another in the kinetic energy
/// (M_kj ≠ 0 for some j ≠ k, or a momentum p_k(q, 0, t) ≠ 0 at rest): holding q̇_k = 0 would
/// not keep p_k fixed, and the hold as a clamp of p_k would be wrong.
pub const COUPLED: &str = "a supported coordinate must not couple with the others in the \
     kinetic energy (M_kj = 0 for j ≠ k, and p_k = 0 at rest)";

/// A system whose coordinate `held` (if any) rests on its support: its state rate is the
/// free one with the rows of q_k and p_k set to 0. With `held: None` it is the free system
/// itself (every method delegated), so that the held phase and the free phases after it
/// are one type.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Supported<Sys> {
    /// The free system.
    pub system: Sys,
    /// The coordinate held on its support, `None` once lifted.
    pub held: Option<usize>,
    /// The launch rail the body is on, if any ([`crate::rail`]): every coordinate but the
    /// position held, the position sliding along the rail (or resting on its bottom).
    pub rail: Option<Rail>,
}

impl<Sys> Supported<Sys> {
    /// The free system, as a phase after the lift-off (or any phase without a support).
    pub fn free(system: Sys) -> Self {
        Self {
            system,
            held: None,
            rail: None,
        }
    }

    /// `system` with coordinate `k` held on its support.
    pub fn held(system: Sys, k: usize) -> Self {
        Self {
            system,
            held: Some(k),
            rail: None,
        }
    }

    /// `system` on the launch rail `rail` ([`crate::rail`]).
    pub fn on_rail(system: Sys, rail: Rail) -> Self {
        Self {
            system,
            held: None,
            rail: Some(rail),
        }
    }

    /// The free system once lifted (nothing held, no rail), `None` while held.
    fn lifted(&self) -> Option<&Sys> {
        (self.held.is_none() && self.rail.is_none()).then_some(&self.system)
    }

    /// The constrained rate (the columns' projected as the state's); without `check`, none
    /// of the checks of [`VariableMassSystem::state_rate`] (the corrections at a change,
    /// whose columns are half entered).
    fn constrained_rate<const N: usize, const S: usize>(
        &self,
        t: f64,
        state: &SVector<f64, S>,
        check: bool,
    ) -> Result<SVector<f64, S>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mut rate = match &self.rail {
            Some(rail) => rail.state_rate(&self.system, t, state)?,
            None => clamped::<N, S>(self.held_below::<N>(), self.system.state_rate(t, state)?),
        };
        self.project_columns(&mut rate, check)?;
        Ok(rate)
    }

    /// The constrained accelerations, without the checks of
    /// [`VariableMassSystem::accelerations`].
    fn constrained_accelerations<const N: usize, const S: usize>(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> Result<SVector<f64, N>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if let Some(rail) = &self.rail {
            return rail.accelerations(&self.system, t, velocity_state);
        }
        let accelerations = self.system.accelerations(t, velocity_state)?;
        Ok(cancelled(self.held_below::<N>(), accelerations))
    }

    /// The held coordinate, if it is one of the system's `N`.
    fn held_below<const N: usize>(&self) -> Option<usize> {
        self.held.filter(|&k| k < N)
    }

    /// The rail's constraint force at a velocity state (0 off a rail), for the Lagrange
    /// side; a failure of the free system's accelerations is NaN here (the trait's force
    /// methods cannot fail), which the steppers' finiteness check turns into a typed error.
    fn rail_force<const N: usize, const S: usize>(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> SVector<f64, N>
    where
        Sys: VariableMassSystem<N, S>,
    {
        match &self.rail {
            None => SVector::zeros(),
            Some(rail) => rail
                .constraint_force(&self.system, t, velocity_state)
                .unwrap_or_else(|_| SVector::repeat(f64::NAN)),
        }
    }

    /// [`SystemError::RailCoupled`] for a body with sensitivities on a rail whose direction
    /// couples with other coordinates (`support/columns.rs`), and
    /// [`SystemError::SupportCoupled`] where the held coordinate couples with another at
    /// `(t, state)` above [`HELD_COUPLING`]: uncoupled at the start ([`phases`] checks, M_kj
    /// and p_k at rest exactly 0), the coupling may appear as the other coordinates move
    /// (M_yθ = g_c m_p sin θ of a pitching rocket is 0 at θ = 0 only), and the clamp of p_k
    /// would then be a wrong motion, silently (review of session 33: θ 0.8 rad off at 3 s,
    /// exit 0). Checked at every held evaluation (the mass matrix once, only while held).
    fn checked_hold<const N: usize, const S: usize>(
        &self,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<(), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        self.check_rail_coupling(t, state)?;
        match self.held_below::<N>() {
            Some(k) if coupled(&self.system, k, t, state, HELD_COUPLING) => {
                Err(SystemError::SupportCoupled { index: k })
            }
            _ => Ok(()),
        }
    }
}

/// The held phase (ended by the lift-off) and the free phase after it, for `system` with
/// coordinate `k` on its support from `(time, state)`; the free phase alone when the body
/// lifts at once (ṗ_k^free ≥ 0 at the start: nothing for the support to hold, N = 0 — at
/// exactly 0 the free motion starts along the support's tangent, so holding and not differ
/// by nothing at the start). Refused (an [`InvalidConfiguration`](crate::StepErrorKind)
/// error at the start) when `k` is not a coordinate, the body is not at rest along q_k, or
/// q_k couples with another coordinate ([`COUPLED`]).
pub fn phases<Sys, const N: usize, const S: usize>(
    system: Sys,
    k: usize,
    (time, state): (f64, &SVector<f64, S>),
) -> Result<Vec<Phase<'static, Supported<Sys>, S>>, StepError<S>>
where
    Sys: VariableMassSystem<N, S> + Clone,
{
    let free = Phase {
        system: Supported::free(system.clone()),
        carry: Carry::Capture,
        state_masses: &[],
        until: None,
    };
    if !starts_held(&system, k, (time, state))? {
        return Ok(vec![free]);
    }
    Ok(vec![held_phase(system, k), free])
}

/// Whether `system` with coordinate `k` on its support from `(time, state)` is held there
/// (ṗ_k^free < 0), after the checks of [`phases`]: false when it lifts at once.
pub fn starts_held<Sys, const N: usize, const S: usize>(
    system: &Sys,
    k: usize,
    (time, state): (f64, &SVector<f64, S>),
) -> Result<bool, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    check_support(system, k, time, state)?;
    let rate = system
        .state_rate(time, state)
        .map_err(|error| StepError::from_system(system, error, time, state))?;
    // A NaN would compare as "not held" and drop the held phase silently.
    let free = rate[N + k];
    if free.is_nan() {
        return Err(StepError::new(time, *state, StepErrorKind::NonFiniteState));
    }
    Ok(free < 0.0)
}

/// The held phase of `system` with coordinate `k` on its support, ended by the lift-off
/// (as [`phases`] makes it, for a caller that builds the free phases itself).
pub fn held_phase<Sys, const S: usize>(system: Sys, k: usize) -> Phase<'static, Supported<Sys>, S> {
    Phase {
        system: Supported::held(system, k),
        carry: Carry::Capture,
        state_masses: &[],
        until: Some(lift_off(k)),
    }
}

/// The lift-off of coordinate `k`: ṗ_k^free rising through 0, ending the held phase.
pub fn lift_off<const S: usize>(k: usize) -> Event<'static, S> {
    Event {
        condition: EventCondition::LiftOff { coordinate: k },
        direction: Direction::Rising,
        action: EventAction::Stop,
    }
}

/// The lift-off time of a run of `phases` (as [`phases`] gave them): the start when the
/// first phase is not held (the body lifted at once), else the first change of phase;
/// `None` when the body was still on its support at the run's end.
pub fn lift_off_time<Sys, const N: usize, const S: usize>(
    phases: &[Phase<'_, Supported<Sys>, S>],
    phased: &PhasedSolution<N, S>,
) -> Option<f64> {
    match phases.first()?.system.held {
        None => phased.solution.times.first().copied(),
        Some(_) => phased.changes.first().map(|change| change.time),
    }
}

/// The checks of [`phases`]: `k` a coordinate, at rest along it, not coupled.
fn check_support<Sys, const N: usize, const S: usize>(
    system: &Sys,
    k: usize,
    time: f64,
    state: &SVector<f64, S>,
) -> Result<(), StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let refuse = |reason| Err(StepError::invalid_configuration(time, *state, reason));
    if k >= N {
        return refuse(NO_SUCH_COORDINATE);
    }
    let velocity_state = system
        .velocity_state(time, state)
        .map_err(|error| StepError::from_system(system, error, time, state))?;
    if velocity_state[N + k] != 0.0 {
        return refuse(NOT_AT_REST);
    }
    let mut at_rest = *state;
    at_rest.fixed_rows_mut::<N>(N).fill(0.0);
    if coupled(system, k, time, state, 0.0) || system.momenta(time, &at_rest)[k] != 0.0 {
        return refuse(COUPLED);
    }
    Ok(())
}

/// The coupling that ends a hold ([`Supported::checked_hold`]): |M_kj| above this
/// fraction of √(M_kk M_jj). Not 0: a coupling that grows from 0 (sin θ) would be refused
/// at every state past the start, and the step controller, which takes a refused stage
/// for a step too long, would shrink its steps towards t₀ for ever (10⁷ steps to
/// t = 6.5e-160); at 1e-12 the clamp's error is below every tolerance, and the steps
/// shrink onto where the coupling reaches it, a typed error there.
const HELD_COUPLING: f64 = 1e-12;

/// Whether the held coordinate `k` couples with another at `(time, q, m)` of `state` (its
/// momentum rows are not read): |M_kj| > `fraction`·√(M_kk M_jj) for some j ≠ k.
fn coupled<Sys, const N: usize, const S: usize>(
    system: &Sys,
    k: usize,
    time: f64,
    state: &SVector<f64, S>,
    fraction: f64,
) -> bool
where
    Sys: VariableMassSystem<N, S>,
{
    let m = system.mass_matrix(time, state);
    let scale = |j: usize| (m[(k, k)] * m[(j, j)]).abs().sqrt();
    (0..N).any(|j| j != k && m[(k, j)].abs() > fraction * scale(j))
}

/// `rate` with the rows of q_k and p_k (the held coordinate's) set to 0.
fn clamped<const N: usize, const S: usize>(
    held: Option<usize>,
    mut rate: SVector<f64, S>,
) -> SVector<f64, S> {
    if let Some(k) = held {
        rate[k] = 0.0;
        rate[N + k] = 0.0;
    }
    rate
}

/// `force` (a per-coordinate vector) with the held coordinate's entry set to 0: the
/// constraint force N cancels it.
fn cancelled<const N: usize>(held: Option<usize>, mut force: SVector<f64, N>) -> SVector<f64, N> {
    if let Some(k) = held {
        force[k] = 0.0;
    }
    force
}

/// The methods that a hold leaves as they are, each forwarded to the free system
/// `self.system` (a generated system's own, specialised, formulas: the trait's defaults
/// would compute them again from the Lagrange side, to other roundings).
macro_rules! forwarded {
    ($($(#[$doc:meta])* fn $name:ident(&self $(, $arg:ident: $ty:ty)*) $(-> $out:ty)?;)*) => {$(
        $(#[$doc])*
        fn $name(&self $(, $arg: $ty)*) $(-> $out)? {
            self.system.$name($($arg),*)
        }
    )*};
}

/// Every method of `Sys`, but the held coordinate's rates clamped to 0. The Lagrange-side
/// functions are the free ones (L, M, p, the forces: the held state is one of the free
/// system's states), except ∂*L/∂q, the generalized force and q̈, whose entry k the
/// constraint force cancels, so that every stepper — those that read the state rate and the
/// variational one, which reads the Lagrange side — integrates the held motion.
impl<Sys, const N: usize, const S: usize> VariableMassSystem<N, S> for Supported<Sys>
where
    Sys: VariableMassSystem<N, S>,
{
    const COORDINATES: [&'static str; N] = Sys::COORDINATES;
    const MASSES: &'static [&'static str] = Sys::MASSES;
    const HELD: usize = Sys::HELD;

    /// A support wraps a system with sensitivities (`support/columns.rs`), not the other
    /// way round: the sensitivities of a supported system would differentiate the free rate.
    fn sensitivity_obstacle(&self) -> Option<&'static str> {
        Some("a support (wrap the system with sensitivities in the support instead)")
    }

    forwarded! {
        fn mass(&self, index: usize, t: f64, state: &SVector<f64, S>) -> f64;
        fn mass_rate(&self, index: usize, t: f64, velocity_state: &SVector<f64, S>) -> f64;
        fn mass_matrix(&self, t: f64, state: &SVector<f64, S>) -> SMatrix<f64, N, N>;
        fn momenta(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;
        fn lagrangian(&self, t: f64, velocity_state: &SVector<f64, S>) -> f64;
        fn active_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;
        fn reactive_thrust(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;
        fn impact_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;
        fn mass_flux_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;
        fn switch_count(&self) -> usize;
        fn switch_name(&self, index: usize) -> Option<&str>;
        fn switching_functions(&self, t: f64, velocity_state: &SVector<f64, S>, values: &mut [f64]);
        fn switch_anchors(&self, t: f64, velocity_state: &SVector<f64, S>, anchors: &mut [f64]);
        fn anchored_switching_functions(
            &self, t: f64, velocity_state: &SVector<f64, S>, anchors: &[f64], values: &mut [f64]
        );
        fn next_stop_time(&self, after: f64) -> Option<f64>;
        fn has_rate_only_state(&self) -> bool;
        /// A system with sensitivities jumps its columns at a switch: without these the
        /// trait's no-op would cross the switches without the jump, silently.
        fn has_switch_gradients(&self) -> bool;
        fn controlled_entries(&self) -> usize;
        fn measured_block(&self) -> usize;
        fn switch_gradient(
            &self, index: usize, t: f64, velocity_state: &SVector<f64, S>, out: &mut [f64]
        ) -> Result<bool, SystemError>;
        /// Without it a supported spatial body's run would report no approach to gimbal
        /// lock (the trait's default), silently.
        fn singular_attitude_distance(&self, t: f64, state: &SVector<f64, S>) -> Option<f64>;
        fn sample(
            &self, t: f64, state: &mut SVector<f64, S>, which: crate::input::Sampling
        ) -> Result<(), SystemError>;
        fn flow_count(&self) -> usize;
        fn flow_name(&self, index: usize) -> Option<&str>;
        fn flow_rate(&self, index: usize, t: f64, velocity_state: &SVector<f64, S>) -> f64;
        fn check_masses(&self, t: f64, state: &SVector<f64, S>) -> Result<(), SystemError>;
        fn velocities(
            &self, t: f64, state: &SVector<f64, S>
        ) -> Result<SVector<f64, N>, SystemError>;
        fn velocity_state(
            &self, t: f64, state: &SVector<f64, S>
        ) -> Result<SVector<f64, S>, SystemError>;
        fn momentum_state(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, S>;
        fn hamiltonian(&self, t: f64, state: &SVector<f64, S>) -> Result<f64, SystemError>;
        /// The free system's power: the constraint force does no work while held
        /// (q̇_k = 0), so dH/dt along the held motion is the same formula
        /// (docs/mechanics.md).
        fn power(&self, t: f64, state: &SVector<f64, S>) -> Result<f64, SystemError>;
    }

    fn lagrangian_gradient(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        let gradient = self.system.lagrangian_gradient(t, velocity_state);
        cancelled(self.held_below::<N>(), gradient)
    }

    fn accelerations(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> Result<SVector<f64, N>, SystemError> {
        self.checked_hold(t, velocity_state)?;
        self.constrained_accelerations(t, velocity_state)
    }

    fn frozen_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        let force = self.system.frozen_force(t, velocity_state);
        cancelled(self.held_below::<N>(), force) + self.rail_force(t, velocity_state)
    }

    fn generalized_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        let force = self.system.generalized_force(t, velocity_state);
        cancelled(self.held_below::<N>(), force) + self.rail_force(t, velocity_state)
    }

    /// The constrained rate; with sensitivities, each column's rate projected as the
    /// state's (`support/columns.rs`).
    fn state_rate(&self, t: f64, state: &SVector<f64, S>) -> Result<SVector<f64, S>, SystemError> {
        self.checked_hold(t, state)?;
        self.constrained_rate(t, state, true)
    }

    /// Free, a system with sensitivities carries its columns across a phase change; held
    /// or on a rail, made the constrained motion's (`support/columns.rs`).
    fn depart(
        &self,
        t: f64,
        state: &SVector<f64, S>,
        end: &crate::departure::PhaseEnd<'_>,
    ) -> Option<Result<crate::departure::Departure, SystemError>> {
        let mut gradient = [(0, 0.0); 3];
        let end = self.resolved_end(end, &mut gradient)?;
        let departure = self.system.depart(t, state, &end)?;
        let linear = match end {
            crate::departure::PhaseEnd::Linear(gradient) => gradient,
            _ => &[],
        };
        Some(departure.and_then(|mut departure| {
            self.constrain_departure((t, state), linear, &mut departure)?;
            Ok(departure)
        }))
    }

    /// As [`Self::depart`], for the columns entering a phase.
    fn arrive(
        &self,
        t: f64,
        state: &mut SVector<f64, S>,
        departure: &crate::departure::Departure,
        keep_momenta: bool,
        reset: &[usize],
    ) -> Option<Result<(), SystemError>> {
        let arrived = self
            .system
            .arrive(t, state, departure, keep_momenta, reset)?;
        Some(arrived.and_then(|()| self.constrain_arrival(t, state, departure)))
    }

    /// Free, the system's own crossing (the columns jump); held or on a rail with
    /// sensitivities, a kink jumps nothing and a jump is refused (`support/columns.rs`).
    fn cross_switches(
        &self,
        crossed: &[usize],
        before: (f64, &SVector<f64, S>, &SVector<f64, S>),
        (t, after): (f64, &mut SVector<f64, S>),
    ) -> Result<(), SystemError> {
        if !(self.constrained() && self.system.has_rate_only_state()) {
            return self.system.cross_switches(crossed, before, (t, after));
        }
        self.constrained_crossing(crossed, before.2, (t, after))
    }

    /// The free system's state rate, unclamped: the lift-off's switching function reads
    /// its momentum rate.
    fn free_state_rate(
        &self,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<SVector<f64, S>, SystemError> {
        self.system.state_rate(t, state)
    }

    fn rail_reading(
        &self,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Option<Result<(f64, f64), SystemError>> {
        let rail = self.rail.as_ref()?;
        Some(
            rail.push(&self.system, t, state)
                .map(|push| (push, rail.travel(state))),
        )
    }

    /// The free Jacobian with the mechanics' rows constrained as the rate is; with
    /// sensitivities, the columns' rows projected too.
    fn jacobian(&self, t: f64, state: &SVector<f64, S>) -> Result<SMatrix<f64, S, S>, SystemError> {
        let mut jacobian = self.system.jacobian(t, state)?;
        if let Some(rail) = &self.rail {
            jacobian = rail.jacobian::<N, S>(jacobian);
        } else if let Some(k) = self.held_below::<N>() {
            jacobian.row_mut(k).fill(0.0);
            jacobian.row_mut(N + k).fill(0.0);
        }
        for mut column in jacobian.column_iter_mut() {
            let mut projected = column.clone_owned();
            self.project_columns(&mut projected, false)?;
            column.copy_from(&projected);
        }
        Ok(jacobian)
    }

    /// The free system's coefficients once lifted; none while held (the free series moves
    /// q_k, and the held one is not a clamp of it), so the Taylor stepper refuses a held
    /// phase at its construction. The same for the head.
    fn taylor_coefficients(
        &self,
        t: f64,
        state: &SVector<f64, S>,
        coefficients: &mut [SVector<f64, S>],
        scratch: &mut crate::steppers::taylor::series::Scratch,
    ) -> Option<Result<(), SystemError>> {
        self.lifted()?
            .taylor_coefficients(t, state, coefficients, scratch)
    }

    fn taylor_head(
        &self,
        t: crate::dd::Dual,
        state: &[crate::dd::Dual; S],
    ) -> Option<[crate::dd::Dual; S]> {
        self.lifted()?.taylor_head(t, state)
    }

    fn taylor_head_rate(&self, t: f64, state: &[crate::dd::Dd; S]) -> Option<[crate::dd::Dd; S]> {
        self.lifted()?.taylor_head_rate(t, state)
    }
}
