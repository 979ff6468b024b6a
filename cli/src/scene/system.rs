//! The system a scene's phases run (`fly.rs`): the interpreter's [`TapeSystem`], or with
//! `--sensitivity` the same inside the core's [`Sensitive`] (docs/sensitivities.md#scenes),
//! its columns integrated with it through the supports, the rail and the changes — one trait,
//! so that one runner flies either.

use varmass::core::nalgebra::SVector;
use varmass::core::sensitivity::{Column, Sensitive};
use varmass::core::{StepError, VariableMassSystem};
use varmass::interpret::{Program, TapeSystem};

use crate::error::CliError;
use crate::run::integrate::describe;
use crate::run::names::Observable;
use crate::run::plan::Plan;
use crate::run::record::Recorded;
use crate::run::sensitivity::{point_derivatives, Constraint, MAX_SENSITIVITIES};

/// What a scene needs of its phases' system besides the mechanics.
pub trait SceneSystem<const N: usize, const S: usize>: VariableMassSystem<N, S> + Sized {
    /// The system of a phase's `program`, with the scene's sensitivity `columns` (none
    /// without `--sensitivity`).
    fn build(program: Program, columns: &[Column]) -> Result<Self, CliError>;

    /// The phase's program, to be given values at a change: `None` with sensitivities
    /// (values set at a change are refused before the run).
    fn program_mut(&mut self) -> Option<&mut Program>;

    /// The phase's program, given back for recording.
    fn into_program(self) -> Program;

    /// The run's start from the plan's initial state `[q, p, m_s]`: padded to `S`; with
    /// sensitivities, the columns seeded.
    fn start(&self, plan: &Plan) -> Result<(f64, SVector<f64, S>), CliError>;

    /// A failure of the run in the tool's words (`flows`: the phase model's).
    fn describe(&self, plan: &Plan, flows: &[String], error: StepError<S>) -> CliError;

    /// The entries the step limits scale with: the model's own and the padded state's.
    fn entries(len: usize, columns: usize) -> (usize, usize);

    /// The derivative columns at a point recording `record` (`d(X)/d(w)`, `d(t)/d(w)`, the
    /// rates `d(X)/d(t)`; none without sensitivities); `event` is the observable of the
    /// condition that ended the run there, if one did; `constraint` what holds the body.
    fn derivatives(
        &self,
        recording: (&Plan, &[(String, Recorded)]),
        point: (f64, &SVector<f64, S>),
        event: Option<Observable>,
        constraint: Constraint,
    ) -> Result<Vec<f64>, String>;
}

impl<const N: usize, const S: usize> SceneSystem<N, S> for TapeSystem<N, S> {
    fn build(program: Program, _: &[Column]) -> Result<Self, CliError> {
        TapeSystem::padded(program).map_err(|e| CliError::Input(e.to_string()))
    }

    fn program_mut(&mut self) -> Option<&mut Program> {
        Some(TapeSystem::program_mut(self))
    }

    fn into_program(self) -> Program {
        TapeSystem::into_program(self)
    }

    fn start(&self, plan: &Plan) -> Result<(f64, SVector<f64, S>), CliError> {
        let mut initial_state = plan.initial_state.clone();
        initial_state.resize(S, 0.0);
        Ok((plan.from, SVector::from_column_slice(&initial_state)))
    }

    fn describe(&self, plan: &Plan, flows: &[String], error: StepError<S>) -> CliError {
        describe(self, plan, flows, error)
    }

    fn entries(len: usize, _: usize) -> (usize, usize) {
        (len, S)
    }

    fn derivatives(
        &self,
        _: (&Plan, &[(String, Recorded)]),
        _: (f64, &SVector<f64, S>),
        _: Option<Observable>,
        _: Constraint,
    ) -> Result<Vec<f64>, String> {
        Ok(Vec::new())
    }
}

/// A phase's system with the scene's sensitivities: `S0` its padded state, `SA` the
/// augmented one (`S0 (1 + MAX_SENSITIVITIES)`, the unused columns `Column::Elsewhere`).
impl<const N: usize, const S0: usize, const SA: usize> SceneSystem<N, SA>
    for Sensitive<TapeSystem<N, S0>, S0>
{
    fn build(program: Program, columns: &[Column]) -> Result<Self, CliError> {
        let system =
            TapeSystem::<N, S0>::padded(program).map_err(|e| CliError::Input(e.to_string()))?;
        let mut columns = columns.to_vec();
        columns.resize(MAX_SENSITIVITIES, Column::Elsewhere);
        Sensitive::new::<N, SA>(system, &columns)
            .map_err(|e| CliError::Input(format!("--sensitivity: {e}")))
    }

    fn program_mut(&mut self) -> Option<&mut Program> {
        None
    }

    fn into_program(self) -> Program {
        self.into_system().into_program()
    }

    fn start(&self, plan: &Plan) -> Result<(f64, SVector<f64, SA>), CliError> {
        let (t0, initial) = SceneSystem::<N, S0>::start(self.system(), plan)?;
        let system = self.system();
        let at_start = |e| {
            describe(
                system,
                plan,
                &plan.flows,
                StepError::from_system(system, e, t0, &initial),
            )
        };
        let velocity_state = system.velocity_state(t0, &initial).map_err(at_start)?;
        let start = self.start_at_velocities::<N, SA>(t0, &velocity_state);
        Ok((t0, start.map_err(at_start)?))
    }

    fn describe(&self, plan: &Plan, flows: &[String], error: StepError<SA>) -> CliError {
        let head = StepError {
            time: error.time,
            state: error.state.fixed_rows::<S0>(0).into_owned(),
            kind: error.kind,
        };
        describe(self.system(), plan, flows, head)
    }

    fn entries(len: usize, columns: usize) -> (usize, usize) {
        (len * (1 + columns), SA)
    }

    fn derivatives(
        &self,
        (plan, record): (&Plan, &[(String, Recorded)]),
        point: (f64, &SVector<f64, SA>),
        event: Option<Observable>,
        constraint: Constraint,
    ) -> Result<Vec<f64>, String> {
        point_derivatives(self, (plan, record), point, event, constraint)
    }
}
