//! A variational integrator for variable-mass systems: the midpoint discretisation of the
//! corrected Hamilton principle (docs/mechanics.md#corrected-hamilton-principle)
//!
//! ```text
//! ∫ [ δ*L + Σ_α (Q*_α − R1_α + R2_α + Σᵢ ṁᵢ ∂*p_α/∂mᵢ) δq_α ] dt = 0
//! ```
//!
//! Discrete Lagrangian L_d(q₀, q₁) = h L(q̄, (q₁ − q₀)/h, t̄) with q̄ = (q₀ + q₁)/2 and
//! t̄ = t₀ + h/2, every mass frozen at its midpoint value (every Lagrange-side function is
//! evaluated at the midpoint velocity state); discrete forces f⁻ = f⁺ = (h/2) F(mid) with
//! F = [`VariableMassSystem::generalized_force`] (Marsden & West, *Discrete mechanics and
//! variational integrators*, Acta Numerica 2001, on forced systems). In position–momentum form:
//!
//! ```text
//! p₀ = ∂L/∂q̇(mid) − (h/2)(∂*L/∂q + F)(mid)     solved for q₁ (and the state masses)
//! p₁ = ∂L/∂q̇(mid) + (h/2)(∂*L/∂q + F)(mid)    taken as p₀ + h (∂*L/∂q + F)(mid)
//! m₁ = m₀ + h ṁ(mid)                            state masses, midpoint rule
//! ```
//!
//! The two momentum equations subtracted give p₁ = p₀ + h (∂*L/∂q + F)(mid), the form the
//! new momentum is computed in: equal at the solution, but the midpoint velocity
//! (q₁ − q₀)/h carries the rounding of q₁, ulp(q)/h, which ∂L/∂q̇(mid) would pass on to p₁
//! whole, while here it enters only through the forces and times h. That rounding is
//! O(1) for the steps a few roundings of t long that a run takes on purpose (the T₁ → T₂
//! step of a table's knot, `core::table::next_knot_time_read`, the halving of a step refused
//! for a mass, `run/drive.rs`): the mass law M(t) of `tests/table_derivative_knots.rs` ended
//! 1.3 % off at any step, a tank burnt to zero propellant 5 % off Tsiolkovsky.
//!
//! [`Principle::LiteralEq19`] drops the mass-flux term Σ ṁᵢ ∂*p/∂mᵢ from F, i.e. takes the
//! paper's eq. 19 literally with ordinary integration by parts. For the sled that yields
//! m ẍ = … − 2c ẋ² instead of − c ẋ²: it exists to show the difference, not to be used.
//!
//! Newton runs on z = [q₁, 0, m₁] ∈ ℝˢ (the momentum block is pinned to zero so that the
//! unknown has the state's shape, as const generics cannot yet express ℝ^(S−N)), with a
//! forward-difference Jacobian of the residual at the predictor.

use nalgebra::{SMatrix, SVector};

use super::fixed::{Fixed, FixedMethod, NewState, Step};
use super::newton::{self, Newton, NewtonConfig};
use super::FixedStep;
use crate::error::{ConfigError, StepError};
use crate::stepper::{Checked, Statistics};
use crate::system::VariableMassSystem;

/// √ε, the relative step of a forward difference.
const SQRT_EPSILON: f64 = 1.490_116_119_384_765_6e-8;

/// Which Hamilton principle the variational stepper discretises.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Principle {
    /// The corrected principle (docs/mechanics.md#corrected-hamilton-principle), with the mass-flux term: the right equations.
    #[default]
    Corrected,
    /// The paper's eq. 19 taken literally (no mass-flux term): wrong whenever ṁ ≠ 0.
    LiteralEq19,
}

/// Settings of the variational stepper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VariationalConfig {
    /// The fixed step size h > 0.
    pub step: f64,
    /// The Newton iteration.
    pub newton: NewtonConfig,
    /// Which principle to discretise.
    pub principle: Principle,
}

impl Default for VariationalConfig {
    fn default() -> Self {
        Self {
            step: 1e-3,
            newton: NewtonConfig::default(),
            principle: Principle::Corrected,
        }
    }
}

/// The midpoint variational integrator on the state `[q, p, m_s]`, fixed step: [`Fixed`]
/// with the step of [`VariationalMethod`].
pub type Variational<'a, Sys, const N: usize, const S: usize> =
    Fixed<'a, Sys, VariationalMethod, N, S>;

/// The step of [`Variational`]: its Newton iteration and the principle it discretises.
#[derive(Clone, Debug)]
pub struct VariationalMethod {
    newton: Newton,
    principle: Principle,
}

/// The discrete equations of one step from `(t0, y0)` with step `h`.
struct DiscreteStep<'s, Sys, const S: usize> {
    system: &'s Sys,
    principle: Principle,
    t0: f64,
    y0: SVector<f64, S>,
    h: f64,
}

impl<Sys, const S: usize> DiscreteStep<'_, Sys, S> {
    /// The midpoint velocity state [q̄, (q₁ − q₀)/h, m̄] of an unknown z = [q₁, ·, m₁].
    fn midpoint<const N: usize>(&self, z: &SVector<f64, S>) -> SVector<f64, S> {
        let mut mid = (self.y0 + z) * 0.5;
        let velocity = (z.fixed_rows::<N>(0) - self.y0.fixed_rows::<N>(0)) / self.h;
        mid.fixed_rows_mut::<N>(N).copy_from(&velocity);
        mid
    }

    /// The midpoint momenta ∂L/∂q̇ and the half-step impulse (h/2)(∂*L/∂q + F), at the
    /// midpoint: the discrete momenta at the two ends are their difference and sum.
    fn momenta_and_impulse<const N: usize>(
        &self,
        t_mid: f64,
        mid: &SVector<f64, S>,
        statistics: &mut Statistics,
    ) -> Result<(SVector<f64, N>, SVector<f64, N>), StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        statistics.rate_evaluations += 1;
        // The Lagrange-side functions cannot fail, but their values are meaningless with a
        // mass ≤ 0 or a non-finite state: check first.
        self.system.check_state(t_mid, mid)?;
        let momenta = self.system.momenta(t_mid, mid);
        let force = match self.principle {
            Principle::Corrected => self.system.generalized_force(t_mid, mid),
            Principle::LiteralEq19 => self.system.frozen_force(t_mid, mid),
        };
        let impulse = (self.system.lagrangian_gradient(t_mid, mid) + force) * (0.5 * self.h);
        Ok((momenta, impulse))
    }

    /// r(z) = [p₀(z) − p₀, z_p, m₁ − m₀ − h ṁ(mid), u₁ − u₀]: zero at the solution of the
    /// step, the held values u of sampled inputs constant over it (their rate is 0).
    fn residual<const N: usize>(
        &self,
        z: &SVector<f64, S>,
        statistics: &mut Statistics,
    ) -> Result<SVector<f64, S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let t_mid = self.t0 + 0.5 * self.h;
        let mid = self.midpoint::<N>(z);
        let (momenta, impulse) = self.momenta_and_impulse(t_mid, &mid, statistics)?;
        let mut r = *z;
        r.fixed_rows_mut::<N>(0)
            .copy_from(&(momenta - impulse - self.y0.fixed_rows::<N>(N)));
        for k in 0..Sys::STATE_MASSES {
            let index = 2 * N + k;
            r[index] = z[index] - self.y0[index] - self.h * self.system.mass_rate(k, t_mid, &mid);
        }
        for index in 2 * N + Sys::STATE_MASSES..S {
            r[index] = z[index] - self.y0[index];
        }
        Ok(r)
    }

    /// Forward-difference Jacobian of the residual; the pinned momentum block is the
    /// identity and needs no evaluation.
    fn residual_jacobian<const N: usize>(
        &self,
        z: &SVector<f64, S>,
        statistics: &mut Statistics,
    ) -> Result<SMatrix<f64, S, S>, StepError<S>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        statistics.jacobian_evaluations += 1;
        let base = self.residual(z, statistics)?;
        let mut jacobian = SMatrix::<f64, S, S>::identity();
        let mut probe = *z;
        for j in (0..N).chain(2 * N..S) {
            let scale = z[j].abs().max(self.y0[j].abs());
            let dz = SQRT_EPSILON * if scale > 0.0 { scale } else { 1.0 };
            probe[j] = z[j] + dz;
            let column = (self.residual(&probe, statistics)? - base) / dz;
            probe[j] = z[j];
            jacobian.set_column(j, &column);
        }
        Ok(jacobian)
    }
}

impl<const N: usize, const S: usize> FixedMethod<N, S> for VariationalMethod {
    type Config = VariationalConfig;

    /// It integrates the Lagrange side: state entries that only the state rate evolves
    /// (forward sensitivities) it would hold constant.
    fn accepts<Sys: VariableMassSystem<N, S>>(system: &Sys) -> Result<(), ConfigError> {
        match system.has_rate_only_state() {
            true => Err(ConfigError {
                reason: "the variational stepper integrates the Lagrange side: it cannot \
                         carry sensitivities (use a Runge–Kutta or the Taylor stepper)",
            }),
            false => Ok(()),
        }
    }

    fn configure(config: VariationalConfig) -> Result<(f64, Self), ConfigError> {
        let step = FixedStep::validated(config.step)?;
        let newton = config.newton.validated()?;
        let principle = config.principle;
        Ok((step, Self { newton, principle }))
    }

    fn advance<Sys: VariableMassSystem<N, S>>(&self, step: Step<'_, Sys, S>) -> NewState<S> {
        let Step {
            system,
            statistics,
            t0,
            y0,
            h,
        } = step;
        let discrete = DiscreteStep {
            system,
            principle: self.principle,
            t0,
            y0,
            h,
        };

        // Predictor: an explicit Euler step of q and of the state masses.
        statistics.rate_evaluations += 1;
        let velocity_state = system.velocity_state_at(t0, &y0)?;
        let mut predictor = y0;
        predictor
            .fixed_rows_mut::<N>(0)
            .copy_from(&(y0.fixed_rows::<N>(0) + velocity_state.fixed_rows::<N>(N) * h));
        predictor.fixed_rows_mut::<N>(N).fill(0.0);
        for k in 0..Sys::STATE_MASSES {
            predictor[2 * N + k] += h * system.mass_rate(k, t0, &velocity_state);
        }

        let jacobian = discrete.residual_jacobian(&predictor, statistics)?;
        let solution = newton::solve(
            |z, statistics| discrete.residual(z, statistics),
            jacobian,
            predictor,
            &self.newton,
            statistics,
            (t0, &y0),
        )?;
        let mid = discrete.midpoint::<N>(&solution);
        let (_, impulse) = discrete.momenta_and_impulse(t0 + 0.5 * h, &mid, statistics)?;
        // p₁ = p₀ + 2·(h/2)(∂*L/∂q + F)(mid), not ∂L/∂q̇(mid) + …: see the module's doc.
        let mut y1 = solution;
        y1.fixed_rows_mut::<N>(N)
            .copy_from(&(y0.fixed_rows::<N>(N) + impulse * 2.0));
        Ok(y1)
    }
}
