//! Switches: the sign changes of the system's switching functions
//! ([`VariableMassSystem::switching_functions`], docs/mechanics.md#switches), located so
//! that no step straddles a jump or a kink of the state rate.
//!
//! A step whose end has a switching function on the other side is discarded: its
//! interpolant locates the crossing's bracket `(near, far)` to rounding, and the run repeats
//! the integration from the step's start to `near`, where the state rate is still smooth
//! (a *redo*). Landed there, it crosses the bracket (usually a few roundings of t wide; an
//! Euler step spans at most 10⁶ of them, about 9·10⁻¹⁰·max(|t|, 1)) by
//! one Euler step with the rate before the switch and restarts the stepper at `far`,
//! forgetting the FSAL rate and the controller's memory. Where that step does not change g's
//! sign (g reads an argument that moves by a rounding of itself only over many roundings of
//! t, a table of a·x + c with |a·ẋ| ≪ 1), the shortest step within a million roundings that
//! does is taken instead (`across_shortest`). A crossing located within the
//! bracket of the step's start is crossed at once. When the interpolant across the jump put
//! `near` too early (a state-dependent switch), the landing finds no change of sign across
//! the bracket and the run simply goes on from `near`: the next crossing step is shorter.
//!
//! Where the state carries more than the motion (forward sensitivities), the crossing step
//! hands it to [`VariableMassSystem::cross_switches`], which jumps it: the columns move by
//! (f⁻ − f⁺) dτ/dw (`sensitivity/switches.rs`). A start standing on a switch applies no
//! jump: the columns are then the derivatives for the perturbations that keep the start on
//! the side the motion enters (the other side's crossing would move the switch's time).
//!
//! A switch crossed [`Switching::chatter_crossings`] times within
//! [`Switching::chatter_window`] of the run's span chatters: the run ends with
//! [`StepErrorKind::Chattering`].

use alloc::vec;
use alloc::vec::Vec;

use nalgebra::SVector;

use super::point::Point;
use crate::error::{StepError, StepErrorKind};
use crate::events::locate_bracket;
use crate::stepper::Checked;
use crate::system::{SystemError, VariableMassSystem};

/// How a run treats the system's switching functions. On by default.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Switching {
    /// Whether crossings are located and the stepper restarted there. Off, the steppers
    /// step across jumps and kinks as they would across any rate (losing their order).
    pub locate: bool,
    /// How many crossings of one switch within the window make it chatter.
    pub chatter_crossings: usize,
    /// The window, as a fraction of the run's span `end_time − start time`.
    pub chatter_window: f64,
}

impl Default for Switching {
    /// Located; 16 crossings within 10⁻⁹ of the run's span chatter.
    fn default() -> Self {
        Self {
            locate: true,
            chatter_crossings: 16,
            chatter_window: 1e-9,
        }
    }
}

/// What the last step showed.
pub(crate) enum Crossing<const S: usize> {
    /// No switch changed sign: the step stands.
    None,
    /// A switch changed sign inside the step: discard it and integrate from its start to
    /// `near` (the stepper must be restarted at the step's start with `near` its stop time).
    Redo {
        /// Where to land, just before the crossing.
        near: f64,
    },
    /// A switch changed sign within rounding of the step's start (or the run landed on a
    /// redo's `near`): restart the stepper at `(time, state)`, past the crossing.
    Cross {
        /// The far end of the crossing's bracket.
        time: f64,
        /// The state there.
        state: SVector<f64, S>,
    },
}

/// The switching functions at the last point, the crossing being approached, and the
/// recent crossings of each switch.
pub(crate) struct SwitchWatch {
    settings: Switching,
    /// g at the last accepted point.
    values: Vec<f64>,
    /// The anchors of the anchored switches (the knots of a table of the state), set at
    /// the start and after each crossing.
    anchors: Vec<f64>,
    scratch: Vec<f64>,
    /// The bracket of the crossing a redo is landing on.
    pending: Option<(f64, f64)>,
    /// Per switch: the time of the first crossing of the current burst and how many.
    bursts: Vec<(f64, usize)>,
    /// The chatter window in t.
    window: f64,
}

impl SwitchWatch {
    /// Watches the switches of `system` from `start`, or `None` when it has none or the run
    /// does not locate them (so a system without switches costs nothing).
    pub(crate) fn start<Sys, const N: usize, const S: usize>(
        system: &Sys,
        settings: Switching,
        start: &Point<S>,
        end_time: f64,
    ) -> Result<Option<Self>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let count = system.switch_count();
        if count == 0 || !settings.locate {
            return Ok(None);
        }
        let mut watch = Self {
            settings,
            values: vec![0.0; count],
            anchors: vec![0.0; count],
            scratch: vec![0.0; count],
            pending: None,
            bursts: vec![(f64::NEG_INFINITY, 0); count],
            window: settings.chatter_window * (end_time - start.time).abs(),
        };
        watch.anchor(system, start.time, &start.state)?;
        let mut values = core::mem::take(&mut watch.values);
        watch.evaluate(system, start.time, &start.state, &mut values)?;
        watch.values = values;
        Ok(Some(watch))
    }

    /// Where the run starts with a switch standing exactly on zero (`sign(x')`, `abs(y')` of
    /// a body released from rest), the start is the switch: the rate there is the kink's
    /// (sign(0) = 0), and a first step whose end lies on either side is no change of sign
    /// (`changed_sign(0, g)`), so it was taken blindly across it (RK4 stepped 0 → + → −
    /// through a body held by friction and ended with ẋ = −0.2; Taylor's |ẏ| took the branch
    /// of ẏ ≥ 0 for a whole first step of a fall). The side the motion enters is found by
    /// probes s = 4ε·max(|t|, 1)·2ᵏ (up to 10⁶ of them, as a crossing's sliver) along
    /// y + s·f(t + s, y + s·f(t, y)): its second stage sees the rate change where the tangent
    /// itself is flat (a push a·t from t = 0 on a body at rest). The first probe off zero is
    /// crossed to as a switch is, counted, and held there ([`Self::sliding`]); `None` when
    /// no switch is on zero or none leaves it within reach (an equilibrium on the switch:
    /// the run steps on as before).
    pub(crate) fn leave_zero<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        point: &Point<S>,
    ) -> Result<Option<Crossing<S>>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let on_zero: Vec<usize> = (self.values.iter().enumerate())
            .filter(|(_, &g)| g == 0.0)
            .map(|(index, _)| index)
            .collect();
        if on_zero.is_empty() {
            return Ok(None);
        }
        let rate = match point.rate {
            Some(rate) => rate,
            None => rate_at(system, point.time, &point.state)?,
        };
        let mut after = vec![0.0; self.values.len()];
        for step in slivers(point.time) {
            let time = point.time + step;
            let predicted = point.state + rate * step;
            let state = point.state + rate_at(system, time, &predicted)? * step;
            self.evaluate(system, time, &state, &mut after)?;
            let left: Vec<usize> = (on_zero.iter().copied())
                .filter(|&index| after[index] != 0.0)
                .collect();
            if !left.is_empty() {
                for &index in &left {
                    self.count(index, time, &state)?;
                }
                let (time, state) = self.sliding(system, &left, step, (time, state), &mut after)?;
                self.keep(&after);
                self.anchor(system, time, &state)?;
                return Ok(Some(Crossing::Cross { time, state }));
            }
        }
        Ok(None)
    }

    /// From `at`, just off zero on the side the switches `left` entered (g there in
    /// `values`), Euler steps of `step` while one of them comes back toward zero or across
    /// it, each crossing counted: where the rate on either side drives g back to zero
    /// (Filippov's sliding mode, a block held by Coulomb friction) the crossings go on and
    /// the run ends with [`StepErrorKind::Chattering`], as an adaptive stepper's shrinking
    /// steps find (a fixed RK4 step from just off zero has stages on both sides and 0.25 s
    /// of them ended on the side it began: no sign change, ẋ garbage). Else the point from
    /// which g moves away from zero; `values` then holds g there (its side where it is 0).
    fn sliding<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        left: &[usize],
        step: f64,
        mut at: (f64, SVector<f64, S>),
        values: &mut [f64],
    ) -> Result<(f64, SVector<f64, S>), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mut previous = values.to_vec();
        let mut next = vec![0.0; values.len()];
        for _ in 0..4 * self.settings.chatter_crossings {
            let time = at.0 + step;
            let state = at.1 + rate_at(system, at.0, &at.1)? * step;
            self.evaluate(system, time, &state, &mut next)?;
            let mut back = false;
            for &index in left {
                if changed_sign(values[index], next[index]) {
                    self.count(index, time, &state)?;
                    back = true;
                }
                back |= next[index].abs() < previous[index].abs();
            }
            if !back {
                break;
            }
            for ((value, kept), &now) in values.iter_mut().zip(&mut previous).zip(&next) {
                *kept = now;
                if now != 0.0 {
                    *value = now;
                }
            }
            at = (time, state);
        }
        Ok(at)
    }

    /// Takes g afresh at `point`, where the run restarted with a state changed by a jump
    /// that is no crossing (a sample of the held inputs, docs/inputs.md#sampled-inputs): a
    /// switch on a held value changes there without the state crossing it. The chatter
    /// counts are kept.
    pub(crate) fn resume<const N: usize, const S: usize>(
        &mut self,
        system: &impl VariableMassSystem<N, S>,
        point: &Point<S>,
    ) -> Result<(), StepError<S>> {
        self.pending = None;
        self.anchor(system, point.time, &point.state)?;
        let mut values = core::mem::take(&mut self.values);
        let evaluated = self.evaluate(system, point.time, &point.state, &mut values);
        self.values = values;
        evaluated
    }

    /// Anchors the anchored switches at `(time, state)`; after a crossing, the g of a
    /// switch whose anchor moved is its value there, ≥ 0 by the anchor's definition (a
    /// zero, on a knot, is stored as the smallest positive number, so that going back is
    /// a crossing too).
    fn anchor<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        time: f64,
        state: &SVector<f64, S>,
    ) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let velocity_state = system.velocity_state_at(time, state)?;
        let before = self.anchors.clone();
        system.switch_anchors(time, &velocity_state, &mut self.anchors);
        if before == self.anchors {
            return Ok(());
        }
        let mut now = vec![0.0; self.values.len()];
        system.anchored_switching_functions(time, &velocity_state, &self.anchors, &mut now);
        let moved = before.iter().zip(&self.anchors).map(|(a, b)| a != b);
        for ((value, now), moved) in self.values.iter_mut().zip(now).zip(moved) {
            if moved {
                *value = now.max(f64::MIN_POSITIVE);
            }
        }
        Ok(())
    }

    /// g at `(time, state)` into `values`.
    fn evaluate<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        time: f64,
        state: &SVector<f64, S>,
        values: &mut [f64],
    ) -> Result<(), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let velocity_state = system.velocity_state_at(time, state)?;
        system.anchored_switching_functions(time, &velocity_state, &self.anchors, values);
        Ok(())
    }

    /// Checks the step from `start` to `end`, the states within it from `interpolate`.
    pub(crate) fn check_step<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        (start, end): (&Point<S>, &Point<S>),
        interpolate: &impl Fn(f64) -> SVector<f64, S>,
    ) -> Result<Crossing<S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mut after = core::mem::take(&mut self.scratch);
        let evaluated = self.evaluate(system, end.time, &end.state, &mut after);
        let crossing = evaluated.map(|()| self.earliest(system, (start, end), interpolate, &after));
        let result = match crossing {
            Ok(Some((near, far))) if near - start.time > far - near => {
                self.pending = Some((near, far));
                Ok(Crossing::Redo { near })
            }
            Ok(Some((near, far))) => {
                self.pending = Some((near, far));
                match self.cross_from(system, start) {
                    Ok(Crossing::None) => {
                        // The interpolant across the jump misplaced the crossing and the
                        // tangent finds none near: let the step stand (rare), re-anchored at
                        // its end so that the switch watches the bracket the run is in
                        // (kept on the old one, its g would keep the sign it changed to
                        // and never change again).
                        let crossed = self.crossed_by(&after);
                        self.keep(&after);
                        self.anchor(system, end.time, &end.state)?;
                        self.carried_across(system, end, &crossed)
                    }
                    other => other,
                }
            }
            Ok(None) => {
                self.keep(&after);
                Ok(Crossing::None)
            }
            Err(error) => Err(error),
        };
        self.scratch = after;
        result
    }

    /// The switches whose g changed sign from the last point to `after`.
    fn crossed_by(&self, after: &[f64]) -> Vec<usize> {
        (self.values.iter().zip(after).enumerate())
            .filter(|(_, (&before, &after))| changed_sign(before, after))
            .map(|(index, _)| index)
            .collect()
    }

    /// A step that stands across the switches `crossed` (their crossing not located): for
    /// a system whose state carries more than the motion (sensitivities), whose jump needs
    /// the crossing's point, a typed error at the step's end, never the jump missed or
    /// guessed from the step's start; else the step simply stands.
    fn carried_across<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        end: &Point<S>,
        crossed: &[usize],
    ) -> Result<Crossing<S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        match crossed.first() {
            Some(&switch) if system.has_rate_only_state() => {
                let error = SystemError::UnlocatedSwitch { switch };
                Err(StepError::from_system(system, error, end.time, &end.state))
            }
            _ => Ok(Crossing::None),
        }
    }

    /// Takes `after` as g at the last point, except where it is exactly zero: there the
    /// side g came from is kept, so that leaving zero on the other side is a crossing.
    fn keep(&mut self, after: &[f64]) {
        for (value, &after) in self.values.iter_mut().zip(after) {
            if after != 0.0 {
                *value = after;
            }
        }
    }

    /// The bracket of the earliest crossing in the step, given g at its end.
    fn earliest<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        (start, end): (&Point<S>, &Point<S>),
        interpolate: &impl Fn(f64) -> SVector<f64, S>,
        after: &[f64],
    ) -> Option<(f64, f64)>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mut values = vec![0.0; after.len()];
        let mut earliest: Option<(f64, f64)> = None;
        for (index, (&before, &after)) in self.values.iter().zip(after).enumerate() {
            if !changed_sign(before, after) {
                continue;
            }
            let g = |time: f64| {
                let state = interpolate(time);
                match self.evaluate(system, time, &state, &mut values) {
                    Ok(()) => values[index],
                    Err(_) => f64::NAN,
                }
            };
            // Located to rounding: the bracket is the width of the step that crosses it.
            let bracket = locate_bracket(g, (start.time, before), (end.time, after), 0.0);
            if earliest.is_none_or(|(near, _)| bracket.0 < near) {
                earliest = Some(bracket);
            }
        }
        earliest
    }

    /// The pending crossing's bracket if the run just landed on its near end at `time`.
    pub(crate) fn landed(&self, time: f64) -> bool {
        self.pending.is_some_and(|(near, _)| near == time)
    }

    /// Crosses the pending bracket from `point` (its near end, or within it of a step's
    /// start): one Euler step with the rate before the switch to the far end, counted
    /// against the chatter limit. When the interpolant across the jump put the bracket too
    /// early (a switch on the state), the crossing is still ahead: the root of g along the
    /// tangent of the motion gives it, crossed the same way when it is within a million
    /// roundings, else landed on again by a redo to 0.9 of the way there. A crossing within
    /// reach is crossed by the shortest step over which g changes sign, which may be many
    /// roundings of t when g's own argument moves slowly ([`Self::across_shortest`]).
    pub(crate) fn cross_from<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        point: &Point<S>,
    ) -> Result<Crossing<S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let Some((_, far)) = self.pending.take() else {
            return Ok(Crossing::None);
        };
        let mut before = vec![0.0; self.values.len()];
        self.evaluate(system, point.time, &point.state, &mut before)?;
        self.keep(&before);
        let rate = match point.rate {
            Some(rate) => rate,
            None => system
                .state_rate(point.time, &point.state)
                .map_err(|error| StepError::from_system(system, error, point.time, &point.state))?,
        };
        // An Euler step is only taken over what rounding (and a million of it) is: its
        // error, the jump times the step, then stays at the level of the bracket itself.
        let rounding = 4.0 * f64::EPSILON * point.time.abs().max(1.0);
        let small = 1e6 * rounding;
        let step = far - point.time;
        if step <= small {
            if let Some(crossing) = self.across(system, point, &rate, step)? {
                return Ok(crossing);
            }
        }
        let ahead = self.tangent_root(system, point, &rate, &before)?;
        if let Some(ahead) = ahead.filter(|&ahead| ahead > small) {
            let near = point.time + 0.9 * ahead;
            self.pending = Some((near, near));
            return Ok(Crossing::Redo { near });
        }
        let from = ahead.unwrap_or(0.0);
        Ok(self
            .across_shortest(system, point, &rate, from, (rounding, small))?
            .unwrap_or(Crossing::None))
    }

    /// The first of the Euler steps `from + rounding · 2ᵏ` (k = 0, 1, …, up to `from +
    /// small`) from `point` over which some switch changes sign.
    ///
    /// A switch changes only by the roundings of what it reads, not of t: the knots of a
    /// table of the state read its argument s, which a step of a few roundings of t moves by
    /// a few roundings of s only when |ds/dt| ≳ 1. For s = a·x + c with |a·ẋ| ≪ 1 the
    /// bracket located in t (or the tangent's root plus a rounding of t) moves s by less
    /// than an ulp, and g, which sits on the last argument of its side (zero there,
    /// `core::table::knot_gap_read`), does not change: the step must be as long as s needs.
    /// Before (review of 2026-11-26) the run then let the step that crossed the box of
    /// G(0.01·x + 0.995) stand, the jump read at its later stages only (5.5e-5 off by RK4 at
    /// step 0.01), and the switch, never re-anchored, missed the exit.
    fn across_shortest<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        point: &Point<S>,
        rate: &SVector<f64, S>,
        from: f64,
        (rounding, small): (f64, f64),
    ) -> Result<Option<Crossing<S>>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mut extra = rounding;
        while extra <= small {
            if let Some(crossing) = self.across(system, point, rate, from + extra)? {
                return Ok(Some(crossing));
            }
            extra *= 2.0;
        }
        Ok(None)
    }

    /// The Euler step of `step` from `point` along `rate`, if some switch changes sign over
    /// it (each such crossing counted).
    fn across<Sys, const N: usize, const S: usize>(
        &mut self,
        system: &Sys,
        point: &Point<S>,
        rate: &SVector<f64, S>,
        step: f64,
    ) -> Result<Option<Crossing<S>>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let (time, mut state) = (point.time + step, point.state + rate * step);
        let mut after = vec![0.0; self.values.len()];
        self.evaluate(system, time, &state, &mut after)?;
        let crossings = self.crossed_by(&after);
        for &index in &crossings {
            self.count(index, time, &state)?;
        }
        let crossed = !crossings.is_empty();
        if !crossed {
            return Ok(None);
        }
        // What the state carries past the motion (sensitivities) jumps here.
        if system.has_rate_only_state() {
            let (t0, y0, f0) = self.side_before(system, point, rate, &crossings)?;
            (system.cross_switches(&crossings, (t0, &y0, &f0), (time, &mut state)))
                .map_err(|error| StepError::from_system(system, error, time, &state))?;
        }
        self.keep(&after);
        self.anchor(system, time, &state)?;
        Ok(Some(Crossing::Cross { time, state }))
    }

    /// A point on the side the switches `crossed` come from, and its rate: `point` itself,
    /// unless one of them stands exactly on zero there (a run landed on a stop time at the
    /// switch, `sign(t_b − t)` at a thrust table's last knot: the rate there is the kink's,
    /// sign(0) = 0, half the jump), then the first of the backward probes
    /// `point − rate·s`, s = 4ε·max(|t|, 1)·2ᵏ, up to a million roundings, where each such
    /// switch has the sign it had before (the watch keeps it, `keep`); none within reach is
    /// [`SystemError::UnlocatedSwitch`].
    fn side_before<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        point: &Point<S>,
        rate: &SVector<f64, S>,
        crossed: &[usize],
    ) -> Result<(f64, SVector<f64, S>, SVector<f64, S>), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let mut now = vec![0.0; self.values.len()];
        self.evaluate(system, point.time, &point.state, &mut now)?;
        let on_zero: Vec<usize> = crossed.iter().copied().filter(|&i| now[i] == 0.0).collect();
        if on_zero.is_empty() {
            return Ok((point.time, point.state, *rate));
        }
        for step in slivers(point.time) {
            let (time, state) = (point.time - step, point.state - rate * step);
            self.evaluate(system, time, &state, &mut now)?;
            let before = |&i: &usize| now[i] * self.values[i] > 0.0;
            if on_zero.iter().all(before) {
                return Ok((time, state, rate_at(system, time, &state)?));
            }
        }
        // The rate there would be the kink's, half the jump: never guessed.
        let switch = on_zero[0];
        let error = SystemError::UnlocatedSwitch { switch };
        Err(StepError::from_system(
            system,
            error,
            point.time,
            &point.state,
        ))
    }

    /// The first root ahead of any g along the tangent t ↦ (t, y + (t − t₀) f) from
    /// `point`, by one secant over a short difference (g values `before` there); 0 for a
    /// switch that stands on zero there and leaves the side it came from.
    fn tangent_root<Sys, const N: usize, const S: usize>(
        &self,
        system: &Sys,
        point: &Point<S>,
        rate: &SVector<f64, S>,
        before: &[f64],
    ) -> Result<Option<f64>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let h = 1e-8 * point.time.abs().max(1.0);
        let mut probe = vec![0.0; before.len()];
        self.evaluate(
            system,
            point.time + h,
            &(point.state + rate * h),
            &mut probe,
        )?;
        // A switch standing exactly on zero (the step before ended on a table's knot) whose
        // probe lies across the side it came from crosses here: its root is 0, not the −0
        // of the secant, which would leave the nearest root to another switch — a redo
        // there re-runs the step that crosses this one, found again at its start, forever
        // (the Calisto flight of issue 34 at tolerance 1e-10, on the density knot 4500 m).
        let roots = (before.iter().zip(&probe).zip(&self.values)).filter_map(
            |((&g0, &g1), &kept)| match g0 == 0.0 {
                true => changed_sign(kept, g1).then_some(0.0),
                false => Some(-g0 * h / (g1 - g0)),
            },
        );
        Ok(roots
            .filter(|root| root.is_finite() && *root >= 0.0)
            .min_by(f64::total_cmp))
    }

    /// Counts a crossing of switch `index` at `time`, failing once it chatters.
    fn count<const S: usize>(
        &mut self,
        index: usize,
        time: f64,
        state: &SVector<f64, S>,
    ) -> Result<(), StepError<S>> {
        let Some((first, crossings)) = self.bursts.get_mut(index) else {
            return Ok(());
        };
        if time - *first <= self.window {
            *crossings += 1;
        } else {
            (*first, *crossings) = (time, 1);
        }
        if *crossings >= self.settings.chatter_crossings {
            let kind = StepErrorKind::Chattering {
                switch: index,
                crossings: *crossings,
                within: time - *first,
            };
            return Err(StepError::new(time, *state, kind));
        }
        Ok(())
    }
}

/// The state rate at `(time, state)`, its failure a step error there.
fn rate_at<Sys, const N: usize, const S: usize>(
    system: &Sys,
    time: f64,
    state: &SVector<f64, S>,
) -> Result<SVector<f64, S>, StepError<S>>
where
    Sys: VariableMassSystem<N, S>,
{
    system
        .state_rate(time, state)
        .map_err(|error| StepError::from_system(system, error, time, state))
}

/// The probe steps 4ε·max(|t|, 1)·2ᵏ at `t`, from one rounding of t up to a million of
/// them: how far `leave_zero` and `side_before` look off a switch standing on zero.
fn slivers(t: f64) -> impl Iterator<Item = f64> {
    let rounding = 4.0 * f64::EPSILON * t.abs().max(1.0);
    core::iter::successors(Some(rounding), |s| Some(s * 2.0))
        .take_while(move |s| *s <= 1e6 * rounding)
}

/// Whether g went from `before` strictly to the other side of zero at `after` (a zero is
/// not yet a crossing: the state rate there is still the one before, or the kink's).
fn changed_sign(before: f64, after: f64) -> bool {
    (before < 0.0 && after > 0.0) || (before > 0.0 && after < 0.0)
}
