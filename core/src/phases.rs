//! Phases: a scene that changes at events (docs/mechanics.md#jumps-and-phases). Each phase
//! is a system of the same model (other parameters: a stage dropped, a burn rate set to 0)
//! run until its event; the state is carried into the next phase by a declared rule, and
//! the runs are recorded into one solution with the phase of every point.
//!
//! *Separation* (the default) is a mass leaving with the body's velocity: q and q̇ are
//! continuous and p is recomputed through the new momentum map (eq. 8), so the kinetic
//! energy ½ q̇ᵀ(M_before − M_after) q̇ leaves with the separated mass. *Capture* is a
//! plastic impact of arriving mass: the momentum p of the whole continues, and q̇ drops.

use alloc::vec::Vec;

use nalgebra::{SMatrix, SVector};

use crate::departure::PhaseEnd;
use crate::error::StepError;
use crate::events::{Direction, Event, EventCondition};
use crate::run::{run, RunConfig, RunError};
use crate::solution::{Solution, StopReason};
use crate::stepper::{Checked, Stepper};
use crate::system::VariableMassSystem;

/// The error of a phase whose end condition already holds where it begins, or stands
/// exactly on its boundary there: its event could never trigger (a run does not count a
/// start at zero, so that a restart does not re-trigger its own event), and the phase would
/// run silently to the end time instead of handing over to the next. A one-way condition
/// (rising or falling) on its boundary may begin: refused only if g then leaves 0 to the
/// side where it holds without a crossing (at the phase's start, after its run).
pub const ALREADY_PAST: &str = "a phase's end condition already holds (or stands exactly on its \
     boundary) where the phase begins, so it would never trigger";

/// The error of a phase that sets a state mass the system does not have, or to a value that
/// is not a positive number.
pub const BAD_STATE_MASS: &str =
    "a phase sets a state mass the system does not have, or to a value that is not positive";

/// The error of a change between systems whose state a change cannot carry as it carries
/// the mechanics: forward sensitivities are carried (`sensitivity/phases.rs`) only out of a
/// phase that ends at an event on a state entry or a state mass, a rail's exit or a lift-off
/// (`support/columns.rs`), whose gradient gives the change's time its derivative, and into
/// a system that takes them.
pub const NOT_CARRIED: &str = "a run of phases carries sensitivities across a change only \
     where the phase before ends at an event on a state entry, a state mass or a velocity \
     reaching a value (a velocity on a free system only: not while a support or a rail \
     holds the body), a fixed time, a rail's exit or a lift-off (its time's derivative \
     needs the event's gradient), between systems that both have them";

/// The error of a change whose masses move against its carry rule: a separation whose mass
/// matrix grows (mass cannot leave and arrive at once) or a capture whose mass matrix
/// shrinks (mass cannot arrive and leave). Either would create kinetic energy at the change
/// instead of removing it: ½ q̇ᵀ (M_before − M_after) q̇ < 0 for a separation, T at the same
/// p raised for a capture.
pub const MASS_AGAINST_CARRY: &str = "a separation must not add mass and a capture must not \
     remove it: the change would create kinetic energy (a phase that gains mass is entered \
     by `capture`, one that loses mass by `separation`)";

/// The error of [`continue_phases`] given phases that failed: there is no event to go on from.
pub const NOTHING_TO_CONTINUE: &str =
    "the phases to continue failed: there is nothing to go on from";

/// What builds the stepper of a phase from its system and where the phase begins: a
/// closure such as `|system, time, state| Dop853::new(system, time, state, control)`.
pub trait StepperFor<'p, Sys: 'p, const N: usize, const S: usize>:
    FnMut(&'p Sys, f64, SVector<f64, S>) -> Result<Self::Stepper, StepError<S>>
{
    /// The stepper it builds.
    type Stepper: Stepper<N, S>;
}

impl<'p, Sys: 'p, St, F, const N: usize, const S: usize> StepperFor<'p, Sys, N, S> for F
where
    F: FnMut(&'p Sys, f64, SVector<f64, S>) -> Result<St, StepError<S>>,
    St: Stepper<N, S>,
{
    type Stepper = St;
}

/// How the state enters a phase from the one before.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Carry {
    /// A mass separates with the body's velocity: q, q̇ continuous, p recomputed.
    #[default]
    Separation,
    /// Arriving mass is captured in a plastic impact: q and p continuous.
    Capture,
}

/// One phase: the system to run, how the state enters it, the state masses it sets, and
/// the event that ends it (`None`: it runs to the end time).
#[derive(Clone, Copy, Debug)]
pub struct Phase<'a, Sys, const S: usize> {
    /// The system of this phase (same coordinates and state masses as the others).
    pub system: Sys,
    /// How the state enters this phase (ignored for the first).
    pub carry: Carry,
    /// State masses set on entry: (index into the state masses, value).
    pub state_masses: &'a [(usize, f64)],
    /// The event that ends the phase.
    pub until: Option<Event<'a, S>>,
}

/// A change of phase: when, into which phase, and the kinetic energy the change removed
/// (≥ 0 for a separation that drops mass and for a capture alike). It is the kinetic part
/// only: with a potential that depends on the masses (m g y), H also loses the dropped
/// mass's potential energy at the change.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhaseChange {
    /// The phase entered.
    pub phase: usize,
    /// The time of the change.
    pub time: f64,
    /// ½ q̇ᵀ (M_before − M_after) q̇ at separation; for a capture, the kinetic energy lost
    /// in the plastic impact, T_before − T_after at the same p.
    pub kinetic_energy_removed: f64,
}

/// The runs of every phase as one solution, with the phase of each point and the changes.
/// The energy residual (when recorded) continues across a change: the jump of H there is
/// what the change removed, not an integration error.
#[derive(Clone, Debug, PartialEq)]
pub struct PhasedSolution<const N: usize, const S: usize> {
    /// Every point of every phase (a change appears twice: the state before and after).
    pub solution: Solution<N, S>,
    /// The phase of each point.
    pub phase: Vec<usize>,
    /// The changes, in order.
    pub changes: Vec<PhaseChange>,
}

/// Runs `phases` in turn from `(time, state)` to `config.end_time`, each with the stepper
/// `stepper_for` builds for its system, until its event (or the end). On a failure the
/// [`RunError`] carries the solution of every phase so far (see [`run_phases_keeping`] to
/// keep the phase of each point too).
pub fn run_phases<'p, Sys, const N: usize, const S: usize>(
    phases: &'p [Phase<'p, Sys, S>],
    start: (f64, SVector<f64, S>),
    stepper_for: impl StepperFor<'p, Sys, N, S>,
    config: &RunConfig,
) -> Result<PhasedSolution<N, S>, RunError<N, S>>
where
    Sys: VariableMassSystem<N, S>,
{
    into_result(run_phases_keeping(phases, start, stepper_for, config))
}

/// [`run_phases`], a failure returned beside the phased solution so far (its `stop`
/// [`StopReason::Failed`]) instead of in a [`RunError`]: the phase of every point and the
/// changes are kept, as a caller recording the phase column needs.
pub fn run_phases_keeping<'p, Sys, const N: usize, const S: usize>(
    phases: &'p [Phase<'p, Sys, S>],
    start: (f64, SVector<f64, S>),
    stepper_for: impl StepperFor<'p, Sys, N, S>,
    config: &RunConfig,
) -> (PhasedSolution<N, S>, Option<StepError<S>>)
where
    Sys: VariableMassSystem<N, S>,
{
    let phased = PhasedSolution {
        solution: Solution::new(),
        phase: Vec::new(),
        changes: Vec::new(),
    };
    extend(phased, None::<&Sys>, phases, start, stepper_for, config)
}

/// Continues `phased` (which ended at its last phase's event, run with the system
/// `before`) with `phases` of another system type: another struct of the same model, with
/// other tags but the same coordinates and state masses (N and S are checked by the types,
/// the coordinates' names at run time). The first of `phases` is entered from `before` by
/// its `carry` rule at the last point, and the phases are numbered on from `phased`'s. A
/// `phased` that reached the end time is returned as it is; one that failed is an
/// [`StepErrorKind::InvalidConfiguration`](crate::StepErrorKind) error ([`NOTHING_TO_CONTINUE`]).
pub fn continue_phases<'p, Before, Sys, const N: usize, const S: usize>(
    phased: PhasedSolution<N, S>,
    before: &Before,
    phases: &'p [Phase<'p, Sys, S>],
    stepper_for: impl StepperFor<'p, Sys, N, S>,
    config: &RunConfig,
) -> Result<PhasedSolution<N, S>, RunError<N, S>>
where
    Before: VariableMassSystem<N, S>,
    Sys: VariableMassSystem<N, S>,
{
    into_result(continue_phases_keeping(
        phased,
        before,
        phases,
        stepper_for,
        config,
    ))
}

/// [`continue_phases`], a failure returned beside the phased solution so far, as
/// [`run_phases_keeping`] does.
pub fn continue_phases_keeping<'p, Before, Sys, const N: usize, const S: usize>(
    phased: PhasedSolution<N, S>,
    before: &Before,
    phases: &'p [Phase<'p, Sys, S>],
    stepper_for: impl StepperFor<'p, Sys, N, S>,
    config: &RunConfig,
) -> (PhasedSolution<N, S>, Option<StepError<S>>)
where
    Before: VariableMassSystem<N, S>,
    Sys: VariableMassSystem<N, S>,
{
    let Some((time, state)) = phased.solution.last() else {
        return (phased, None);
    };
    if phased.solution.stop == StopReason::Failed {
        let error = StepError::invalid_configuration(time, *state, NOTHING_TO_CONTINUE);
        return (phased, Some(error));
    }
    if phased.solution.stop != (StopReason::EventFound { index: 0 }) {
        return (phased, None);
    }
    if Before::COORDINATES != Sys::COORDINATES {
        let reason = "the next phase's system has other coordinates than the phase before";
        let error = StepError::invalid_configuration(time, *state, reason);
        let mut phased = phased;
        phased.solution.stop = StopReason::Failed;
        return (phased, Some(error));
    }
    let start = (time, *state);
    extend(phased, Some(before), phases, start, stepper_for, config)
}

/// The loop of [`run_phases_keeping`] and [`continue_phases_keeping`]: runs `phases` from
/// `(time, state)`, the first entered from `entry` when there is one, appending to `phased`.
fn extend<'p, Before, Sys, const N: usize, const S: usize>(
    mut phased: PhasedSolution<N, S>,
    entry: Option<&Before>,
    phases: &'p [Phase<'p, Sys, S>],
    (mut time, mut state): (f64, SVector<f64, S>),
    mut stepper_for: impl StepperFor<'p, Sys, N, S>,
    config: &RunConfig,
) -> (PhasedSolution<N, S>, Option<StepError<S>>)
where
    Before: VariableMassSystem<N, S>,
    Sys: VariableMassSystem<N, S>,
{
    let fail = |error, mut phased: PhasedSolution<N, S>| {
        phased.solution.stop = StopReason::Failed;
        (phased, Some(error))
    };
    let first = phased.phase.last().map_or(0, |last| last + 1);
    for (index, phase) in phases.iter().enumerate() {
        let carried = match (index.checked_sub(1), entry) {
            (Some(previous), _) => {
                let before = &phases[previous];
                let ended_by = before.until.as_ref().map(|event| &event.condition);
                Some(carry((&before.system, ended_by), phase, time, &state))
            }
            (None, Some(before)) => Some(carry((before, None), phase, time, &state)),
            (None, None) => None,
        };
        let carried_in = carried.is_some();
        if let Some(carried) = carried {
            let (entered, removed) = match carried {
                Ok(carried) => carried,
                Err(error) => return fail(error, phased),
            };
            state = entered;
            phased.changes.push(PhaseChange {
                phase: first + index,
                time,
                kinetic_energy_removed: removed,
            });
        }
        let on_boundary = match may_begin(phase, time, &state) {
            Ok(on_boundary) => on_boundary,
            Err(error) => return fail(error, phased),
        };
        let mut stepper = match stepper_for(&phase.system, time, state) {
            Ok(stepper) => stepper,
            Err(error) => return fail(error, phased),
        };
        let events: Vec<Event<'_, S>> = phase.until.into_iter().collect();
        // A phase entered from another keeps the held inputs' values and grid.
        let config = match carried_in {
            true => config.continuing(),
            false => *config,
        };
        let (solution, failure) = match run(&mut stepper, &config, &events) {
            Ok(solution) => (solution, None),
            Err(failure) => (*failure.partial, Some(failure.error)),
        };
        if on_boundary && failure.is_none() && held_from_start(phase, &solution) {
            let error = StepError::invalid_configuration(time, state, ALREADY_PAST);
            return fail(error, phased);
        }
        append(&mut phased, solution, first + index);
        if let Some(error) = failure {
            return fail(error, phased);
        }
        let Some((end, last)) = phased.solution.last() else {
            break;
        };
        (time, state) = (end, *last);
        if phased.solution.stop != (StopReason::EventFound { index: 0 }) {
            break;
        }
    }
    (phased, None)
}

/// Whether `phase` may begin at `(time, state)`, and whether it begins exactly on the
/// boundary of a one-way end condition (g = 0 for a rising or falling event: a body lifting
/// off at y = 0 whose phase ends when `y < 0`). Refused ([`ALREADY_PAST`]) where the
/// condition already holds, and on the boundary of an either-way condition, where g may
/// leave 0 to either side and a run does not count a start at zero: it could never trigger.
fn may_begin<Sys, const N: usize, const S: usize>(
    phase: &Phase<'_, Sys, S>,
    time: f64,
    state: &SVector<f64, S>,
) -> Result<bool, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let Some(until) = &phase.until else {
        return Ok(false);
    };
    let g = until.value(&phase.system, time, state);
    let one_way = until.direction != Direction::Either;
    match (g == 0.0 && !one_way) || until.already_past(g) {
        true => Err(StepError::invalid_configuration(time, *state, ALREADY_PAST)),
        false => Ok(g == 0.0),
    }
}

/// Whether a phase begun on its one-way condition's boundary ran without meeting it and
/// ended on the side where it holds: g left 0 that way at once (a start at zero is not
/// counted as a crossing), so the condition held from the start and never triggered.
fn held_from_start<Sys, const N: usize, const S: usize>(
    phase: &Phase<'_, Sys, S>,
    solution: &Solution<N, S>,
) -> bool
where
    Sys: VariableMassSystem<N, S>,
{
    let (Some(until), Some((end, last))) = (&phase.until, solution.last()) else {
        return false;
    };
    let found = solution.stop == (StopReason::EventFound { index: 0 });
    !found && until.already_past(until.value(&phase.system, end, last))
}

/// A kept failure as a [`RunError`] carrying the solution so far.
fn into_result<const N: usize, const S: usize>(
    kept: (PhasedSolution<N, S>, Option<StepError<S>>),
) -> Result<PhasedSolution<N, S>, RunError<N, S>> {
    match kept {
        (phased, None) => Ok(phased),
        (phased, Some(error)) => Err(RunError {
            error,
            partial: alloc::boxed::Box::new(phased.solution),
        }),
    }
}

/// The state entering `phase` from `before`'s `state` at `time`, and the kinetic energy
/// the change removed.
fn carry<Before, Sys, const N: usize, const S: usize>(
    (before, ended_by): (&Before, Option<&EventCondition<'_, S>>),
    phase: &Phase<'_, Sys, S>,
    time: f64,
    state: &SVector<f64, S>,
) -> Result<(SVector<f64, S>, f64), StepError<S>>
where
    Before: VariableMassSystem<N, S>,
    Sys: VariableMassSystem<N, S>,
{
    let (entered, removed) = carry_motion(before, phase, time, state)?;
    if !(before.has_rate_only_state() || phase.system.has_rate_only_state()) {
        return Ok((entered, removed));
    }
    let entered = carry_columns((before, ended_by), phase, time, (state, entered))?;
    Ok((entered, removed))
}

/// The entries past the motion (forward sensitivities) carried from `state` before the
/// change into `entered` after it ([`VariableMassSystem::depart`] and
/// [`VariableMassSystem::arrive`]); refused ([`NOT_CARRIED`]) unless the phase before ended
/// on a state entry, a state mass, a velocity, a fixed time, a rail's exit or a lift-off
/// and both systems carry such entries.
fn carry_columns<Before, Sys, const N: usize, const S: usize>(
    (before, ended_by): (&Before, Option<&EventCondition<'_, S>>),
    phase: &Phase<'_, Sys, S>,
    time: f64,
    (state, mut entered): (&SVector<f64, S>, SVector<f64, S>),
) -> Result<SVector<f64, S>, StepError<S>>
where
    Before: VariableMassSystem<N, S>,
    Sys: VariableMassSystem<N, S>,
{
    let refused = || StepError::invalid_configuration(time, *state, NOT_CARRIED);
    let gradient: [(usize, f64); 1];
    let end = match ended_by {
        Some(EventCondition::StateComponent { index, .. }) => {
            gradient = [(*index, 1.0)];
            PhaseEnd::Linear(&gradient)
        }
        Some(EventCondition::Mass { index, .. }) if *index < Before::STATE_MASSES => {
            gradient = [(2 * N + index, 1.0)];
            PhaseEnd::Linear(&gradient)
        }
        Some(EventCondition::RailExit { .. }) => PhaseEnd::RailTravel,
        Some(EventCondition::LiftOff { .. } | EventCondition::RailLiftOff) => PhaseEnd::Smooth,
        Some(EventCondition::Velocity { coordinate, .. }) => PhaseEnd::Velocity {
            coordinate: *coordinate,
        },
        // The time of the change does not move: dτ/dw = 0.
        Some(EventCondition::Time { .. }) => PhaseEnd::Linear(&[]),
        _ => return Err(refused()),
    };
    let departure = match before.depart(time, state, &end) {
        Some(departure) => departure.map_err(|e| StepError::from_system(before, e, time, state))?,
        None => return Err(refused()),
    };
    let reset: Vec<usize> = (phase.state_masses.iter())
        .map(|(k, _)| 2 * N + k)
        .collect();
    let capture = phase.carry == Carry::Capture;
    let system = &phase.system;
    match system.arrive(time, &mut entered, &departure, capture, &reset) {
        Some(arrived) => arrived.map_err(|e| StepError::from_system(system, e, time, &entered))?,
        None => return Err(refused()),
    }
    Ok(entered)
}

/// The motion carried into `phase` from `before`'s `state` at `time` by the phase's rule
/// (every entry past it copied), and the kinetic energy the change removed.
fn carry_motion<Before, Sys, const N: usize, const S: usize>(
    before: &Before,
    phase: &Phase<'_, Sys, S>,
    time: f64,
    state: &SVector<f64, S>,
) -> Result<(SVector<f64, S>, f64), StepError<S>>
where
    Before: VariableMassSystem<N, S>,
    Sys: VariableMassSystem<N, S>,
{
    let to_step_error = |error| StepError::from_system(before, error, time, state);
    let velocity_state = before.velocity_state(time, state).map_err(to_step_error)?;
    let mut entered = *state;
    let mut moving = velocity_state;
    for &(k, value) in phase.state_masses {
        let index = 2 * N + k;
        // Against the phase's state masses, not S: the held values of sampled inputs follow
        // them, and an index past the masses would write a held value.
        if k >= Sys::STATE_MASSES || !(value.is_finite() && value > 0.0) {
            return Err(StepError::invalid_configuration(
                time,
                *state,
                BAD_STATE_MASS,
            ));
        }
        (entered[index], moving[index]) = (value, value);
    }
    let system = &phase.system;
    let mass_before = before.mass_matrix(time, &velocity_state);
    let mass_after = system.mass_matrix(time, &moving);
    let (larger, smaller) = match phase.carry {
        Carry::Separation => (&mass_before, &mass_after),
        Carry::Capture => (&mass_after, &mass_before),
    };
    if !dominates(larger, smaller) {
        let reason = MASS_AGAINST_CARRY;
        return Err(StepError::invalid_configuration(time, *state, reason));
    }
    let before_energy = kinetic(before, time, &velocity_state);
    match phase.carry {
        Carry::Separation => {
            let after = system.momentum_state(time, &moving);
            Ok((after, before_energy - kinetic(system, time, &moving)))
        }
        Carry::Capture => {
            let after_velocity = system.velocity_state_at(time, &entered)?;
            Ok((
                entered,
                before_energy - kinetic(system, time, &after_velocity),
            ))
        }
    }
}

/// Whether `larger − smaller` is positive semidefinite to the rounding of their entries:
/// then ½ q̇ᵀ (larger − smaller) q̇ ≥ 0 for every q̇, and the change removes kinetic energy
/// whatever the velocity (for a capture at the same p, T = ½ pᵀ M⁻¹ p falls exactly when
/// M_after − M_before ⪰ 0). Tested by a Cholesky factorisation of the difference shifted by
/// 1e-12 of the largest entry (a semidefinite difference, mass unchanged along some
/// direction, factors once shifted); a NaN passes, to be reported where it arises.
fn dominates<const N: usize>(larger: &SMatrix<f64, N, N>, smaller: &SMatrix<f64, N, N>) -> bool {
    let scale = larger.amax().max(smaller.amax());
    let shift = 1e-12 * scale;
    let shifted = larger - smaller + SMatrix::<f64, N, N>::identity() * shift;
    shifted.iter().any(|x| x.is_nan()) || shifted.cholesky().is_some()
}

/// ½ q̇ᵀ M q̇ of `system` at a velocity state.
fn kinetic<Sys, const N: usize, const S: usize>(
    system: &Sys,
    time: f64,
    velocity_state: &SVector<f64, S>,
) -> f64
where
    Sys: VariableMassSystem<N, S>,
{
    let q_dot = velocity_state.fixed_rows::<N>(N);
    0.5 * q_dot.dot(&(system.mass_matrix(time, velocity_state) * q_dot))
}

/// Appends a phase's solution, the energy residual continued from the last one.
fn append<const N: usize, const S: usize>(
    phased: &mut PhasedSolution<N, S>,
    solution: Solution<N, S>,
    index: usize,
) {
    let offset = phased
        .solution
        .energy_residual
        .last()
        .copied()
        .unwrap_or(0.0);
    let all = &mut phased.solution;
    phased
        .phase
        .extend(core::iter::repeat_n(index, solution.times.len()));
    all.times.extend(solution.times);
    all.states.extend(solution.states);
    all.hamiltonian.extend(solution.hamiltonian);
    all.forces.extend(solution.forces);
    all.power.extend(solution.power);
    all.energy_residual
        .extend(solution.energy_residual.into_iter().map(|r| r + offset));
    all.events.extend(solution.events);
    all.stop = solution.stop;
    all.statistics = all.statistics.combine(solution.statistics);
    if let Some(distance) = solution.closest_singular_attitude {
        all.note_attitude(distance);
    }
}
