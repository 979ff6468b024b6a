//! A launch rail (docs/mechanics.md#a-launch-rail): the body's reference point moves along a
//! straight line and every other coordinate is held, until the last rail button leaves the
//! rail; before that, optionally, the body rests on the rail's bottom (its pad) until the
//! net force along the rail lifts it.
//!
//! The rail is a set of linear velocity constraints with constant coefficients: q̇ = b ṡ,
//! where b is the rail's unit direction d written on the position coordinates (x, y, z) of
//! the body's reference point and 0 on every other coordinate, and s the distance travelled
//! along the rail. Lagrange's equations with the constraint forces (d'Alembert: the rail
//! does no work on a motion along it, so the constraint force Q_c is orthogonal to b):
//!
//!   M q̈ = f + Q_c,   bᵀ Q_c = 0,   q̈ = b s̈,
//!
//! where f = M q̈_free is the right-hand side of the free equations (q̈_free the free
//! accelerations at the same q, q̇, t: everything in f — gravity, thrust, the frozen-mass
//! terms — is the free system's). Multiplying by bᵀ gives the one equation of the motion on
//! the rail, s̈ = bᵀ f / (bᵀ M b), and Q_c = M b s̈ − f. The momenta p = ∂L/∂q̇ change
//! with q̈ through M alone (ṗ = M q̈ + terms of q, q̇ and t), so the constrained momentum
//! rate is the free one plus Q_c: ṗ = ṗ_free + Q_c. On the pad (held at the rail's bottom)
//! s̈ = 0, so Q_c = −f: the body stays at rest, and the masses (a motor burning on its pad)
//! run on; a body with no momentum at rest (checked at the start) keeps p = 0 there, so the
//! pad's momentum rate is 0 exactly. The pad holds while bᵀ f ≤ 0 (the support
//! pushes, never pulls) and releases the body where bᵀ f turns positive: [`Rail::push`] is
//! the lift-off's switching function.
//!
//! The coordinate rates are the velocities of the state projected on the rail, q̇ = b (bᵀ q̇)
//! (0 on the pad): the integrated p gives q̇ = b ṡ up to the integration error, and the
//! projection keeps the position on the rail's line and the held coordinates exactly where
//! they are.

use alloc::vec::Vec;

use nalgebra::{SMatrix, SVector};

use crate::error::{StepError, StepErrorKind};
use crate::events::{Direction, Event, EventAction, EventCondition};
use crate::phases::{Carry, Phase, PhasedSolution};
use crate::support::Supported;
use crate::system::{SystemError, VariableMassSystem};

/// A straight launch rail: the position coordinates of the body's reference point, the
/// rail's unit direction in those coordinates' axes, and whether the body still rests on
/// the rail's bottom (its pad).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rail {
    /// The indices of the coordinates x, y, z of the body's reference point.
    pub position: [usize; 3],
    /// The rail's direction, a unit vector in the axes of `position` (up the rail).
    pub direction: [f64; 3],
    /// Where the reference point starts on the rail (the values of `position` there): the
    /// travel up the rail is measured from it.
    pub origin: [f64; 3],
    /// Whether the body rests on the rail's bottom (held there until [`Rail::push`] turns
    /// positive), rather than sliding along the rail.
    pub on_pad: bool,
}

/// The error of a rail whose position indices are not three distinct coordinates.
pub const BAD_POSITION: &str = "a rail's position must be three distinct coordinates";

/// The error of a rail whose direction is not a finite unit vector (to 1e-12).
pub const BAD_DIRECTION: &str = "a rail's direction must be a unit vector";

/// The error of a rail whose length (the travel to the exit) is not positive and finite.
pub const BAD_LENGTH: &str = "a rail's length (the travel to its exit) must be positive";

/// The error of a body with momentum at rest (p = ∂L/∂q̇ ≠ 0 at q̇ = 0: a moving frame, a
/// gyroscopic term), which the pad's p = 0 would not keep.
pub const MOMENTUM_AT_REST: &str = "a body on a rail must have no momentum at rest (p = ∂L/∂q̇ \
     at q̇ = 0 must be 0: the pad holds p at 0)";

/// The error of a body that does not start at rest on its rail.
pub const NOT_AT_REST: &str =
    "a body on a rail must start at rest (every velocity 0): it rests there until lift-off";

impl Rail {
    /// The rail's direction b written on the `N` coordinates.
    pub fn along<const N: usize>(&self) -> SVector<f64, N> {
        let mut b = SVector::<f64, N>::zeros();
        for (i, d) in self.position.iter().zip(self.direction) {
            b[*i] = d;
        }
        b
    }

    /// The rail's checks against a system of `N` coordinates: distinct position indices
    /// within the coordinates, a unit direction.
    pub fn check<const N: usize>(&self) -> Result<(), &'static str> {
        let [i, j, k] = self.position;
        if i == j || j == k || i == k || self.position.iter().any(|&p| p >= N) {
            return Err(BAD_POSITION);
        }
        let norm: f64 = self.direction.iter().map(|d| d * d).sum();
        if !norm.is_finite() || (norm - 1.0).abs() > 1e-12 {
            return Err(BAD_DIRECTION);
        }
        Ok(())
    }

    /// The distance the reference point has travelled up the rail from its origin,
    /// dᵀ(r − r₀).
    pub fn travel<const S: usize>(&self, state: &SVector<f64, S>) -> f64 {
        (self.position.iter().zip(self.direction).zip(self.origin))
            .map(|((&i, d), r0)| d * (state[i] - r0))
            .sum()
    }

    /// bᵀ f: the net generalized force along the rail (the free equations' right-hand side
    /// f = M q̈_free projected on the rail) at `state` `[q, p, m_s]`. The pad pushes while
    /// it is ≤ 0; its rise through 0 is the lift-off.
    pub fn push<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<f64, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let velocity_state = system.velocity_state(t, state)?;
        let (f, _) = free_side(system, t, &velocity_state)?;
        Ok(self.along::<N>().dot(&f))
    }

    /// The constraint force Q_c = M b s̈ − f (module documentation), with s̈ = 0 on the
    /// pad, at a velocity state `[q, q̇, m_s]`.
    pub fn constraint_force<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> Result<SVector<f64, N>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let (f, m) = free_side(system, t, velocity_state)?;
        Ok(m * self.along::<N>() * self.slide(&f, &m) - f)
    }

    /// The constrained accelerations q̈ = b s̈ at a velocity state.
    pub fn accelerations<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> Result<SVector<f64, N>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let (f, m) = free_side(system, t, velocity_state)?;
        Ok(self.along::<N>() * self.slide(&f, &m))
    }

    /// The state rate on the rail at `state` `[q, p, m_s]`: the free one with ṗ += Q_c and
    /// q̇ projected on b; on the pad q̇ = ṗ = 0 and only the masses run.
    pub fn state_rate<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<SVector<f64, S>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mut rate = system.state_rate(t, state)?;
        if self.on_pad {
            // p stays 0 (checked at the start: no momentum at rest, [`on_rail`]), so its rate
            // is 0 exactly rather than ṗ_free − f to rounding, which would leave the resting
            // body velocities of 1e-17 m/s (a condition `z' < 0` met on the pad); the masses
            // run on. Nothing of Q_c is needed.
            rate.fixed_rows_mut::<N>(0).fill(0.0);
            rate.fixed_rows_mut::<N>(N).fill(0.0);
            return Ok(rate);
        }
        let velocity_state = system.velocity_state(t, state)?;
        let force = self.constraint_force(system, t, &velocity_state)?;
        let b = self.along::<N>();
        let sliding = b.dot(&velocity_state.fixed_rows::<N>(N));
        rate.fixed_rows_mut::<N>(0).copy_from(&(b * sliding));
        let momentum_rate = rate.fixed_rows::<N>(N) + force;
        rate.fixed_rows_mut::<N>(N).copy_from(&momentum_rate);
        Ok(rate)
    }

    /// The Jacobian of the rail's state rate, from the free one: the coordinate rows
    /// projected as the rates are (b bᵀ J_q; on the pad these and the momentum rows 0), the
    /// momentum rows on the rail the free ones: the derivative of Q_c is left out. The
    /// implicit steppers' Newton iteration converges with it approximate to the same
    /// solution (their residual is the exact rate); their error estimate, filtered through
    /// (I − hγJ)⁻¹, then reads stiff free momentum rows the rail cancels, which can only
    /// shrink their steps or slow Newton on a stiff model, not change the rate integrated.
    pub fn jacobian<const N: usize, const S: usize>(
        &self,
        mut jacobian: SMatrix<f64, S, S>,
    ) -> SMatrix<f64, S, S> {
        let b = self.along::<N>();
        if self.on_pad {
            jacobian.fixed_rows_mut::<N>(0).fill(0.0);
            jacobian.fixed_rows_mut::<N>(N).fill(0.0);
            return jacobian;
        }
        let rows = b * (b.transpose() * jacobian.fixed_rows::<N>(0));
        jacobian.fixed_rows_mut::<N>(0).copy_from(&rows);
        jacobian
    }

    /// s̈ = bᵀ f / (bᵀ M b) sliding, 0 on the pad.
    fn slide<const N: usize>(&self, f: &SVector<f64, N>, m: &SMatrix<f64, N, N>) -> f64 {
        if self.on_pad {
            return 0.0;
        }
        let b = self.along::<N>();
        b.dot(f) / b.dot(&(m * b))
    }
}

/// f = M q̈_free and M at a velocity state `[q, q̇, m_s]`.
fn free_side<Sys, const N: usize, const S: usize>(
    system: &Sys,
    t: f64,
    velocity_state: &SVector<f64, S>,
) -> Result<(SVector<f64, N>, SMatrix<f64, N, N>), SystemError>
where
    Sys: VariableMassSystem<N, S>,
{
    let free = system.accelerations(t, velocity_state)?;
    let m = system.mass_matrix(t, velocity_state);
    Ok((m * free, m))
}

/// The phases of a launch from a rail: on the pad (when the net force along the rail holds
/// the body there at the start, bᵀ f < 0), sliding up the rail until its reference point
/// has travelled `length` (the last button leaves the rail), and free after it — all of the
/// one wrapper type [`Supported`], entered by [`Carry::Capture`] (q and p continuous: on
/// the pad and the rail the momenta are the free system's at the constrained velocity, so
/// nothing jumps). `position` names the coordinates x, y, z of the body's reference point and
/// `direction` is the rail's unit vector up the rail in their axes. Refused as
/// [`on_rail`] refuses.
pub fn phases<Sys, const N: usize, const S: usize>(
    system: Sys,
    (position, direction): ([usize; 3], [f64; 3]),
    length: f64,
    (time, state): (f64, &SVector<f64, S>),
) -> Result<Vec<Phase<'static, Supported<Sys>, S>>, StepError<S>>
where
    Sys: VariableMassSystem<N, S> + Clone,
{
    let (rail, on_pad) = on_rail(&system, (position, direction), length, (time, state))?;
    let mut phases = Vec::new();
    if on_pad {
        phases.push(pad_phase(system.clone(), rail));
    }
    phases.push(slide_phase(system.clone(), rail, length));
    phases.push(phase(Supported::free(system), None));
    Ok(phases)
}

/// The rail of `system` starting at `(time, state)` (sliding; its origin the position
/// there) and whether the body rests on the pad there (bᵀ f < 0), after the checks: refused
/// (an [`InvalidConfiguration`](StepErrorKind) error at the start) are a bad position or
/// direction ([`Rail::check`]), a length that is not positive, a body not at rest; a
/// non-finite bᵀ f is a [`StepErrorKind::NonFiniteState`].
pub fn on_rail<Sys, const N: usize, const S: usize>(
    system: &Sys,
    (position, direction): ([usize; 3], [f64; 3]),
    length: f64,
    (time, state): (f64, &SVector<f64, S>),
) -> Result<(Rail, bool), StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    let refuse = |reason| StepError::invalid_configuration(time, *state, reason);
    let failed = |error| StepError::from_system(system, error, time, state);
    let rail = Rail {
        position,
        direction,
        origin: [0.0; 3],
        on_pad: false,
    };
    rail.check::<N>().map_err(refuse)?;
    let rail = Rail {
        origin: position.map(|i| state[i]),
        ..rail
    };
    if !(length.is_finite() && length > 0.0) {
        return Err(refuse(BAD_LENGTH));
    }
    let velocities = system.velocities(time, state).map_err(failed)?;
    if velocities.iter().any(|&v| v != 0.0) {
        return Err(refuse(NOT_AT_REST));
    }
    if state.fixed_rows::<N>(N).iter().any(|&p| p != 0.0) {
        return Err(refuse(MOMENTUM_AT_REST));
    }
    let push = rail.push(system, time, state).map_err(failed)?;
    if push.is_nan() {
        return Err(StepError::new(time, *state, StepErrorKind::NonFiniteState));
    }
    Ok((rail, push < 0.0))
}

/// The phase on the pad of `rail`, ended by the lift-off.
pub fn pad_phase<Sys, const S: usize>(
    system: Sys,
    rail: Rail,
) -> Phase<'static, Supported<Sys>, S> {
    let pad = Rail {
        on_pad: true,
        ..rail
    };
    phase(
        Supported::on_rail(system, pad),
        Some(EventCondition::RailLiftOff),
    )
}

/// The phase sliding up `rail`, ended where the reference point has travelled `length`.
pub fn slide_phase<Sys, const S: usize>(
    system: Sys,
    rail: Rail,
    length: f64,
) -> Phase<'static, Supported<Sys>, S> {
    let sliding = Rail {
        on_pad: false,
        ..rail
    };
    let exit = EventCondition::RailExit { length };
    phase(Supported::on_rail(system, sliding), Some(exit))
}

/// A phase of [`phases`]: entered by capture, ended by `condition` rising through 0.
fn phase<Sys, const S: usize>(
    system: Supported<Sys>,
    condition: Option<EventCondition<'static, S>>,
) -> Phase<'static, Supported<Sys>, S> {
    let until = condition.map(|condition| Event {
        condition,
        direction: Direction::Rising,
        action: EventAction::Stop,
    });
    Phase {
        system,
        carry: Carry::Capture,
        state_masses: &[],
        until,
    }
}

/// The lift-off and rail-exit times of a run of `phases` (as [`phases`] gave them): the
/// lift-off is the start when the body did not rest on its pad, and either is `None` when
/// the run ended before it.
pub fn times<Sys, const N: usize, const S: usize>(
    phases: &[Phase<'_, Supported<Sys>, S>],
    phased: &PhasedSolution<N, S>,
) -> (Option<f64>, Option<f64>) {
    let on_pad = phases
        .first()
        .and_then(|p| p.system.rail)
        .is_some_and(|rail| rail.on_pad);
    let change = |i: usize| phased.changes.get(i).map(|change| change.time);
    match on_pad {
        true => (change(0), change(1)),
        false => (phased.solution.times.first().copied(), change(0)),
    }
}
