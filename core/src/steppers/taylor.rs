//! Taylor's method: each step expands the solution through the current state into its
//! Taylor series, y(t₀ + h) = Σₖ y\[k\] hᵏ, from the coefficients y\[k\] = y⁽ᵏ⁾(t₀)/k! the
//! system gives ([`VariableMassSystem::taylor_coefficients`]: emitted by the macro with
//! `emit = [..., "taylor"]`, or the run-time tapes of a model file), computed by automatic
//! differentiation (Jorba & Zou 2005; Biscani & Izzo 2021).
//!
//! Order and step come from the tolerance as in Jorba & Zou (2005, §3.2, eqs. 3.9–3.12):
//! with ε = atol when rtol‖y‖∞ ≤ atol (absolute) and ε = rtol otherwise (relative),
//!
//! * the order p = ⌈−½ ln ε + 1⌉, so that the step below makes the truncation error
//!   about ε;
//! * the step h = min(ρₚ₋₁, ρₚ) e⁻² e^(−0.7/(p−1)) with ρⱼ = (1/‖y\[j\]‖∞)^(1/j)
//!   (absolute) or (‖y‖∞/‖y\[j\]‖∞)^(1/j) (relative): the radius of convergence estimated
//!   from the last two coefficients, times J&Z's safety factor.
//!
//! There is no error estimate to reject a step against: the step is chosen before it is
//! taken, so steps are rejected only when their result is unusable. The dense output is the
//! series itself, exact to the method's order over the whole step, so events are located on
//! it. A fixed order and step ([`TaylorControl::Fixed`]) serve convergence studies.
//!
//! Rounding is kept from accumulating over many steps in two ways. The state advances by
//! compensated summation: the increment Σₖ₌₁ y\[k\] hᵏ is added to the state by Knuth's
//! two-sum, and the part of it rounding drops is carried into the next step's increment
//! (Kahan's compensated summation; dropped when the run restarts). And the step the series
//! is evaluated at is the one the clock takes, h = (t₀ + h) − t₀ (exact when t₀ and
//! t₀ + h are within a factor 2 of each other, Sterbenz), so the state belongs to the time
//! stored beside it. Over 400 steps of Kepler at order 30 the two together cut the error
//! against the nominal orbit from 7.6e-14 to a few 1e-14 (`tests/taylor_rounding.rs`, whose
//! reference is the orbit through the start as stored: the start's own rounding moves the
//! end point by 8e-15). What is left is the rounding of the first two coefficients, the
//! rate c₁ = f(y) and c₂ = ½ f′(y) f(y), to a few ulps at every step: over 16 starts near
//! Kepler's (e ≈ 0.5, three orbits) the stepper ends 2.0e-14 rms off at tolerance 1e-14 and
//! at 1e-15 (1.3e-14 at 1e-16, when it was accepted), against 1.2e-16 were c₁ and c₂
//! computed in double-double, 9e-17 for truncation, 1.0e-14 with a double-double state and
//! sum, 1.2e-14 with the carried part fed into the next c₁ (a harness mirroring the
//! stepper, `tests/kepler_floor.rs`). No summation removes it, and finer tolerances do not
//! lower it: below 1e-15 ([`Floor::Taylor`]) the stepper refuses them.
//!
//! The head ([`Taylor::with_head`], opt-in) removes it: c₁ and c₂ come from the system's
//! state rate evaluated over double-double dual numbers ([`crate::dd`];
//! [`VariableMassSystem::taylor_head`], emitted with `emit = [..., "taylor", "head"]` for
//! models whose state rate is arithmetic, √, ∛ and integer powers) at y_hi + y_lo, the
//! state and its compensation, and the increment c₁h + c₂h² + Σₖ≥₃ cₖhᵏ is added in
//! double-double (the tail Σₖ≥₃ in double: multiplied by h³ and more, its rounding is far
//! below the state's ulp); the state keeps the sum's high part and the compensation its low
//! part. Order and steps are unchanged (the coefficients from c₃ on, and the step rule,
//! are the double expansion's). Kepler at tolerance 2.2e-16, the head's floor
//! ([`Floor::TaylorHead`]): 2.4e-16 against the exact orbit through the stored start,
//! 1.3e-14 without at the double floor 1e-15 (`tests/kepler_floor.rs`). Run-time
//! models (the interpreter's tapes, `varmass run --method taylor`) have no head: their
//! tapes evaluate in `f64` only, so they keep the double floor.
//!
//! The statistics count one rate evaluation per expansion (the work of an expansion to
//! order p is about p²/2 products per subexpression, against one evaluation's one).
//! Piecewise functions (abs, sign, min, max) are expanded on the branch of the step's start
//! (abs, min, max at a tie: the branch that holds just after, `varmass_table::recurrence`):
//! their switches must be located by events, so that no step straddles one.

#[path = "taylor/head.rs"]
mod head;
#[path = "taylor/series.rs"]
pub mod series;

use nalgebra::SVector;

use crate::dd::Dual;
use crate::error::{ConfigError, StepError, StepErrorKind};
use crate::math::{ceil, exp, ln, powf};
use crate::scratch::Scratch;
use crate::stepper::{Progress, ProgressMut, Restarting, StepOutcome, Stepper};
use crate::system::VariableMassSystem;
use crate::tolerance::{Floor, Tolerance};

pub use crate::scratch::MAX_ORDER;

/// How the Taylor stepper chooses its order and steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TaylorControl {
    /// Order and step from the tolerance (Jorba & Zou 2005, §3.2): ε is its absolute part
    /// when rtol‖y‖∞ ≤ atol, its relative part otherwise. Its relative part must be at
    /// least the stepper's [`Floor`]: [`Floor::Taylor`] (1e-15) for [`Taylor::new`],
    /// [`Floor::TaylorHead`] (2.2e-16) for [`Taylor::with_head`].
    Adaptive {
        /// The tolerance (build one below 100 ε with [`Tolerance::for_floor`]).
        tolerance: Tolerance,
        /// The largest step allowed.
        max_step: f64,
    },
    /// A fixed order p (1 ≤ p ≤ [`MAX_ORDER`]) and step h, for convergence studies.
    Fixed {
        /// The order p.
        order: usize,
        /// The step h > 0.
        step: f64,
    },
}

impl TaylorControl {
    /// Adaptive control with this tolerance and no step limit.
    pub fn adaptive(tolerance: Tolerance) -> Self {
        Self::Adaptive {
            tolerance,
            max_step: f64::INFINITY,
        }
    }

    /// Checks the settings against the stepper's `floor`.
    fn validated(self, floor: Floor) -> Result<Self, ConfigError> {
        let ok = match self {
            Self::Adaptive {
                tolerance,
                max_step,
            } => {
                floor.check(tolerance.relative())?;
                max_step > 0.0
            }
            Self::Fixed { order, step } => {
                (1..=MAX_ORDER).contains(&order) && step.is_finite() && step > 0.0
            }
        };
        if ok {
            Ok(self)
        } else {
            Err(ConfigError {
                reason: "Taylor control: max_step positive; a fixed order in 1..=32 and a \
                         positive finite step",
            })
        }
    }
}

impl Default for TaylorControl {
    /// The tolerances of the other adaptive steppers' defaults: 1e-6 relative, 1e-9 absolute.
    fn default() -> Self {
        Self::adaptive(Tolerance::new(1e-6, 1e-9).expect("1e-6 and 1e-9 are usable"))
    }
}

/// The Taylor stepper on the state `[q, p, m_s]`.
#[derive(Clone, Debug)]
pub struct Taylor<'a, Sys, const N: usize, const S: usize> {
    system: &'a Sys,
    progress: Progress<S>,
    control: TaylorControl,
    /// The series of the last step (about its start), y\[0\] … y\[order\].
    coefficients: [SVector<f64, S>; MAX_ORDER + 1],
    order: usize,
    last_step: f64,
    /// What rounding dropped from the state in the last step's sum (compensated summation).
    compensation: SVector<f64, S>,
    /// The order and safety factor of adaptive control, absolute (`[0]`) and relative
    /// (`[1]`): fixed by the tolerances, so computed once (a logarithm and an exponential
    /// per step were a tenth of the sled's step).
    rules: [(usize, f64); 2],
    /// The expansions' working memory, kept from step to step.
    scratch: Scratch,
    /// Whether c₁ and c₂ come from the system's double-double head ([`Taylor::with_head`]).
    head: bool,
}

impl<'a, Sys, const N: usize, const S: usize> Taylor<'a, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// Starts at `(time, state)`, every coefficient in double; the state and the control
    /// (its tolerance against [`Floor::Taylor`]) are checked, and the system must provide
    /// Taylor coefficients (otherwise an
    /// [`InvalidConfiguration`](StepErrorKind::InvalidConfiguration) error says how to get
    /// them).
    pub fn new(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        control: TaylorControl,
    ) -> Result<Self, StepError<S>> {
        Self::checked(system, (time, state), control.validated(Floor::Taylor))
    }

    /// Starts as [`Taylor::new`] with its head: c₁ and c₂ from the system's state rate
    /// evaluated in double-double dual numbers ([`VariableMassSystem::taylor_head`],
    /// emitted with `emit = [..., "taylor", "head"]`) at the state and its compensation
    /// y_hi + y_lo, and the increment c₁h + c₂h² + Σₖ≥₃ cₖhᵏ added in double-double (see
    /// the module docs: what it buys and costs). The tolerance is checked against the
    /// head's floor, [`Floor::TaylorHead`]. An
    /// [`InvalidConfiguration`](StepErrorKind::InvalidConfiguration) error when the
    /// system has no head.
    pub fn with_head(
        system: &'a Sys,
        time: f64,
        state: SVector<f64, S>,
        control: TaylorControl,
    ) -> Result<Self, StepError<S>> {
        let control = control.validated(Floor::TaylorHead);
        let mut stepper = Self::checked(system, (time, state), control)?;
        let probe = core::array::from_fn(|i| Dual::from(state[i]));
        if system.taylor_head(Dual::from(time), &probe).is_none() {
            return Err(StepError::invalid_configuration(
                time,
                state,
                "the system has no double-double head (generate it with \
                 emit = [..., \"taylor\", \"head\"])",
            ));
        }
        stepper.head = true;
        Ok(stepper)
    }

    /// The stepper at `(time, state)` with `control` as its check left it, once the state
    /// is checked and the system shows that it provides Taylor coefficients.
    fn checked(
        system: &'a Sys,
        (time, state): (f64, SVector<f64, S>),
        control: Result<TaylorControl, ConfigError>,
    ) -> Result<Self, StepError<S>> {
        let control = control.map_err(|e| e.at(time, &state))?;
        let progress = Progress::new(system, time, state)?;
        let mut stepper = Self::assembled(system, progress, control, rules(control));
        let probe = &mut stepper.coefficients[..2];
        match system.taylor_coefficients(time, &state, probe, &mut stepper.scratch) {
            None => Err(StepError::invalid_configuration(
                time,
                state,
                "the system provides no Taylor coefficients (generate them with \
                 emit = [..., \"taylor\"]; with sensitivities the recurrences need a \
                 tangent form: q' in closed form, and for generated code no tables, \
                 inputs or switches)",
            )),
            Some(Err(error)) => Err(StepError::from_system(system, error, time, &state)),
            Some(Ok(())) => Ok(stepper),
        }
    }

    /// A member's stepper in a run in lanes: [`Taylor::new`]'s, with the run's `rules`
    /// (`rules(control)`, computed once) and without the probe expansion that shows the
    /// system provides coefficients. The lanes showed that once for every member
    /// (`lanes/taylor.rs`), and the probe's one error, a singular mass matrix, makes a
    /// lane's expansion non-finite, which expands the member here alone
    /// ([`Self::expanded_elsewhere`]) and flies it again on the scalar path: the scalar
    /// run's error is the member's either way.
    pub(crate) fn in_lanes(
        system: &'a Sys,
        (time, state): (f64, SVector<f64, S>),
        control: TaylorControl,
        rules: [(usize, f64); 2],
    ) -> Result<Self, StepError<S>> {
        let validated = control.validated(Floor::Taylor);
        let control = validated.map_err(|e| e.at(time, &state))?;
        let progress = Progress::new(system, time, state)?;
        Ok(Self::assembled(system, progress, control, rules))
    }

    /// The stepper of checked parts, before its first step.
    fn assembled(
        system: &'a Sys,
        progress: Progress<S>,
        control: TaylorControl,
        rules: [(usize, f64); 2],
    ) -> Self {
        Self {
            system,
            progress,
            control,
            coefficients: [SVector::zeros(); MAX_ORDER + 1],
            order: 0,
            last_step: 0.0,
            compensation: SVector::zeros(),
            rules,
            scratch: Scratch::new(),
            head: false,
        }
    }

    /// Whether the stepper uses the system's double-double head.
    pub fn has_head(&self) -> bool {
        self.head
    }

    /// The order of the last step (0 before the first).
    pub fn order(&self) -> usize {
        self.order
    }

    /// The series of the last step at `time` (the current state before the first step).
    pub fn interpolate(&self, time: f64) -> SVector<f64, S> {
        // The end of the step is the accepted state exactly (t₁ − t₀ may differ from h in
        // the last bit).
        if self.last_step <= 0.0 || time == self.progress.time() {
            return *self.progress.state();
        }
        horner(
            &self.coefficients[..=self.order],
            time - self.progress.previous_time(),
        )
    }

    /// Jorba & Zou's step from the last two coefficients of an expansion to `order`, with
    /// the safety factor `safety`.
    fn adaptive_step(
        &self,
        (order, safety): (usize, f64),
        relative_mode: bool,
        max_step: f64,
    ) -> f64 {
        let block = self.system.measured_block();
        if block > 0 && block < S {
            return self.blockwise_step((order, safety), relative_mode, max_step, block);
        }
        let scale = if relative_mode {
            self.progress.state().amax()
        } else {
            1.0
        };
        let radius = |j: usize| powf(scale / self.coefficients[j].amax(), 1.0 / j as f64);
        // min(ρₚ₋₁, ρₚ) as exp(min(ln ρₚ₋₁, ln ρₚ)): two logarithms and an exponential
        // cost less than two powers (a seventh of the sled's step, issue 38), and agree with
        // them to about |ln x| ε/j relative (a few ulps for moderate ρ, 2.5e-14 at x = 1e-200
        // and j = 2: harmless under the safety factor e⁻²; 0 and ∞ included: ln 0 = −∞,
        // ln ∞ = ∞; near 1.7e308 at order 2 exp(ln x) may round to ∞ where the power did
        // not, which takes the lower orders' branch below). Times 1/j, which
        // waits on nothing, not over j, which would wait on the logarithm.
        let log_radius = |j: usize| {
            let inverse = 1.0 / j as f64;
            ln(scale / self.coefficients[j].amax()) * inverse
        };
        let mut rho = exp(log_radius(order - 1).min(log_radius(order)));
        if rho.is_infinite() {
            // The last two coefficients vanish: the lower ones bound the radius.
            rho = (1..order - 1).map(radius).fold(f64::INFINITY, f64::min);
        }
        let step = rho * safety;
        if step.is_finite() {
            step.min(max_step)
        } else if max_step.is_finite() {
            // A constant solution: any step is exact.
            max_step
        } else {
            1.0 + self.progress.time().abs()
        }
    }

    /// Expands the solution at the current point to `order`.
    fn expand(&mut self, order: usize) -> Result<(), StepError<S>> {
        let (t0, y0) = (self.progress.time(), *self.progress.state());
        self.progress.statistics.rate_evaluations += 1;
        let result = self.system.taylor_coefficients(
            t0,
            &y0,
            &mut self.coefficients[..=order],
            &mut self.scratch,
        );
        match result {
            Some(Ok(())) => {}
            Some(Err(error)) => return Err(StepError::from_system(self.system, error, t0, &y0)),
            None => {
                return Err(StepError::invalid_configuration(
                    t0,
                    y0,
                    "the system stopped providing Taylor coefficients",
                ))
            }
        }
        let finite = self.coefficients[..=order]
            .iter()
            .all(|c| c.iter().all(|x| x.is_finite()));
        if finite {
            Ok(())
        } else {
            Err(StepError::new(t0, y0, StepErrorKind::NonFiniteState))
        }
    }
}

/// The order and safety factor of `control`'s adaptive rule, absolute (`[0]`) and relative
/// (`[1]`); `[(2, 0.0); 2]` for fixed steps (unread).
pub(crate) fn rules(control: TaylorControl) -> [(usize, f64); 2] {
    match control {
        TaylorControl::Adaptive { tolerance, .. } => {
            [rule(tolerance.absolute()), rule(tolerance.relative())]
        }
        TaylorControl::Fixed { .. } => [(2, 0.0); 2],
    }
}

/// The order p = ⌈−½ ln ε + 1⌉ for the tolerance ε and J&Z's safety factor
/// e⁻² e^(−0.7/(p−1)) (eqs. 3.9–3.12).
fn rule(epsilon: f64) -> (usize, f64) {
    let order = ceil(-0.5 * ln(epsilon) + 1.0);
    let order = if order.is_finite() && epsilon > 0.0 {
        (order as usize).clamp(2, MAX_ORDER)
    } else {
        2
    };
    (order, exp(-2.0 - 0.7 / (order - 1) as f64))
}

/// `y0 + Σₖ₌₁ cₖ hᵏ + carried`, the increment summed by Horner's rule and added to `y0` by
/// Knuth's two-sum; the new state and what rounding dropped from it.
fn compensated_sum<const S: usize>(
    y0: &SVector<f64, S>,
    coefficients: &[SVector<f64, S>],
    h: f64,
    carried: &SVector<f64, S>,
) -> (SVector<f64, S>, SVector<f64, S>) {
    let increment = split_horner(coefficients, h);
    let mut sum = SVector::zeros();
    let mut dropped = SVector::zeros();
    for i in 0..S {
        let (a, b) = (y0[i], increment[i] + carried[i]);
        let s = a + b;
        let b_virtual = s - a;
        let a_virtual = s - b_virtual;
        sum[i] = s;
        dropped[i] = (a - a_virtual) + (b - b_virtual);
    }
    (sum, dropped)
}

/// Σₖ₌₁ cₖ hᵏ = h (O + h E), O = Σ c₂ᵢ₊₁ h²ⁱ and E = Σ c₂ᵢ₊₂ h²ⁱ each by Horner's rule in
/// h²: two chains of p/2 dependent steps where one Horner's rule in h is a chain of p,
/// and the next expansion waits on this sum (the sled's step 5 % faster, issue 38). Each
/// chain's rounding is Horner's; the increment is dominated by c₁h in any case.
fn split_horner<const S: usize>(coefficients: &[SVector<f64, S>], h: f64) -> SVector<f64, S> {
    let Some(mut k) = coefficients.len().checked_sub(1).filter(|&p| p > 0) else {
        return SVector::zeros();
    };
    let h2 = h * h;
    let mut odd = SVector::<f64, S>::zeros();
    let mut even = SVector::<f64, S>::zeros();
    if k % 2 == 0 {
        even = coefficients[k];
        k -= 1;
    }
    // k is odd from here: the pairs (k, k − 1) down to (3, 2), then c₁.
    while k >= 3 {
        odd = odd * h2 + coefficients[k];
        even = even * h2 + coefficients[k - 1];
        k -= 2;
    }
    odd = odd * h2 + coefficients[1];
    (odd + even * h) * h
}

/// Σₖ cₖ hᵏ by Horner's rule.
fn horner<const S: usize>(coefficients: &[SVector<f64, S>], h: f64) -> SVector<f64, S> {
    let mut value = SVector::zeros();
    for c in coefficients.iter().rev() {
        value = value * h + c;
    }
    value
}

impl<Sys, const N: usize, const S: usize> Stepper<N, S> for Taylor<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    type System = Sys;

    fn parts(&self) -> (&Sys, &Progress<S>) {
        (self.system, &self.progress)
    }

    fn parts_mut(&mut self) -> ProgressMut<'_, Sys, S> {
        ProgressMut::new(self.system, &mut self.progress)
    }

    fn forget_history(&mut self, _: Restarting) {
        self.last_step = 0.0;
        self.compensation = SVector::zeros();
    }

    fn dense_output(&self, time: f64) -> Option<SVector<f64, S>> {
        Some(self.interpolate(time))
    }

    fn step(&mut self) -> Result<StepOutcome, StepError<S>> {
        let plan = self.plan();
        self.expand(plan.order)?;
        self.take_step(plan)
    }
}

/// What a step expands to before it is taken: the order, and for adaptive control whether
/// the step rule is relative.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Plan {
    pub(crate) order: usize,
    relative_mode: bool,
}

impl<Sys, const N: usize, const S: usize> Taylor<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// The order of the next step's expansion: fixed, or the absolute or relative rule's
    /// (relative when rtol‖y‖∞ > atol: J&Z's ε is then rtol).
    pub(crate) fn plan(&self) -> Plan {
        match self.control {
            TaylorControl::Fixed { order, .. } => Plan {
                order,
                relative_mode: false,
            },
            TaylorControl::Adaptive { tolerance, .. } => {
                let block = self.system.measured_block().min(S);
                let size = self.progress.state().rows(0, block).amax();
                let relative_mode = tolerance.relative() * size > tolerance.absolute();
                Plan {
                    order: self.rules[usize::from(relative_mode)].0,
                    relative_mode,
                }
            }
        }
    }

    /// The expansion of the next step made elsewhere (in lanes): coefficient k is
    /// `coefficient(k)`, k ≤ `order`, counted and checked as [`Self::expand`] counts and
    /// checks its own. Where one is not finite the member is expanded again here, alone,
    /// for the scalar expansion's own error (a singular mass matrix, say).
    pub(crate) fn expanded_elsewhere(
        &mut self,
        order: usize,
        coefficient: impl Fn(usize) -> SVector<f64, S>,
    ) -> Result<(), StepError<S>> {
        let mut finite = true;
        for (k, c) in self.coefficients[..=order].iter_mut().enumerate() {
            *c = coefficient(k);
            finite &= c.iter().all(|x| x.is_finite());
        }
        if !finite {
            return self.expand(order);
        }
        self.progress.statistics.rate_evaluations += 1;
        Ok(())
    }

    /// The step from the expansion to `plan`'s order now in the coefficients: its size by
    /// the control, the series summed, the new state accepted.
    pub(crate) fn take_step(&mut self, plan: Plan) -> Result<StepOutcome, StepError<S>> {
        let t0 = self.progress.time();
        let order = plan.order;
        let nominal = match self.control {
            TaylorControl::Fixed { step, .. } => step,
            TaylorControl::Adaptive { max_step, .. } => {
                let rule = self.rules[usize::from(plan.relative_mode)];
                self.adaptive_step(rule, plan.relative_mode, max_step)
            }
        };
        let (h, reaches_stop) = self.progress.next_step(nominal)?;
        if !(h > 0.0 && t0 + h != t0) {
            let state = *self.progress.state();
            return Err(StepError::new(
                t0,
                state,
                StepErrorKind::StepSizeUnderflow { step: h },
            ));
        }
        // The step the clock takes: the series is summed at the time stored with the state.
        let h = if reaches_stop { h } else { (t0 + h) - t0 };
        let y0 = *self.progress.state();
        let (state, dropped) = if self.head {
            self.head_sum(order, h)?
        } else {
            compensated_sum(&y0, &self.coefficients[..=order], h, &self.compensation)
        };
        let outcome = self.progress.accept(self.system, h, reaches_stop, state)?;
        self.compensation = dropped;
        self.order = order;
        self.last_step = h;
        Ok(outcome)
    }
}

impl<Sys, const N: usize, const S: usize> Taylor<'_, Sys, N, S>
where
    Sys: VariableMassSystem<N, S>,
{
    /// [`Self::adaptive_step`] over a state of blocks of `block` entries
    /// ([`VariableMassSystem::measured_block`]: forward sensitivities' state and columns),
    /// those the error control weighs ([`VariableMassSystem::controlled_entries`]): each
    /// block's radius from its own coefficients, held to its own tolerance
    /// max(rtol ‖y_b‖, atol) (a column of size 10⁶ to rtol of it, one still 0 to atol): the
    /// scale is that tolerance over the mode's ε, so the first block's is `adaptive_step`'s
    /// (‖y‖ relative, 1 absolute). A block whose last two coefficients vanish bounds nothing;
    /// if none bounds the step, the first block's lower orders do, as in `adaptive_step`.
    /// That assumes such a block's series is exact over the step (a column polynomial in t,
    /// ∂m/∂μ = −t; or identically 0): two consecutive coefficients of every entry of a
    /// block vanish exactly by structure, not by a coincidence of the point (an extremum
    /// zeroes one coefficient of one entry). The step the smallest radius allows.
    fn blockwise_step(
        &self,
        (order, safety): (usize, f64),
        relative_mode: bool,
        max_step: f64,
        block: usize,
    ) -> f64 {
        let controlled = self.system.controlled_entries().clamp(block.min(S), S);
        let (rtol, atol) = match self.control {
            TaylorControl::Adaptive { tolerance, .. } => {
                (tolerance.relative(), tolerance.absolute())
            }
            TaylorControl::Fixed { .. } => (0.0, 1.0),
        };
        let state = self.progress.state();
        let norm =
            |v: &SVector<f64, S>, first: usize| v.rows(first, block.min(controlled - first)).amax();
        // A block held to a tolerance of 0 (rtol alone, the block still 0) bounds nothing
        // yet: its scale is infinite, as a block whose coefficients vanish.
        let scale = |first: usize| {
            let size = norm(state, first);
            let relative = rtol * size > atol;
            match (relative_mode, relative) {
                (true, true) => size,
                (_, false) if atol == 0.0 => f64::INFINITY,
                (true, false) => atol / rtol,
                (false, true) => size * (rtol / atol),
                (false, false) => 1.0,
            }
        };
        // Each block's scale once; its radius as `adaptive_step` computes it (the same
        // bits for one block).
        let bounded = (0..controlled).step_by(block.max(1)).map(|first| {
            let scale = scale(first);
            let log_radius = |j: usize| {
                let inverse = 1.0 / j as f64;
                ln(scale / norm(&self.coefficients[j], first)) * inverse
            };
            exp(log_radius(order - 1).min(log_radius(order)))
        });
        let mut rho = bounded.fold(f64::INFINITY, f64::min);
        if rho.is_infinite() {
            let scale = scale(0);
            let radius = |j: usize| powf(scale / norm(&self.coefficients[j], 0), 1.0 / j as f64);
            rho = (1..order - 1).map(radius).fold(f64::INFINITY, f64::min);
        }
        let step = rho * safety;
        if step.is_finite() {
            step.min(max_step)
        } else if max_step.is_finite() {
            max_step
        } else {
            1.0 + self.progress.time().abs()
        }
    }
}
