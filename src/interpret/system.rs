//! [`TapeSystem`]: a [`Program`] with its sizes fixed at compile time, so that the core's
//! steppers integrate it like generated code.

use varmass_core::input::Sampling;
use varmass_core::nalgebra::{SMatrix, SVector};
use varmass_core::system::central_jacobian;
use varmass_core::tangent::Tangent;
use varmass_core::{SystemError, VariableMassSystem};

use super::error::ProgramError;
use super::program::{Program, Quantity};

/// A run-time model as a [`VariableMassSystem`] with `N` coordinates and state dimension
/// `S = 2N + K` (`+ HELD` with sampled inputs, whose held values follow the state masses:
/// [`Program::sample`] replaces them). Every required method evaluates the program's tapes; q̇(q, p), H, the
/// state rate and the power are overridden with their tapes too, and the Jacobian is the
/// trait's central-difference default.
///
/// Associated constants cannot hold names known only at run time, so
/// [`VariableMassSystem::COORDINATES`] holds empty names and
/// [`VariableMassSystem::MASSES`] is empty: read the names from [`Program::coordinate_names`]
/// and [`Program::mass_names`]. [`VariableMassSystem::check_masses`] is overridden to check
/// every mass of the model all the same. A mass event therefore cannot be given by index
/// ([`varmass_core::Event::mass_reaches`] is rejected as out of range): stop on a state
/// mass with [`varmass_core::Event::state_reaches`], or on any mass with an
/// [`varmass_core::Event::function`].
#[derive(Debug)]
pub struct TapeSystem<const N: usize, const S: usize> {
    program: Program,
}

impl<const N: usize, const S: usize> TapeSystem<N, S> {
    /// Fixes the sizes of `program`; they must be its number of coordinates and its state
    /// length.
    pub fn new(program: Program) -> Result<Self, ProgramError> {
        let state_fits = program.state_len() == S;
        Self::sized(program, state_fits)
    }

    /// Like [`TapeSystem::new`], but `S` may exceed the program's state length: the extra
    /// entries are state masses of no consequence, kept at their values (rate 0, never
    /// read by the program), after the model's own. So one monomorphization of the steppers
    /// for `(N, S)` runs every model with `N` coordinates and up to `S − 2N` state masses
    /// (the command line tool's size table, `cli/src/run/dispatch.rs`). The error control
    /// averages over all `S` components, so a caller who wants the step control of the
    /// unpadded system scales its tolerances by √(len / S).
    pub fn padded(program: Program) -> Result<Self, ProgramError> {
        let state_fits = program.state_len() <= S;
        Self::sized(program, state_fits)
    }

    /// `program` if it has `N` coordinates and its state fits (as the caller judged), else
    /// [`ProgramError::WrongSize`].
    fn sized(program: Program, state_fits: bool) -> Result<Self, ProgramError> {
        if program.coordinate_count() != N || !state_fits {
            return Err(ProgramError::WrongSize {
                coordinates: program.coordinate_count(),
                state_masses: program.state_mass_count(),
                n: N,
                s: S,
            });
        }
        Ok(Self { program })
    }

    /// The program evaluated.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// The program, to give it other parameter values between runs
    /// ([`Program::set_parameters`]; the sizes it was fixed with do not change): a scene's
    /// value set at the time of a change (docs/scenes.md#a-value-set-at-the-change).
    pub fn program_mut(&mut self) -> &mut Program {
        &mut self.program
    }

    /// Gives the program back.
    pub fn into_program(self) -> Program {
        self.program
    }

    fn vector(
        &self,
        quantity: Quantity,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> SVector<f64, N> {
        let mut out = SVector::<f64, N>::from_element(f64::NAN);
        self.program
            .evaluate(quantity, t, velocity_state.as_slice(), out.as_mut_slice());
        out
    }

    /// The model's index of mass `index` in the trait's order (the state masses, the
    /// padding of [`TapeSystem::padded`], then the law masses); `None` for padding.
    fn model_mass(&self, index: usize) -> Option<usize> {
        let state_masses = self.program.state_mass_count();
        // The held inputs and the padding: entries after the state masses that are no mass.
        let padding = S - 2 * N - state_masses;
        match index {
            i if i < state_masses => Some(i),
            i if i < state_masses + padding => None,
            i => Some(i - padding),
        }
    }

    fn scalar(&self, quantity: Quantity, t: f64, velocity_state: &SVector<f64, S>) -> f64 {
        let mut out = [f64::NAN];
        self.program
            .evaluate(quantity, t, velocity_state.as_slice(), &mut out);
        out[0]
    }

    /// A one-value `quantity` at a state `[q, p, m_s]` (q̇ recovered from p).
    fn scalar_at_state(
        &self,
        quantity: Quantity,
        t: f64,
        state: &SVector<f64, S>,
    ) -> Result<f64, SystemError> {
        let mut out = [f64::NAN];
        self.program
            .evaluate_at_state(quantity, t, state.as_slice(), &mut out)?;
        Ok(out[0])
    }
}

/// The vector a program's solve writes into `out` (NaN where it writes nothing), or its
/// error.
fn filled<const M: usize>(
    solve: impl FnOnce(&mut [f64]) -> Result<(), SystemError>,
) -> Result<SVector<f64, M>, SystemError> {
    let mut out = SVector::<f64, M>::from_element(f64::NAN);
    solve(out.as_mut_slice())?;
    Ok(out)
}

impl<const N: usize, const S: usize> VariableMassSystem<N, S> for TapeSystem<N, S> {
    const COORDINATES: [&'static str; N] = [""; N];
    const MASSES: &'static [&'static str] = &[];

    fn next_stop_time(&self, after: f64) -> Option<f64> {
        self.program.next_stop_time(after)
    }

    /// The held values sit after the state masses, inside the padding of
    /// [`TapeSystem::padded`] ([`VariableMassSystem::HELD`] stays 0: the count is known only
    /// at run time, and a held entry, like the padding, has rate 0 and is no mass).
    fn sample(
        &self,
        t: f64,
        state: &mut SVector<f64, S>,
        which: Sampling,
    ) -> Result<(), SystemError> {
        self.program.sample(t, state.as_mut_slice(), which)
    }

    fn mass(&self, index: usize, t: f64, state: &SVector<f64, S>) -> f64 {
        let Some(model) = self.model_mass(index) else {
            // A padding mass is its own state entry (state masses come first).
            return state[2 * N + index];
        };
        let index = model;
        let mut masses = vec![f64::NAN; self.program.derivation().masses.len()];
        self.program.masses(t, state.as_slice(), &mut masses);
        masses.get(index).copied().unwrap_or(f64::NAN)
    }

    fn mass_rate(&self, index: usize, t: f64, velocity_state: &SVector<f64, S>) -> f64 {
        let Some(index) = self.model_mass(index) else {
            return 0.0;
        };
        let mut rates = vec![f64::NAN; self.program.derivation().masses.len()];
        self.program.evaluate(
            Quantity::MassRates,
            t,
            velocity_state.as_slice(),
            &mut rates,
        );
        rates.get(index).copied().unwrap_or(f64::NAN)
    }

    fn mass_matrix(&self, t: f64, state: &SVector<f64, S>) -> SMatrix<f64, N, N> {
        let mut entries = SMatrix::<f64, N, N>::from_element(f64::NAN);
        // Row-major values into a column-major matrix: M is symmetric.
        self.program.evaluate(
            Quantity::MassMatrix,
            t,
            state.as_slice(),
            entries.as_mut_slice(),
        );
        entries.transpose()
    }

    fn momenta(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.vector(Quantity::Momenta, t, velocity_state)
    }

    fn lagrangian(&self, t: f64, velocity_state: &SVector<f64, S>) -> f64 {
        self.scalar(Quantity::Lagrangian, t, velocity_state)
    }

    fn lagrangian_gradient(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.vector(Quantity::LagrangianGradient, t, velocity_state)
    }

    fn active_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.vector(Quantity::ActiveForce, t, velocity_state)
    }

    fn reactive_thrust(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.vector(Quantity::ReactiveThrust, t, velocity_state)
    }

    fn impact_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.vector(Quantity::ImpactForce, t, velocity_state)
    }

    fn mass_flux_force(&self, t: f64, velocity_state: &SVector<f64, S>) -> SVector<f64, N> {
        self.vector(Quantity::MassFluxForce, t, velocity_state)
    }

    fn accelerations(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> Result<SVector<f64, N>, SystemError> {
        filled(|out| {
            self.program
                .accelerations(t, velocity_state.as_slice(), out)
        })
    }

    /// The symbolic Jacobian when the program has it ([`Program::has_jacobians`]), the
    /// padding's rows and columns 0; else the trait's central differences.
    fn jacobian(&self, t: f64, state: &SVector<f64, S>) -> Result<SMatrix<f64, S, S>, SystemError> {
        let len = self.program.state_len();
        let mut entries = vec![0.0; len * len];
        if !self.program.jacobian(t, state.as_slice(), &mut entries)? {
            return central_jacobian(t, state, |t, y| self.state_rate(t, y));
        }
        Ok(padded(len, &entries))
    }

    /// The program's J and the parameter Jacobian's columns `wanted` from one evaluation
    /// ([`Program::jacobians`]), the padding's rows and columns 0; without the symbolic
    /// Jacobians, the trait's central differences and no parameter Jacobian.
    fn jacobians(
        &self,
        t: f64,
        state: &SVector<f64, S>,
        wanted: &[usize],
        out: &mut [f64],
    ) -> Result<(SMatrix<f64, S, S>, bool), SystemError> {
        let len = self.program.state_len();
        let rows = len * self.parameter_names().len();
        let mut entries = vec![0.0; len * len];
        out.iter_mut().for_each(|x| *x = 0.0);
        let given = match out.get_mut(..rows) {
            Some(model_rows) => {
                (self.program).jacobians(t, state.as_slice(), wanted, &mut entries, model_rows)?
            }
            None => false,
        };
        if !given {
            return Ok((self.jacobian(t, state)?, wanted.is_empty()));
        }
        Ok((padded(len, &entries), true))
    }

    fn sensitivity_obstacle(&self) -> Option<&'static str> {
        self.program.sensitivity_obstacle()
    }

    fn parameter_jacobian(
        &self,
        t: f64,
        state: &SVector<f64, S>,
        out: &mut [f64],
    ) -> Result<bool, SystemError> {
        let rows = self.program.state_len() * self.parameter_names().len();
        out.iter_mut().for_each(|x| *x = 0.0);
        let Some(model_rows) = out.get_mut(..rows) else {
            return Ok(false);
        };
        self.program
            .parameter_jacobian(t, state.as_slice(), model_rows)
    }

    fn parameter_names(&self) -> &'static [&'static str] {
        self.program.parameter_names()
    }

    fn has_switch_gradients(&self) -> bool {
        self.program.has_switch_gradients()
    }

    /// The program's gradient, the velocity state's part padded to S entries.
    fn switch_gradient(
        &self,
        index: usize,
        t: f64,
        velocity_state: &SVector<f64, S>,
        out: &mut [f64],
    ) -> Result<bool, SystemError> {
        let moved = 2 * self.program.coordinate_count() + self.program.state_mass_count();
        let parameters = self.parameter_names().len();
        let mut model = vec![0.0; 1 + moved + parameters];
        if !(self.program).switch_gradient(index, t, velocity_state.as_slice(), &mut model)? {
            return Ok(false);
        }
        out.iter_mut().for_each(|x| *x = 0.0);
        let (head, theta) = model.split_at(1 + moved);
        let places = (0..head.len()).chain((1 + S)..(1 + S + parameters));
        for (place, value) in places.zip(head.iter().chain(theta)) {
            if let Some(o) = out.get_mut(place) {
                *o = *value;
            }
        }
        Ok(true)
    }

    fn switch_count(&self) -> usize {
        self.program.switch_count()
    }

    fn switch_name(&self, index: usize) -> Option<&str> {
        self.program.switch_name(index)
    }

    fn flow_count(&self) -> usize {
        self.program.flow_count()
    }

    fn singular_attitude_distance(&self, t: f64, state: &SVector<f64, S>) -> Option<f64> {
        self.program.singular_attitude_distance(t, state.as_slice())
    }

    fn flow_name(&self, index: usize) -> Option<&str> {
        self.program.flow_name(index)
    }

    fn flow_rate(&self, index: usize, t: f64, velocity_state: &SVector<f64, S>) -> f64 {
        self.program.flow_rate(index, t, velocity_state.as_slice())
    }

    fn switching_functions(&self, t: f64, velocity_state: &SVector<f64, S>, values: &mut [f64]) {
        self.program
            .switching_functions(t, velocity_state.as_slice(), values);
    }

    fn switch_anchors(&self, t: f64, velocity_state: &SVector<f64, S>, anchors: &mut [f64]) {
        self.program
            .switch_anchors(t, velocity_state.as_slice(), anchors);
    }

    fn anchored_switching_functions(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
        anchors: &[f64],
        values: &mut [f64],
    ) {
        self.program
            .anchored_switching_functions(t, velocity_state.as_slice(), anchors, values);
    }

    fn check_masses(&self, t: f64, state: &SVector<f64, S>) -> Result<(), SystemError> {
        let mut masses = vec![f64::NAN; self.program.derivation().masses.len()];
        self.program.masses(t, state.as_slice(), &mut masses);
        match masses.iter().position(|m| m.is_nan() || *m <= 0.0) {
            Some(index) => Err(SystemError::NonPositiveMass { index }),
            None => Ok(()),
        }
    }

    fn velocities(&self, t: f64, state: &SVector<f64, S>) -> Result<SVector<f64, N>, SystemError> {
        filled(|out| self.program.velocities(t, state.as_slice(), out))
    }

    fn hamiltonian(&self, t: f64, state: &SVector<f64, S>) -> Result<f64, SystemError> {
        self.scalar_at_state(Quantity::Energy, t, state)
    }

    fn state_rate(&self, t: f64, state: &SVector<f64, S>) -> Result<SVector<f64, S>, SystemError> {
        let mut out = SVector::<f64, S>::from_element(f64::NAN);
        let len = self.program.state_len();
        self.program
            .state_rate(t, state.as_slice(), &mut out.as_mut_slice()[..len])?;
        // The padding of `TapeSystem::padded` stays where it is.
        out.as_mut_slice()[len..].fill(0.0);
        Ok(out)
    }

    fn power(&self, t: f64, state: &SVector<f64, S>) -> Result<f64, SystemError> {
        self.scalar_at_state(Quantity::Power, t, state)
    }

    fn taylor_coefficients(
        &self,
        t: f64,
        state: &SVector<f64, S>,
        coefficients: &mut [SVector<f64, S>],
        // The tapes keep their own jet (`TaylorProgram`'s scratch).
        _: &mut varmass_core::scratch::Scratch,
    ) -> Option<Result<(), SystemError>> {
        let order = coefficients.len().checked_sub(1)?;
        Some(
            self.program
                .taylor_each(t, state.as_slice(), order, |k, i, value| {
                    if let Some(c) = coefficients.get_mut(k) {
                        c[i] = value;
                    }
                }),
        )
    }

    /// The tapes' recurrences over tangents (`Program::taylor_tangents`); the padding of
    /// `TapeSystem::padded` stays 0.
    fn taylor_coefficients_tangents<const W: usize>(
        &self,
        t: f64,
        state: &[Tangent<W>; S],
        seeds: &[Option<usize>; W],
        coefficients: &mut [[Tangent<W>; S]],
        _: &mut varmass_core::scratch::Scratch<Tangent<W>>,
    ) -> Option<Result<(), SystemError>> {
        let order = coefficients.len().checked_sub(1)?;
        for c in coefficients.iter_mut() {
            c.fill(Tangent::constant(0.0));
        }
        let len = self.program.state_len();
        self.program
            .taylor_tangents(t, &state[..len.min(S)], seeds, order, |k, i, value| {
                if let Some(c) = coefficients.get_mut(k) {
                    c[i] = value;
                }
            })
    }
}

/// The row-major `len × len` `entries` as an S × S matrix, the padding's rows and columns 0.
fn padded<const S: usize>(len: usize, entries: &[f64]) -> SMatrix<f64, S, S> {
    SMatrix::<f64, S, S>::from_fn(|i, j| match i < len && j < len {
        true => entries[i * len + j],
        false => 0.0,
    })
}
