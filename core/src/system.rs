//! The trait a variable-mass system implements (by the `#[variable_mass_system]` macro, or by
//! hand), in the paper's language.
//!
//! Two vectors of the same shape appear throughout:
//!
//! * the **state** `[q, p, m_s]` — coordinates, momenta p = ∂*L/∂q̇ (eq. 8) and the state
//!   masses; this is what the steppers integrate;
//! * the **velocity state** `[q, q̇, m_s]` — the same with velocities in place of momenta;
//!   the Lagrange-side functions take it.
//!
//! A system with `N` coordinates and `K` state masses has `S = 2N + K`; a system with
//! sampled inputs carries their held values after the masses, `S = 2N + K + HELD`
//! ([`VariableMassSystem::HELD`]).
//!
//! The required methods are the Lagrange side, which a person can write by hand for a small
//! system; everything else (q̇(q, p), H, the canonical equations, the true state rate, the
//! energy-budget power, the Jacobian) has a default built from them, which generated code
//! replaces with specialised formulas.

use nalgebra::{SMatrix, SVector};

pub use crate::cholesky::{regular_pivot, RELATIVE_PIVOT_FLOOR};
pub use crate::error::SystemError;
use crate::error::{is_finite, StepError, StepErrorKind};
use crate::input::Sampling;

/// ε^(1/3), the step of a central difference that balances truncation against rounding.
/// A literal because `f64::powf` is not available without `std`.
const CBRT_EPSILON: f64 = 6.055_454_452_393_343e-6;

/// The Jacobian of `rate` at `(t, state)` by central differences, step ∛ε·max(|yⱼ|, 1):
/// [`VariableMassSystem::jacobian`]'s default, and the fallback of a system whose symbolic
/// Jacobian is optional (the interpreter's).
pub fn central_jacobian<const S: usize>(
    t: f64,
    state: &SVector<f64, S>,
    rate: impl Fn(f64, &SVector<f64, S>) -> Result<SVector<f64, S>, SystemError>,
) -> Result<SMatrix<f64, S, S>, SystemError> {
    let mut jacobian = SMatrix::<f64, S, S>::zeros();
    let mut probe = *state;
    for j in 0..S {
        let h = CBRT_EPSILON * state[j].abs().max(1.0);
        probe[j] = state[j] + h;
        let forward = rate(t, &probe)?;
        probe[j] = state[j] - h;
        let backward = rate(t, &probe)?;
        probe[j] = state[j];
        jacobian.set_column(j, &((forward - backward) / (2.0 * h)));
    }
    Ok(jacobian)
}

/// A holonomic variable-mass system in the sense of Zhang Jiuzhu (2015): generalized
/// coordinates q, frozen masses mᵢ(q, t) or state masses, a Lagrangian L = T − V, and
/// generalized forces Q* (active, non-potential), R1 (reactive thrust) and R2 (impact).
///
/// `N` is the number of coordinates, `S = 2N + K (+ HELD)` the state dimension with `K`
/// state masses (and [`Self::HELD`] held inputs).
pub trait VariableMassSystem<const N: usize, const S: usize> {
    /// Names of the generalized coordinates, in state order.
    const COORDINATES: [&'static str; N];
    /// Names of every frozen mass and inertia. The first [`Self::STATE_MASSES`] are the state masses, in
    /// state order; the rest follow laws m(q, t).
    const MASSES: &'static [&'static str];

    /// The number of held values of sampled inputs (`input u(…) every T`,
    /// docs/inputs.md#sampled-inputs), the last entries of the state, after the state
    /// masses: `S = 2N + K + HELD`. Their rate is 0; a run replaces them at each sample
    /// time through [`Self::sample`]. None by default.
    const HELD: usize = 0;

    /// The number of state masses, `K = S − 2N − HELD`.
    const STATE_MASSES: usize = S - 2 * N - Self::HELD;

    /// The value of mass `index` (into [`Self::MASSES`]) at time `t`. Only q and the state
    /// masses of `state` are read, so either a state or a velocity state may be passed.
    fn mass(&self, index: usize, t: f64, state: &SVector<f64, S>) -> f64;

    /// ṁ of mass `index` along the motion, at the velocity state `velocity_state`: for a
    /// state mass its declared rate, for a law m(q, t) its total time derivative.
    fn mass_rate(&self, index: usize, t: f64, velocity_state: &SVector<f64, S>) -> f64;

    /// The mass matrix M = ∂²L/∂q̇², with masses frozen. Reads q and the state masses only.
    fn mass_matrix(&self, t: f64, state: &SVector<f64, S>) -> SMatrix<f64, N, N>;

    /// The generalized momenta p = ∂*L/∂q̇ (eq. 8) at a velocity state.
    fn momenta(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;

    /// The Lagrangian L = T − V at a velocity state.
    fn lagrangian(&self, t: f64, velocity_state: &SVector<f64, S>) -> f64;

    /// ∂*L/∂q at a velocity state: the partial with masses frozen (−∂*H/∂q, eq. 13).
    fn lagrangian_gradient(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;

    /// The generalized active (non-potential) force Q*.
    fn active_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;

    /// The generalized reactive thrust R1 = Σᵢ Q1ᵢ v_r1ᵢ · ∂rᵢ/∂q.
    fn reactive_thrust(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;

    /// The generalized impact force R2 = Σᵢ Q2ᵢ v_r2ᵢ · ∂rᵢ/∂q.
    fn impact_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;

    /// The mass-flux term Σᵢ ṁᵢ ∂*p/∂mᵢ that turns d*p/dt into the true ṗ (docs/mechanics.md#true-momentum-rate).
    fn mass_flux_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N>;

    /// Lagrange-form accelerations q̈(q, q̇, t), from eq. 6 with the frozen-mass rule:
    /// M q̈ = ∂*L/∂q − ∂*p/∂q · q̇ − ∂*p/∂t + Q* − R1 + R2.
    fn accelerations(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> Result<SVector<f64, N>, SystemError>;

    // ---------------------------------------------------------------- provided methods

    /// The number of switching functions: the non-smooth points of the state rate
    /// (docs/mechanics.md#switches). None by default; generated systems count the arguments
    /// of `sign` and `abs` and the sides of `min` and `max` in their equations.
    fn switch_count(&self) -> usize {
        0
    }

    /// The text of switching function `index` (its DSL expression), for messages.
    fn switch_name(&self, _index: usize) -> Option<&str> {
        None
    }

    /// Writes the switching functions g(t, q, q̇, m_s) at a velocity state into `values`
    /// (of length [`Self::switch_count`]). A run lands on every sign change and restarts
    /// the stepper there, so that no step straddles a jump or a kink.
    fn switching_functions(&self, _t: f64, _velocity_state: &SVector<f64, S>, _values: &mut [f64]) {
    }

    /// Sets the anchors of the switches whose function depends on where the run is
    /// (`anchors` of length [`Self::switch_count`]; the others are left alone): a switch at
    /// the knots of a table of the state is anchored at the knot bracket of the table's
    /// argument ([`crate::table::knot_bracket_read`]). A run sets them at its start and after
    /// every crossing. None by default.
    fn switch_anchors(&self, _t: f64, _velocity_state: &SVector<f64, S>, _anchors: &mut [f64]) {}

    /// The switching functions with the anchors a run last set by [`Self::switch_anchors`]:
    /// an anchored switch is ≥ 0 at the point it was anchored at and changes sign where
    /// the run leaves its bracket ([`crate::table::knot_gap_read`]), so that a step across
    /// several knots is a crossing too. [`Self::switching_functions`] by default, which
    /// gives an anchored switch anchored at the point itself.
    fn anchored_switching_functions(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
        _anchors: &[f64],
        values: &mut [f64],
    ) {
        self.switching_functions(t, velocity_state, values);
    }

    /// How many leading entries of the state the adaptive steppers' error control weighs:
    /// all by default; forward sensitivities without their columns' error control
    /// (`sensitivity::Sensitive::with_error_control(false)`, CVODES's `errconS = false`)
    /// weigh the state's only.
    fn controlled_entries(&self) -> usize {
        S
    }

    /// The length of the blocks of the state that the Taylor stepper's step rule measures
    /// one by one (each its own norm and scale, the step the smallest any block allows): the
    /// whole state by default; forward sensitivities measure the mechanics' state and each
    /// column apart (`sensitivity::Sensitive`), so that a column that grows large does not
    /// loosen the state's tolerance.
    fn measured_block(&self) -> usize {
        S
    }

    /// Whether [`Self::switch_gradient`] gives the switches' gradients (what forward
    /// sensitivities need to move a switch's time with a parameter, `sensitivity::Sensitive`).
    /// `false` by default; a run-time model derived with sensitivities has them.
    fn has_switch_gradients(&self) -> bool {
        false
    }

    /// The gradient of switching function `index` at a velocity state,
    /// `[g_t, g_q, g_q̇, g_{m_s}, g_θ]` into `out` (1 + 2N + state masses + the
    /// [`Self::parameter_names`] count entries; total derivatives, the mass laws followed).
    /// An anchored switch's is its argument's: g = ±(argument − knot) near a crossing, and
    /// its sign cancels in the time's derivative. `Ok(false)` when the system has none, the
    /// default.
    fn switch_gradient(
        &self,
        _index: usize,
        _t: f64,
        _velocity_state: &SVector<f64, S>,
        _out: &mut [f64],
    ) -> Result<bool, SystemError> {
        Ok(false)
    }

    /// Where a run crossed the switches `crossed` from `before` (its time, state and state
    /// rate there, on the side the run came from) to `after` (the far end of the crossing,
    /// by one Euler step over rounding): a system whose state carries more than the motion
    /// moves it there — forward sensitivities jump by (f⁻ − f⁺) dτ/dw
    /// (`sensitivity::Sensitive`). Nothing by default.
    fn cross_switches(
        &self,
        _crossed: &[usize],
        _before: (f64, &SVector<f64, S>, &SVector<f64, S>),
        _after: (f64, &mut SVector<f64, S>),
    ) -> Result<(), SystemError> {
        Ok(())
    }

    /// Where a phase of this system ends at `(t, state)` at an event that moves as `end`
    /// says (an event on a coordinate, a momentum or a state mass, a rail's exit, a
    /// lift-off): what a state carrying more than the motion (forward sensitivities,
    /// `sensitivity/phases.rs`) hands to the next phase's system ([`Self::arrive`]). `None`
    /// for a system without such entries, the default.
    fn depart(
        &self,
        _t: f64,
        _state: &SVector<f64, S>,
        _end: &crate::departure::PhaseEnd<'_>,
    ) -> Option<Result<crate::departure::Departure, SystemError>> {
        None
    }

    /// Where a phase of this system begins at `(t, state)`, the motion already carried into
    /// `state` (q̇ continuous, or p with `keep_momenta`: a capture), from what the phase
    /// before handed over ([`Self::depart`]): the entries past the motion set. `reset` are
    /// the state entries the phase sets to constants (its state masses). `None` for a
    /// system without such entries, the default.
    fn arrive(
        &self,
        _t: f64,
        _state: &mut SVector<f64, S>,
        _departure: &crate::departure::Departure,
        _keep_momenta: bool,
        _reset: &[usize],
    ) -> Option<Result<(), SystemError>> {
        None
    }

    /// The first time after `after` at which the state rate is not smooth in t (a knot of a
    /// table of t, a sample of a held input), which runs land on exactly and restart at.
    /// None by default.
    fn next_stop_time(&self, _after: f64) -> Option<f64> {
        None
    }

    /// Replaces the held values of the sampled inputs (the last [`Self::HELD`] entries of
    /// `state`) that `which` takes by the inputs' values at `(t, state)`: a zero-order hold
    /// samples here (docs/inputs.md#sampled-inputs). An input is sampled on its own grid
    /// only: with [`Sampling::Due`] its entry is replaced only when t = k·T of its period T
    /// ([`crate::input::is_sample_time`]), and left as it is at any other stop time (a knot
    /// of a table of t, another input's sample); [`Sampling::All`] replaces every entry (a
    /// run's start). A run calls it at its start time and at every stop time it lands on
    /// (the sample times are among [`Self::next_stop_time`]), never inside a step. Nothing
    /// by default (no sampled inputs).
    fn sample(
        &self,
        _t: f64,
        _state: &mut SVector<f64, S>,
        _which: Sampling,
    ) -> Result<(), SystemError> {
        Ok(())
    }

    /// The angle, rad, from the nearest singular attitude of the system's Euler sequences at
    /// `(t, state)` ([`crate::math::singular_attitude_distance`]), which a run records its
    /// closest approach to (`Solution::closest_singular_attitude`); `None` (the default) for
    /// a system without spatial rigid bodies.
    fn singular_attitude_distance(&self, t: f64, state: &SVector<f64, S>) -> Option<f64> {
        let _ = (t, state);
        None
    }

    /// The number of flows (`outflow` and `inflow` statements) whose rates a run checks.
    /// None by default; generated systems count their flows.
    fn flow_count(&self) -> usize {
        0
    }

    /// Flow `index` as the model declares it (e.g. ``inflow `cart` ``), for messages.
    fn flow_name(&self, _index: usize) -> Option<&str> {
        None
    }

    /// The rate of flow `index` (Q1 of an outflow, Q2 of an inflow, eqs. 15–16) at a
    /// velocity state, NaN past the last. It is ≥ 0 by definition (the statement says which
    /// way the mass goes), so a run ends with
    /// [`StepErrorKind::NegativeFlowRate`] at the
    /// first point where one is negative, instead of turning the reactive forces round.
    fn flow_rate(&self, _index: usize, _t: f64, _velocity_state: &SVector<f64, S>) -> f64 {
        f64::NAN
    }

    /// Q* − R1 + R2: the generalized forces of the paper's eq. 6 and 14 (what drives d*p/dt
    /// besides ∂*L/∂q).
    fn frozen_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.active_force(t, velocity_state) - self.reactive_thrust(t, velocity_state)
            + self.impact_force(t, velocity_state)
    }

    /// Q* − R1 + R2 + Σ ṁᵢ ∂*p/∂mᵢ: everything that drives the true ṗ besides ∂*L/∂q.
    fn generalized_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.frozen_force(t, velocity_state) + self.mass_flux_force(t, velocity_state)
    }

    /// Checks that every mass and inertia is positive.
    fn check_masses(&self, t: f64, state: &SVector<f64, S>) -> Result<(), SystemError> {
        for index in 0..Self::MASSES.len() {
            let mass = self.mass(index, t, state);
            // NaN fails `mass > 0.0` too, so it is rejected here as well.
            if mass.is_nan() || mass <= 0.0 {
                return Err(SystemError::NonPositiveMass { index });
            }
        }
        Ok(())
    }

    /// q̇(q, p, t): solves M q̇ = p − p(q, 0, t) (p is affine in q̇ because L is at most
    /// quadratic in the velocities).
    fn velocities(&self, t: f64, state: &SVector<f64, S>) -> Result<SVector<f64, N>, SystemError> {
        let mut at_rest = *state;
        at_rest.fixed_rows_mut::<N>(N).fill(0.0);
        let offset = self.momenta(t, &at_rest);
        let rhs = state.fixed_rows::<N>(N) - offset;
        let mass_matrix = self.mass_matrix(t, state);
        let factor = mass_matrix
            .cholesky()
            .ok_or(SystemError::SingularMassMatrix)?;
        // l_jj² is the pivot d_j (see RELATIVE_PIVOT_FLOOR).
        let l = factor.l_dirty();
        if (0..N).any(|j| !regular_pivot(l[(j, j)] * l[(j, j)], mass_matrix[(j, j)])) {
            return Err(SystemError::SingularMassMatrix);
        }
        Ok(factor.solve(&rhs))
    }

    /// The velocity state `[q, q̇, m_s]` of a state `[q, p, m_s]`.
    fn velocity_state(
        &self,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<SVector<f64, S>, SystemError> {
        let velocities = self.velocities(t, state)?;
        let mut out = *state;
        out.fixed_rows_mut::<N>(N).copy_from(&velocities);
        Ok(out)
    }

    /// The state `[q, p, m_s]` of a velocity state `[q, q̇, m_s]`.
    fn momentum_state(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, S> {
        let momenta = self.momenta(t, velocity_state);
        let mut out = *velocity_state;
        out.fixed_rows_mut::<N>(N).copy_from(&momenta);
        out
    }

    /// The Hamiltonian H(q, p, t) = p·q̇ − L with q̇ eliminated (eqs. 9–10).
    fn hamiltonian(&self, t: f64, state: &SVector<f64, S>) -> Result<f64, SystemError> {
        let velocity_state = self.velocity_state(t, state)?;
        let p = state.fixed_rows::<N>(N);
        let v = velocity_state.fixed_rows::<N>(N);
        Ok(p.dot(&v) - self.lagrangian(t, &velocity_state))
    }

    /// The canonical equations of the paper (eq. 14): `(q̇, d*p/dt)` with
    /// q̇ = ∂*H/∂p and d*p/dt = −∂*H/∂q + Q* − R1 + R2. Note d*p/dt is not the true ṗ;
    /// see [`Self::state_rate`].
    fn canonical_rates(
        &self,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<(SVector<f64, N>, SVector<f64, N>), SystemError> {
        let velocity_state = self.velocity_state(t, state)?;
        // −∂*H/∂q|_p = ∂*L/∂q|_q̇ (eq. 13).
        let frozen_rate =
            self.lagrangian_gradient(t, &velocity_state) + self.frozen_force(t, &velocity_state);
        Ok((velocity_state.fixed_rows::<N>(N).into_owned(), frozen_rate))
    }

    /// The rate of the state the steppers integrate: `[q̇, ṗ, ṁ_s]` with the true momentum rate
    /// ṗ = d*p/dt + Σᵢ ṁᵢ ∂*p/∂mᵢ.
    fn state_rate(&self, t: f64, state: &SVector<f64, S>) -> Result<SVector<f64, S>, SystemError> {
        let velocity_state = self.velocity_state(t, state)?;
        let momentum_rate = self.lagrangian_gradient(t, &velocity_state)
            + self.generalized_force(t, &velocity_state);
        let mut rate = SVector::<f64, S>::zeros();
        rate.fixed_rows_mut::<N>(0)
            .copy_from(&velocity_state.fixed_rows::<N>(N));
        rate.fixed_rows_mut::<N>(N).copy_from(&momentum_rate);
        for k in 0..Self::STATE_MASSES {
            rate[2 * N + k] = self.mass_rate(k, t, &velocity_state);
        }
        Ok(rate)
    }

    /// A body on a launch rail ([`crate::rail`], a system wrapped by `Supported::on_rail`):
    /// the net generalized force along the rail bᵀ f (the pad's lift-off function) and the
    /// distance its reference point has travelled up the rail, at `state`. `None` for every
    /// other system (the default).
    fn rail_reading(
        &self,
        _t: f64,
        _state: &SVector<f64, S>,
    ) -> Option<Result<(f64, f64), SystemError>> {
        None
    }

    /// The state rate of the free equations: [`Self::state_rate`] itself, except for a body
    /// held on its support ([`crate::support::Supported`]), whose state rate clamps the
    /// supported coordinate while this gives the rate the body would have without the
    /// support (its momentum rate is the lift-off's switching function).
    fn free_state_rate(
        &self,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<SVector<f64, S>, SystemError> {
        self.state_rate(t, state)
    }

    /// The energy-budget power dH/dt along the motion (docs/mechanics.md#energy-budget). The default differentiates
    /// H along the state rate by central differences; generated systems return the formula
    /// ∂*H/∂t + q̇·(Q* − R1 + R2 + Σ ṁᵢ ∂*p/∂mᵢ) + Σ ṁᵢ ∂H/∂mᵢ.
    fn power(&self, t: f64, state: &SVector<f64, S>) -> Result<f64, SystemError> {
        let rate = self.state_rate(t, state)?;
        let scale = state.norm().max(1.0) * (1.0 + t.abs());
        let h = CBRT_EPSILON * scale / rate.norm().max(1.0).max(scale);
        let forward = self.hamiltonian(t + h, &(state + rate * h))?;
        let backward = self.hamiltonian(t - h, &(state - rate * h))?;
        Ok((forward - backward) / (2.0 * h))
    }

    /// The Jacobian ∂(state rate)/∂(state) for implicit steppers. The default uses central
    /// differences; generated systems return the symbolic Jacobian.
    fn jacobian(&self, t: f64, state: &SVector<f64, S>) -> Result<SMatrix<f64, S, S>, SystemError> {
        central_jacobian(t, state, |t, y| self.state_rate(t, y))
    }

    /// Whether the state has entries past the mechanics (q, p, m_s, held inputs) that only
    /// the state rate evolves: forward sensitivities (`sensitivity::Sensitive`), which jump
    /// at a phase change ([`Self::depart`], [`Self::arrive`]). The variational stepper,
    /// which integrates the Lagrange side, refuses such a system at construction.
    /// `false` by default.
    fn has_rate_only_state(&self) -> bool {
        false
    }

    /// What of this system forward sensitivities cannot follow, if anything
    /// (`sensitivity::Sensitive::new` refuses it with this reason). By default every system
    /// is refused: the sensitivities need the symbolic Jacobians, which generated code
    /// gives with `emit = [..., "sensitivities"]` (and then names what it still cannot
    /// follow: inputs, a table of t whose knots move with a parameter).
    fn sensitivity_obstacle(&self) -> Option<&'static str> {
        Some("a system without the symbolic Jacobians of emit = [\"sensitivities\"]")
    }

    /// ∂(state rate)/∂θ at a fixed state `[q, p, m_s]` for the parameters θ named by
    /// [`Self::parameter_names`], row-major S × P into `out` (of length S · P): what forward
    /// sensitivities integrate with ([`crate::sensitivity`]). `Ok(false)` when the system
    /// does not provide it, the default (generated code does with `emit = [...,
    /// "sensitivities"]`).
    fn parameter_jacobian(
        &self,
        _t: f64,
        _state: &SVector<f64, S>,
        _out: &mut [f64],
    ) -> Result<bool, SystemError> {
        Ok(false)
    }

    /// The state rate over [`Tangent`](crate::tangent::Tangent)s: at `state` (values y,
    /// tangents s_c) with parameter j moved by 1 in direction c where `seeds[c] = Some(j)`,
    /// the values f and the tangents J_y s_c + ∂f/∂θ_j — forward sensitivities without a
    /// Jacobian formed ([`crate::sensitivity`]). `None` when the system has no such form, the
    /// default (generated code has one with `emit = [..., "sensitivities"]` for a state
    /// rate without tables, inputs, `sign`, `abs`, `min`, `max`, or a `powf` or `atan2` of a
    /// constant or of t alone: `emit/tangents.rs`).
    fn state_rate_tangents<const W: usize>(
        &self,
        _t: f64,
        _state: &[crate::tangent::Tangent<W>; S],
        _seeds: &[Option<usize>; W],
    ) -> Option<Result<[crate::tangent::Tangent<W>; S], SystemError>> {
        None
    }

    /// The Taylor coefficients of the solution through `(t, state)` over tangents: the
    /// expansion of [`Self::taylor_coefficients`] with the state's entries and the
    /// parameters `seeds` names moved in W directions, whose derivatives are then the
    /// Taylor coefficients of the sensitivities (`sensitivity::Sensitive` on the Taylor
    /// stepper). `None` by default (generated code has it with `emit = [..., "taylor",
    /// "sensitivities"]` where the state rate has tangents and no numeric solve of q̇).
    fn taylor_coefficients_tangents<const W: usize>(
        &self,
        _t: f64,
        _state: &[crate::tangent::Tangent<W>; S],
        _seeds: &[Option<usize>; W],
        _coefficients: &mut [[crate::tangent::Tangent<W>; S]],
        _scratch: &mut crate::scratch::Scratch<crate::tangent::Tangent<W>>,
    ) -> Option<Result<(), SystemError>> {
        None
    }

    /// [`Self::jacobian`] and the columns `wanted` of [`Self::parameter_jacobian`]
    /// (increasing indices into [`Self::parameter_names`]) into `out`, from one evaluation
    /// where the system can: what forward sensitivities read at each stage. The other
    /// columns of `out` are unspecified (a system that leaves them out writes NaN); the
    /// flag is `parameter_jacobian`'s, `true` when `wanted` is empty. The default calls the
    /// two; the interpreter evaluates one tape holding J and those columns alone (a 6-DOF
    /// flight's ascent with two sensitivities took 100 s through two evaluations of the
    /// tape of every parameter's column, 56 s so).
    fn jacobians(
        &self,
        t: f64,
        state: &SVector<f64, S>,
        wanted: &[usize],
        out: &mut [f64],
    ) -> Result<(SMatrix<f64, S, S>, bool), SystemError> {
        let jacobian = self.jacobian(t, state)?;
        let given = wanted.is_empty() || self.parameter_jacobian(t, state, out)?;
        Ok((jacobian, given))
    }

    /// The names of the parameters θ, the columns of [`Self::parameter_jacobian`]; none by
    /// default.
    fn parameter_names(&self) -> &'static [&'static str] {
        &[]
    }

    /// The Taylor coefficients y\[k\] = y⁽ᵏ⁾(t)/k! of the solution through `(t, state)`,
    /// k = 0 … `coefficients.len() − 1`, into `coefficients`: what the
    /// [`Taylor`](crate::steppers::Taylor) stepper integrates with. `None` when the system
    /// does not provide them, the default (generated code provides them with
    /// `emit = [..., "taylor"]`; a run-time model always does), and the stepper then refuses
    /// the system at construction. `scratch` is the expansion's working memory, kept by the
    /// caller between calls so that an expansion neither allocates nor clears it (what it
    /// held before never reaches the result).
    fn taylor_coefficients(
        &self,
        _t: f64,
        _state: &SVector<f64, S>,
        _coefficients: &mut [SVector<f64, S>],
        _scratch: &mut crate::scratch::Scratch,
    ) -> Option<Result<(), SystemError>> {
        None
    }

    /// The state rate evaluated over [`Dual`](crate::dd::Dual) double-double numbers: at
    /// `t + ε` and `state = y + ε ẏ` it gives f(t, y) + ε (∂f/∂y ẏ + ∂f/∂t), which the
    /// [`Taylor`](crate::steppers::Taylor) stepper's head
    /// ([`with_head`](crate::steppers::Taylor::with_head)) turns into the first two Taylor
    /// coefficients in double-double. `None` when the system has no head, the default
    /// (generated code has one with `emit = [..., "taylor", "head"]`).
    fn taylor_head(
        &self,
        _t: crate::dd::Dual,
        _state: &[crate::dd::Dual; S],
    ) -> Option<[crate::dd::Dual; S]> {
        None
    }

    /// The state rate f(t, y) in double-double alone: the head's first evaluation (c₁),
    /// which needs no derivative part. Generated with
    /// [`taylor_head`](VariableMassSystem::taylor_head); `None` by default.
    fn taylor_head_rate(&self, _t: f64, _state: &[crate::dd::Dd; S]) -> Option<[crate::dd::Dd; S]> {
        None
    }
}

// The bridge from the trait to the run's errors lives beside the trait, so that the errors
// (`crate::error`) stay a leaf that every module may read.
impl<const S: usize> StepError<S> {
    /// Attaches the time and state to a [`SystemError`]. A singular mass matrix is reported
    /// as the non-positive mass that caused it when there is one, and a non-finite state as
    /// such, because those are the causes a user can act on.
    pub fn from_system<Sys, const N: usize>(
        system: &Sys,
        error: SystemError,
        time: f64,
        state: &SVector<f64, S>,
    ) -> Self
    where
        Sys: VariableMassSystem<N, S> + ?Sized,
    {
        let state = *state;
        if !is_finite(&state) {
            return Self::new(time, state, StepErrorKind::NonFiniteState);
        }
        let error = match error {
            SystemError::SingularMassMatrix => match system.check_masses(time, &state) {
                Err(mass_error) => mass_error,
                Ok(()) => error,
            },
            SystemError::NonPositiveMass { .. }
            | SystemError::TableOutside { .. }
            | SystemError::SampledInputNotFinite { .. }
            | SystemError::SupportCoupled { .. }
            | SystemError::NoParameterJacobian
            | SystemError::RailCoupled
            | SystemError::RailColumnAcross { .. }
            | SystemError::SupportedSwitch { .. }
            | SystemError::NoSwitchGradient { .. }
            | SystemError::UnlocatedSwitch { .. }
            | SystemError::TangentSwitch { .. }
            | SystemError::SwitchesTogether { .. }
            | SystemError::TangentPhaseEnd { .. }
            | SystemError::TangentVelocityEnd { .. }
            | SystemError::PhaseColumns { .. }
            | SystemError::PhaseColumnDiffers { .. } => error,
        };
        Self::new(time, state, StepErrorKind::System(error))
    }
}
