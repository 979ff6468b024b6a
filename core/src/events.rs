//! Events: functions g(t, state) whose sign changes a run watches for, located by root
//! finding on the stepper's dense output (or a cubic Hermite interpolant), that either stop
//! the run or are recorded.
//!
//! Root finding is the Illinois variant of regula falsi (Dowell & Jarratt, BIT 11, 1971):
//! superlinear, and it always keeps a bracket. The located time is the end of the final
//! bracket on the far side of the crossing, so g has already changed sign there.
//! Two sign changes within one step cancel and go unseen, as in every such scheme: keep
//! steps shorter than the time between crossings.

use core::fmt;

use nalgebra::SVector;

use crate::error::ConfigError;
use crate::system::VariableMassSystem;

/// Which sign changes of g trigger an event.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Direction {
    /// g goes from negative to zero or positive.
    Rising,
    /// g goes from positive to zero or negative.
    Falling,
    /// Either.
    #[default]
    Either,
}

/// What a run does when an event triggers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EventAction {
    /// End the run at the event.
    #[default]
    Stop,
    /// Record the event and continue.
    Record,
}

/// The function g(t, state) an event watches.
#[derive(Clone, Copy)]
pub enum EventCondition<'a, const S: usize> {
    /// g = mᵢ(t, state) − threshold: a mass (index into
    /// [`VariableMassSystem::MASSES`]) reaching a threshold.
    Mass {
        /// Index into [`VariableMassSystem::MASSES`].
        index: usize,
        /// The mass at which the event triggers.
        threshold: f64,
    },
    /// g = `state[index]` − value: a coordinate, momentum or state mass reaching a value.
    StateComponent {
        /// Index into the state `[q, p, m_s]`.
        index: usize,
        /// The value at which the event triggers.
        value: f64,
    },
    /// g = ṗ_k of the free equations ([`VariableMassSystem::free_state_rate`]): the net
    /// generalized force along coordinate k's support, whose rise through 0 lifts a held
    /// body off it ([`crate::support`]).
    LiftOff {
        /// The supported coordinate, an index into the coordinates.
        coordinate: usize,
    },
    /// g = bᵀ f, the net force along a launch rail ([`crate::rail`]) of a body resting on
    /// the rail's bottom, whose rise through 0 lifts it (the phase's system is on a rail:
    /// [`VariableMassSystem::rail_reading`]).
    RailLiftOff,
    /// g = the distance travelled up a launch rail − `length`: the last rail button
    /// leaving the rail as g rises through 0.
    RailExit {
        /// The travel of the body's reference point at which it leaves the rail, m.
        length: f64,
    },
    /// g = q̇_k(t, state) − value: coordinate k's velocity reaching a value (an apogee:
    /// a vertical velocity through 0, falling).
    Velocity {
        /// The coordinate, an index into the coordinates.
        coordinate: usize,
        /// The velocity at which the event triggers.
        value: f64,
    },
    /// g = t − value: a fixed time.
    Time {
        /// The time at which the event triggers.
        value: f64,
    },
    /// Any function of the time and the state `[q, p, m_s]`.
    Function(&'a dyn Fn(f64, &SVector<f64, S>) -> f64),
}

impl<const S: usize> fmt::Debug for EventCondition<'_, S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Mass { index, threshold } => f
                .debug_struct("Mass")
                .field("index", index)
                .field("threshold", threshold)
                .finish(),
            Self::StateComponent { index, value } => f
                .debug_struct("StateComponent")
                .field("index", index)
                .field("value", value)
                .finish(),
            Self::LiftOff { coordinate } => f
                .debug_struct("LiftOff")
                .field("coordinate", coordinate)
                .finish(),
            Self::RailLiftOff => f.write_str("RailLiftOff"),
            Self::RailExit { length } => {
                f.debug_struct("RailExit").field("length", length).finish()
            }
            Self::Velocity { coordinate, value } => f
                .debug_struct("Velocity")
                .field("coordinate", coordinate)
                .field("value", value)
                .finish(),
            Self::Time { value } => f.debug_struct("Time").field("value", value).finish(),
            Self::Function(_) => f.write_str("Function(..)"),
        }
    }
}

/// An event: a condition, the sign changes that count, and what to do.
#[derive(Clone, Copy, Debug)]
pub struct Event<'a, const S: usize> {
    /// The function g(t, state).
    pub condition: EventCondition<'a, S>,
    /// Which sign changes trigger.
    pub direction: Direction,
    /// Stop or record.
    pub action: EventAction,
}

impl<'a, const S: usize> Event<'a, S> {
    /// The built-in mass event: stop when mass `index` reaches `threshold` (from either
    /// side), e.g. a rocket's propellant running out.
    pub fn mass_reaches(index: usize, threshold: f64) -> Self {
        Self {
            condition: EventCondition::Mass { index, threshold },
            direction: Direction::Either,
            action: EventAction::Stop,
        }
    }

    /// Stop when state component `index` reaches `value` in the given direction.
    pub fn state_reaches(index: usize, value: f64, direction: Direction) -> Self {
        Self {
            condition: EventCondition::StateComponent { index, value },
            direction,
            action: EventAction::Stop,
        }
    }

    /// Stop when coordinate `coordinate`'s velocity q̇ reaches `value` in the given
    /// direction (an apogee: `velocity_reaches(k, 0.0, Direction::Falling)`).
    pub fn velocity_reaches(coordinate: usize, value: f64, direction: Direction) -> Self {
        Self {
            condition: EventCondition::Velocity { coordinate, value },
            direction,
            action: EventAction::Stop,
        }
    }

    /// Stop at the time `value` (reached rising).
    pub fn time_reaches(value: f64) -> Self {
        Self {
            condition: EventCondition::Time { value },
            direction: Direction::Rising,
            action: EventAction::Stop,
        }
    }

    /// An event on a user function g(t, state).
    pub fn function(
        function: &'a dyn Fn(f64, &SVector<f64, S>) -> f64,
        direction: Direction,
        action: EventAction,
    ) -> Self {
        Self {
            condition: EventCondition::Function(function),
            direction,
            action,
        }
    }

    /// Checks the indices against the system.
    pub(crate) fn validate<Sys, const N: usize>(&self) -> Result<(), ConfigError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let ok = match self.condition {
            EventCondition::Mass { index, threshold } => {
                index < Sys::MASSES.len() && threshold.is_finite()
            }
            EventCondition::StateComponent { index, value } => index < S && value.is_finite(),
            EventCondition::LiftOff { coordinate } => coordinate < N,
            EventCondition::RailLiftOff => true,
            EventCondition::RailExit { length } => length.is_finite(),
            EventCondition::Velocity { coordinate, value } => coordinate < N && value.is_finite(),
            EventCondition::Time { value } => value.is_finite(),
            EventCondition::Function(_) => true,
        };
        if ok {
            Ok(())
        } else {
            Err(ConfigError {
                reason: "an event's index is out of range or its threshold is not finite",
            })
        }
    }

    /// g(t, state): the event's function, whose sign changes trigger it.
    pub fn value<Sys, const N: usize>(
        &self,
        system: &Sys,
        time: f64,
        state: &SVector<f64, S>,
    ) -> f64
    where
        Sys: VariableMassSystem<N, S>,
    {
        match self.condition {
            EventCondition::Mass { index, threshold } => {
                system.mass(index, time, state) - threshold
            }
            EventCondition::StateComponent { index, value } => state
                .get(index)
                .map_or(f64::NAN, |component| component - value),
            EventCondition::LiftOff { coordinate } => system
                .free_state_rate(time, state)
                .map_or(f64::NAN, |rate| rate[N + coordinate]),
            EventCondition::RailLiftOff => match system.rail_reading(time, state) {
                Some(Ok((push, _))) => push,
                _ => f64::NAN,
            },
            EventCondition::RailExit { length } => match system.rail_reading(time, state) {
                Some(Ok((_, travel))) => travel - length,
                _ => f64::NAN,
            },
            EventCondition::Velocity { coordinate, value } => system
                .velocities(time, state)
                .map_or(f64::NAN, |velocities| velocities[coordinate] - value),
            EventCondition::Time { value } => time - value,
            EventCondition::Function(function) => function(time, state),
        }
    }

    /// Whether g already stands where this event's crossing would take it (g > 0 for a
    /// rising event, g < 0 for a falling one): started there, the event can never trigger.
    pub(crate) fn already_past(&self, g: f64) -> bool {
        match self.direction {
            Direction::Rising => g > 0.0,
            Direction::Falling => g < 0.0,
            Direction::Either => false,
        }
    }

    /// Whether g going from `before` to `after` is a sign change this event counts. A start
    /// exactly at zero does not count, so a run restarted at an event does not re-trigger.
    pub(crate) fn triggered(&self, before: f64, after: f64) -> bool {
        let rising = before < 0.0 && after >= 0.0;
        let falling = before > 0.0 && after <= 0.0;
        match self.direction {
            Direction::Rising => rising,
            Direction::Falling => falling,
            Direction::Either => rising || falling,
        }
    }
}

/// An event that triggered during a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EventHit<const S: usize> {
    /// Index of the event in the list given to the run.
    pub index: usize,
    /// The located time.
    pub time: f64,
    /// The interpolated state at that time.
    pub state: SVector<f64, S>,
}

/// Locates a sign change of g in `[start, end]` (values `g_start`, `g_end` of opposite sign,
/// or `g_end == 0`) to within `tolerance` in t by the Illinois method, falling back to
/// bisection if the bracket does not shrink in 100 iterations.
pub(crate) fn locate_root(
    g: impl FnMut(f64) -> f64,
    start: (f64, f64),
    end: (f64, f64),
    tolerance: f64,
) -> f64 {
    locate_bracket(g, start, end, tolerance).1
}

/// [`locate_root`]'s final bracket `(near, far)`: g at `near` has the sign of `g_start`, g
/// at `far` has changed sign (or is zero), and they are within `tolerance` (or rounding)
/// of each other; both are `end` when g is zero there. Switches land on the near end and
/// restart at the far one.
pub(crate) fn locate_bracket(
    mut g: impl FnMut(f64) -> f64,
    (start, g_start): (f64, f64),
    (end, g_end): (f64, f64),
    tolerance: f64,
) -> (f64, f64) {
    if g_end == 0.0 {
        return (end, end);
    }
    let (mut a, mut g_a, mut b, mut g_b) = (start, g_start, end, g_end);
    // Which end was kept by the last iteration: −1 for a, +1 for b, 0 for none yet.
    let mut kept = 0i8;
    for iteration in 0..200 {
        let width = (b - a).abs();
        if width <= tolerance.max(4.0 * f64::EPSILON * a.abs().max(b.abs())) {
            break;
        }
        let secant = (a * g_b - b * g_a) / (g_b - g_a);
        let inside = secant > a.min(b) && secant < a.max(b);
        let c = if iteration < 100 && inside {
            secant
        } else {
            0.5 * (a + b)
        };
        let g_c = g(c);
        // A zero counts as the far side (g has reached it), so the near end keeps closing in.
        let near_side = g_c != 0.0 && (g_c > 0.0) == (g_a > 0.0);
        if !near_side {
            b = c;
            g_b = g_c;
            if kept == -1 {
                // a kept twice in a row: halve its value so the secant moves past it.
                g_a *= 0.5;
            }
            kept = -1;
        } else {
            a = c;
            g_a = g_c;
            if kept == 1 {
                g_b *= 0.5;
            }
            kept = 1;
        }
    }
    (a, b)
}
