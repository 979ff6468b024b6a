//! [`Program`]: a derivation with its parameter values, compiled into tapes and evaluated
//! on run-time sized slices.

use std::cell::RefCell;
use std::sync::Arc;

use varmass_core::math::singular_attitude_distance;
use varmass_core::table::{knot_bracket_read, knot_gap_read, next_knot_time_read, Table};
use varmass_core::tangent::Tangent;
use varmass_core::SystemError;
use varmass_symbolic::expr::{Id, Symbol, Tape};
use varmass_symbolic::mechanics::{time_tables, Coordinate, Derivation, Outputs};
use varmass_symbolic::parse::keywords::closest;
use varmass_symbolic::quantity::Evaluated;
pub use varmass_symbolic::quantity::Quantity;

use super::cholesky::cholesky_solve;
use super::error::ProgramError;
use super::taylor::TaylorProgram;

mod gradients;
mod held;
mod jacobians;

pub use gradients::Direction;
use jacobians::Jacobians;

/// How each group of quantities is evaluated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Evaluation {
    /// A straight-line [`Tape`] per group (`ExprPool::compile`): the fast way.
    #[default]
    Tape,
    /// `ExprPool::eval` on each expression, which compiles a one-expression tape at every
    /// call (nothing shared between expressions, buffers allocated per call): what compiling
    /// the groups once saves, for the benches' comparison. Never faster than `Tape`.
    Tree,
}

/// A group of expressions and their tape.
#[derive(Debug)]
struct Stage {
    roots: Vec<Id>,
    tape: Tape,
}

/// The buffers of an evaluation: the environment (one slot per symbol, parameters filled
/// in) and the values of a stage.
#[derive(Debug)]
struct Scratch {
    env: Vec<f64>,
    values: Vec<f64>,
    /// The first table lookup outside its data since the state was loaded.
    outside: Option<SystemError>,
}

/// A derivation with its parameter values, ready to evaluate its state rate and any
/// [`Quantity`] at run time. Not `Sync` (it reuses internal buffers): one per thread.
#[derive(Debug)]
pub struct Program {
    d: Derivation,
    evaluation: Evaluation,
    /// Env slots of the law masses, in mass order.
    law_slots: Vec<usize>,
    laws: Stage,
    /// q̇ in closed form, or the mass-matrix entries (row-major) then the offsets b.
    velocities: Stage,
    numeric: bool,
    /// ṗ then ṁ of the state masses.
    rates: Stage,
    /// One stage per [`Quantity::ALL`] entry.
    quantities: Vec<Stage>,
    /// The switching functions (`mechanics::switching_functions`), then the arguments of
    /// the tables of the state whose knots are switches (`mechanics::table_switches`).
    switches: Stage,
    /// Those tables, in order: switch `switches.roots.len() - switch_tables.len() + i` is
    /// at the knots of `switch_tables[i]`.
    /// Each as the orders the equations read, 0 to the highest.
    switch_tables: Vec<Vec<Arc<Table>>>,
    switch_names: Vec<String>,
    /// The Taylor recurrences of the state rate.
    taylor: TaylorProgram,
    /// The flows' rates (Q1 of an outflow, Q2 of an inflow), in the model's order.
    flows: Stage,
    /// The Euler middle angles of the spatial rigid bodies (`Derivation::euler_middles`).
    attitudes: Stage,
    /// The tables of t (each the orders the equations read, 0 to the highest) with the
    /// slope and offset of their argument: their knots are stop times
    /// (docs/tables.md#knots-are-switches).
    stops: Vec<(Vec<Arc<Table>>, f64, f64)>,
    /// Each stop table's slope and offset (made of parameters), to recompute [`Self::stops`]
    /// when [`Program::set_parameters`] changes the values.
    stop_arguments: Stage,
    /// The parameters the equations read (`Derivation::used_parameters`, a walk of every
    /// expression): found once, checked at every [`Program::set_parameters`].
    used: Vec<String>,
    /// The held values of the sampled inputs (`held.rs`), their laws (one stage each, so
    /// that a sample evaluates only the inputs due) and periods.
    held_symbols: Vec<Symbol>,
    held_laws: Vec<Stage>,
    periods: Vec<f64>,
    /// The symbolic Jacobians (`jacobians.rs`), when the derivation has the parameter
    /// Jacobian (`Outputs::sensitivities`).
    jacobians: Option<Jacobians>,
    /// The gradients of recorded expressions (`gradients.rs`), compiled when asked.
    gradients: Vec<(Id, Stage)>,
    /// The switching functions' gradients, one after the other (`gradients.rs`), with the
    /// Jacobians: what the sensitivities jump by at a switch.
    switch_gradients: Option<Stage>,
    /// Times the run lands on besides the stop times of the model ([`Program::land_on`]),
    /// increasing.
    landings: Vec<f64>,
    scratch: RefCell<Scratch>,
}

impl Program {
    /// Compiles `derivation` with the given parameter values into tapes. Every parameter
    /// the equations read needs a finite value; a name that is no parameter is an error
    /// naming the nearest one.
    pub fn new(derivation: Derivation, parameters: &[(&str, f64)]) -> Result<Self, ProgramError> {
        Self::with_evaluation(derivation, parameters, Evaluation::Tape)
    }

    /// [`Program::new`] with a choice of [`Evaluation`].
    pub fn with_evaluation(
        mut d: Derivation,
        parameters: &[(&str, f64)],
        evaluation: Evaluation,
    ) -> Result<Self, ProgramError> {
        check_given(&d)?;
        let used = d.used_parameters();
        let env = parameter_env(&d, &used, parameters)?;
        // Law masses → q̇ → ṗ and ṁ, as every evaluator of the state rate stages them.
        let stages = d.rate_stages();
        let law_slots = stages
            .law_masses
            .iter()
            .map(|&i| d.masses[i].symbol.index());
        let law_slots = law_slots.collect();
        let (switch_roots, switch_names, switch_tables) = switches(&mut d);
        let jacobians = Jacobians::new(&mut d);
        let switch_gradients = jacobians
            .as_ref()
            .map(|_| gradients::switch_gradients(&mut d, &switch_roots));
        let code = d.code_roots(Outputs::FULL);
        let (tables, stop_roots) = stop_tables(
            &mut d,
            &[&stages.rates, &stages.velocities, &stages.laws, &code],
        );
        let stage = |roots: Vec<Id>| Stage {
            tape: d.pool.compile(&roots),
            roots,
        };
        let stop_arguments = stage(stop_roots);
        let stops = stop_values(&tables, &stop_arguments, &env);
        let quantities = Quantity::ALL
            .iter()
            .map(|q| stage(d.quantity(*q)))
            .collect();
        let sampled: Vec<_> = d.inputs.iter().filter(|i| i.held.is_some()).collect();
        if let Some(input) = sampled.iter().find(|i| i.law.is_none()) {
            return Err(ProgramError::MissingInputLaw {
                name: input.name.clone(),
            });
        }
        let held_laws = sampled
            .iter()
            .filter_map(|i| i.law)
            .map(|law| stage(vec![law]));
        let held_laws = held_laws.collect();
        let periods = sampled.iter().filter_map(|i| i.every).collect();
        Ok(Self {
            taylor: TaylorProgram::new(&d, &env),
            evaluation,
            law_slots,
            laws: stage(stages.laws),
            velocities: stage(stages.velocities),
            numeric: stages.numeric,
            rates: stage(stages.rates),
            quantities,
            switches: stage(switch_roots),
            switch_tables,
            switch_names,
            flows: stage(d.flow_rates.clone()),
            attitudes: stage(d.euler_middles.iter().map(|(angle, _)| *angle).collect()),
            stops,
            stop_arguments,
            used,
            held_symbols: d.held(),
            held_laws,
            periods,
            jacobians,
            gradients: Vec::new(),
            switch_gradients,
            landings: Vec::new(),
            scratch: RefCell::new(Scratch {
                env,
                values: Vec::new(),
                outside: None,
            }),
            d,
        })
    }

    /// Gives the parameters new values, with [`Program::new`]'s checks and errors (on an
    /// error the program keeps its former values). The tapes do not depend on the values,
    /// so a sweep or an ensemble compiles the derivation once and only refills the
    /// parameters' slots: evaluations after it are exactly those of a program made anew
    /// with these values.
    pub fn set_parameters(&mut self, parameters: &[(&str, f64)]) -> Result<(), ProgramError> {
        let env = parameter_env(&self.d, &self.used, parameters)?;
        let tables: Vec<Vec<Arc<Table>>> = self.stops.iter().map(|(t, _, _)| t.clone()).collect();
        self.stops = stop_values(&tables, &self.stop_arguments, &env);
        self.taylor.set_env(&env);
        let scratch = self.scratch.get_mut();
        scratch.env = env;
        scratch.outside = None;
        Ok(())
    }

    /// The derivation this program evaluates.
    pub fn derivation(&self) -> &Derivation {
        &self.d
    }

    /// N, the number of coordinates.
    pub fn coordinate_count(&self) -> usize {
        self.d.coordinates.len()
    }

    /// K, the number of state masses.
    pub fn state_mass_count(&self) -> usize {
        self.d.state_mass_count()
    }

    /// S = 2N + K + HELD, the length of a state `[q, p, m_s, u_held]`.
    pub fn state_len(&self) -> usize {
        2 * self.coordinate_count() + self.state_mass_count() + self.held_count()
    }

    /// The coordinates' names, in state order.
    pub fn coordinate_names(&self) -> impl Iterator<Item = &str> {
        self.d.coordinates.iter().map(|c| c.name.as_str())
    }

    /// Every mass's name: state masses first (in state order), then the laws.
    pub fn mass_names(&self) -> impl Iterator<Item = &str> {
        self.d.masses.iter().map(|m| m.name.as_str())
    }

    /// Instructions in the law, velocity and rate tapes together: the work of one state
    /// rate.
    pub fn tape_length(&self) -> usize {
        self.laws.tape.len() + self.velocities.tape.len() + self.rates.tape.len()
    }

    /// Instructions of the q̇ stage alone.
    pub fn velocity_tape_length(&self) -> usize {
        self.velocities.tape.len()
    }

    /// Instructions of the Taylor tapes of the state rate.
    pub fn taylor_tape_length(&self) -> usize {
        self.taylor.len()
    }

    /// The Taylor coefficients y\[k\] = y⁽ᵏ⁾(t)/k!, k = 0 … `order`, of the solution through
    /// `(t, state)`, into `out`: coefficient k of state component i at `out[k * S + i]`
    /// (S = 2N + K; as many as fit). Allocation-free once the buffers have grown to `order`.
    pub fn taylor(
        &self,
        t: f64,
        state: &[f64],
        order: usize,
        out: &mut [f64],
    ) -> Result<(), SystemError> {
        let s = self.state_len();
        self.taylor.expand(t, state, order, |k, i, value| {
            if let Some(o) = out.get_mut(k * s + i) {
                *o = value;
            }
        })
    }

    /// [`Program::taylor`] giving each coefficient to `write(k, i, y[k]ᵢ)`.
    pub fn taylor_each(
        &self,
        t: f64,
        state: &[f64],
        order: usize,
        write: impl FnMut(usize, usize, f64),
    ) -> Result<(), SystemError> {
        self.taylor.expand(t, state, order, write)
    }

    /// Whether [`Program::taylor_tangents`] expands this model: q̇ in closed form (a tangent
    /// M q̇ = p − b is not solved).
    pub fn has_taylor_tangents(&self) -> bool {
        self.taylor.has_tangents()
    }

    /// [`Program::taylor_each`] over tangents: the state's derivatives and parameter j moved
    /// by 1 in direction c where `seeds[c] = Some(j)` ([`Program::parameter_names`] order)
    /// give the Taylor coefficients of the sensitivities; `None` where q̇ has no closed form.
    pub fn taylor_tangents<const W: usize>(
        &self,
        t: f64,
        state: &[Tangent<W>],
        seeds: &[Option<usize>; W],
        order: usize,
        write: impl FnMut(usize, usize, Tangent<W>),
    ) -> Option<Result<(), SystemError>> {
        self.taylor.expand_tangents(t, state, seeds, order, write)
    }

    /// Every mass at `(t, state)` into `out` (in [`Program::mass_names`] order). Only q and
    /// the state masses are read, so a state or a velocity state may be passed.
    pub fn masses(&self, t: f64, state: &[f64], out: &mut [f64]) {
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_positions(scratch, t, state);
        for (o, m) in out.iter_mut().zip(&self.d.masses) {
            *o = scratch
                .env
                .get(m.symbol.index())
                .copied()
                .unwrap_or(f64::NAN);
        }
    }

    /// q̇(q, p, t) at a state `[q, p, m_s]` into `out`.
    pub fn velocities(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<(), SystemError> {
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_state(scratch, t, state)?;
        self.read_velocities(&scratch.env, out);
        Ok(())
    }

    /// The state rate `[q̇, ṗ, ṁ_s]` at `(t, state)` into `out`.
    pub fn state_rate(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<(), SystemError> {
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_state(scratch, t, state)?;
        self.read_velocities(&scratch.env, out);
        let n = self.coordinate_count();
        self.run(&self.rates, scratch);
        if let Some(error) = scratch.outside.take() {
            return Err(error);
        }
        for (o, v) in out.iter_mut().skip(n).zip(&scratch.values) {
            *o = *v;
        }
        // A held value is constant between samples.
        let held = 2 * n + self.state_mass_count()..self.state_len();
        if let Some(rates) = out.get_mut(held) {
            rates.fill(0.0);
        }
        Ok(())
    }

    /// A velocity-form quantity at a velocity state `[q, q̇, m_s]` into `out`. The
    /// accelerations are here only in closed form (up to `SYMBOLIC_INVERSE_MAX_DOF`
    /// coordinates); [`Program::evaluate_at_state`] and [`Program::accelerations`] solve
    /// eq. 6 beyond.
    pub fn evaluate(&self, quantity: Quantity, t: f64, velocity_state: &[f64], out: &mut [f64]) {
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_velocity_state(scratch, t, velocity_state);
        self.run(self.stage(quantity), scratch);
        copy(&scratch.values, out);
    }

    /// [`Program::evaluate`], a table lookup outside its data the typed error (not NaN,
    /// which a solve would report as something else).
    fn evaluate_checked(
        &self,
        quantity: Quantity,
        t: f64,
        velocity_state: &[f64],
        out: &mut [f64],
    ) -> Result<(), SystemError> {
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_velocity_state(scratch, t, velocity_state);
        self.run_checked(quantity, scratch, out)
    }

    /// A velocity-form quantity at a state `[q, p, m_s]` (q̇ recovered from p) into `out`.
    pub fn evaluate_at_state(
        &self,
        quantity: Quantity,
        t: f64,
        state: &[f64],
        out: &mut [f64],
    ) -> Result<(), SystemError> {
        if self.solved_numerically(quantity) {
            let mut velocity_state = state.to_vec();
            let n = self.coordinate_count();
            let velocities = velocity_state.get_mut(n..2 * n).unwrap_or_default();
            self.velocities(t, state, velocities)?;
            return self.accelerations(t, &velocity_state, out);
        }
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_state(scratch, t, state)?;
        self.run_checked(quantity, scratch, out)
    }

    /// Runs the stage of `quantity` on the loaded `scratch` into `out`; a table lookup
    /// outside its data is the typed error.
    fn run_checked(
        &self,
        quantity: Quantity,
        scratch: &mut Scratch,
        out: &mut [f64],
    ) -> Result<(), SystemError> {
        self.run(self.stage(quantity), scratch);
        if let Some(error) = scratch.outside.take() {
            return Err(error);
        }
        copy(&scratch.values, out);
        Ok(())
    }

    /// Whether `quantity` is one the derivation leaves to a numerical solve (q̈ beyond the
    /// closed form).
    fn solved_numerically(&self, quantity: Quantity) -> bool {
        quantity.spec().evaluated == Evaluated::SolvedOrNumeric
            && self.stage(quantity).roots.is_empty()
    }

    /// q̈ at a velocity state `[q, q̇, m_s]` into `out`: M q̈ = rhs (eq. 6) solved by
    /// Cholesky.
    pub fn accelerations(
        &self,
        t: f64,
        velocity_state: &[f64],
        out: &mut [f64],
    ) -> Result<(), SystemError> {
        let n = self.coordinate_count();
        let mut matrix = vec![f64::NAN; n * n];
        self.evaluate_checked(Quantity::MassMatrix, t, velocity_state, &mut matrix)?;
        let mut rhs = vec![f64::NAN; n];
        self.evaluate_checked(Quantity::AccelerationRhs, t, velocity_state, &mut rhs)?;
        if !cholesky_solve(&mut matrix, &mut rhs, n) {
            return Err(SystemError::SingularMassMatrix);
        }
        copy(&rhs, out);
        Ok(())
    }

    /// The first knot time of a table of t (docs/tables.md#knots-are-switches), sample
    /// time of a sampled input (docs/inputs.md#sampled-inputs) or landing time
    /// ([`Program::land_on`]) after `after`.
    pub fn next_stop_time(&self, after: f64) -> Option<f64> {
        let landing = self.landings.partition_point(|&t| t <= after);
        let next = self
            .stops
            .iter()
            .map(|(orders, slope, offset)| {
                let orders: Vec<&Table> = orders.iter().map(|t| &**t).collect();
                next_knot_time_read(&orders, *slope, *offset, after)
            })
            .fold(self.next_sample_time(after), f64::min)
            .min(self.landings.get(landing).copied().unwrap_or(f64::INFINITY));
        (next < f64::INFINITY).then_some(next)
    }

    /// Makes `times` stop times of the run (as a table's knots are): the steppers land on
    /// each exactly and restart there, so that a point is recorded at each (a fit's data
    /// times in a scene, docs/sensitivities.md#fitting-a-scene). The times not finite are
    /// dropped; the rest are sorted.
    pub fn land_on(&mut self, times: &[f64]) {
        self.landings = times.iter().copied().filter(|t| t.is_finite()).collect();
        self.landings.sort_by(f64::total_cmp);
        self.landings.dedup();
    }

    /// The angle from gimbal lock of the spatial rigid bodies' Euler sequences at
    /// `(t, state)` (`varmass_core::math::singular_attitude_distance`); `None` without them.
    pub fn singular_attitude_distance(&self, t: f64, state: &[f64]) -> Option<f64> {
        if self.d.euler_middles.is_empty() {
            return None;
        }
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_positions(scratch, t, state);
        self.run(&self.attitudes, scratch);
        let middles: Vec<(f64, bool)> = (scratch.values.iter())
            .zip(&self.d.euler_middles)
            .map(|(&angle, &(_, proper))| (angle, proper))
            .collect();
        Some(singular_attitude_distance(&middles))
    }

    /// The value of the pool's table `table` (`ExprPool::table_name` names it) at
    /// `argument`, by its interpolant and outside rule; a lookup outside its data (or a NaN
    /// argument, or an unknown table) is the typed error generated code returns.
    pub fn table_value(&self, table: u16, argument: f64) -> Result<f64, SystemError> {
        match self.d.pool.table(table, 0).map(|t| t.value(argument)) {
            Some(Ok(value)) => Ok(value),
            _ => Err(SystemError::TableOutside {
                table: super::names::intern(self.d.pool.table_name(table)),
                argument,
            }),
        }
    }

    /// The number of switching functions (docs/mechanics.md#switches).
    pub fn switch_count(&self) -> usize {
        self.switch_names.len()
    }

    /// The DSL text of switching function `index`.
    pub fn switch_name(&self, index: usize) -> Option<&str> {
        self.switch_names.get(index).map(String::as_str)
    }

    /// The switching functions at a velocity state `[q, q̇, m_s]` into `out`.
    pub fn switching_functions(&self, t: f64, velocity_state: &[f64], out: &mut [f64]) {
        self.switch_values(t, velocity_state, None, out);
    }

    /// The anchors of the switches at the knots of tables of the state (their arguments'
    /// knot brackets, `varmass_core::table::knot_bracket_read`) into `anchors`; the other
    /// switches' are left alone.
    pub fn switch_anchors(&self, t: f64, velocity_state: &[f64], anchors: &mut [f64]) {
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_velocity_state(scratch, t, velocity_state);
        self.run(&self.switches, scratch);
        let first = scratch.values.len() - self.switch_tables.len();
        for (i, table) in self.switch_tables.iter().enumerate() {
            if let Some(anchor) = anchors.get_mut(first + i) {
                *anchor = knot_bracket_read(table, scratch.values[first + i]);
            }
        }
    }

    /// The switching functions with the anchors of [`Program::switch_anchors`].
    pub fn anchored_switching_functions(
        &self,
        t: f64,
        velocity_state: &[f64],
        anchors: &[f64],
        out: &mut [f64],
    ) {
        self.switch_values(t, velocity_state, Some(anchors), out);
    }

    /// The switching functions, a table's anchored at `anchors` or (`None`) at the point.
    fn switch_values(
        &self,
        t: f64,
        velocity_state: &[f64],
        anchors: Option<&[f64]>,
        out: &mut [f64],
    ) {
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_velocity_state(scratch, t, velocity_state);
        self.run(&self.switches, scratch);
        let first = scratch.values.len() - self.switch_tables.len();
        for (i, table) in self.switch_tables.iter().enumerate() {
            let x = scratch.values[first + i];
            let anchor = anchors
                .and_then(|a| a.get(first + i).copied())
                .unwrap_or_else(|| knot_bracket_read(table, x));
            scratch.values[first + i] = knot_gap_read(table, x, anchor);
        }
        copy(&scratch.values, out);
    }

    /// The number of flows (`outflow` and `inflow` statements).
    pub fn flow_count(&self) -> usize {
        self.d.flow_rates.len()
    }

    /// Flow `index` as the model declares it (``inflow `cart` ``).
    pub fn flow_name(&self, index: usize) -> Option<&str> {
        self.d.flow_names.get(index).map(String::as_str)
    }

    /// The rate of flow `index` at a velocity state `[q, q̇, m_s]` (NaN past the last).
    pub fn flow_rate(&self, index: usize, t: f64, velocity_state: &[f64]) -> f64 {
        if index >= self.flow_count() {
            return f64::NAN;
        }
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_velocity_state(scratch, t, velocity_state);
        self.run(&self.flows, scratch);
        scratch.values.get(index).copied().unwrap_or(f64::NAN)
    }

    fn stage(&self, quantity: Quantity) -> &Stage {
        &self.quantities[quantity.index()]
    }

    /// Evaluates `stage` on the loaded environment into `scratch.values`; a table lookup
    /// outside its data (NaN values) is remembered in `scratch.outside` for the fallible
    /// methods to report.
    fn run(&self, stage: &Stage, scratch: &mut Scratch) {
        let Scratch {
            env,
            values,
            outside,
        } = scratch;
        values.clear();
        values.resize(stage.roots.len(), f64::NAN);
        match self.evaluation {
            Evaluation::Tape => {
                stage.tape.eval(env, values);
                note_outside(&stage.tape, outside);
            }
            Evaluation::Tree => {
                // One-root tapes compiled at each call (not `ExprPool::eval`, whose tables
                // extrapolate for the checks).
                for (value, root) in values.iter_mut().zip(&stage.roots) {
                    let tape = self.d.pool.compile(&[*root]);
                    tape.eval(env, std::slice::from_mut(value));
                    note_outside(&tape, outside);
                }
            }
        }
    }

    /// Sets t, q and the state masses, then the law masses.
    fn load_positions(&self, scratch: &mut Scratch, t: f64, state: &[f64]) {
        scratch.outside = None;
        let n = self.coordinate_count();
        let env = &mut scratch.env;
        set(env, self.d.time.index(), t);
        for (a, c) in self.d.coordinates.iter().enumerate() {
            set(env, c.q.index(), component(state, a));
        }
        let state_masses = self.d.masses.iter().take(self.state_mass_count());
        for (k, m) in state_masses.enumerate() {
            set(env, m.symbol.index(), component(state, 2 * n + k));
        }
        self.load_held(scratch, state);
        self.run(&self.laws, scratch);
        for (slot, value) in self.law_slots.iter().zip(&scratch.values) {
            set(&mut scratch.env, *slot, *value);
        }
    }

    /// Loads t, q, the masses, and the middle block of `values` (q̇ or p) into the slot of
    /// the symbol `second` picks of each coordinate.
    fn load_with(
        &self,
        scratch: &mut Scratch,
        t: f64,
        values: &[f64],
        second: fn(&Coordinate) -> Symbol,
    ) {
        self.load_positions(scratch, t, values);
        let n = self.coordinate_count();
        for (a, c) in self.d.coordinates.iter().enumerate() {
            set(
                &mut scratch.env,
                second(c).index(),
                component(values, n + a),
            );
        }
    }

    /// Loads a velocity state `[q, q̇, m_s]`.
    fn load_velocity_state(&self, scratch: &mut Scratch, t: f64, velocity_state: &[f64]) {
        self.load_with(scratch, t, velocity_state, |c| c.velocity);
    }

    /// Loads a state `[q, p, m_s]` and the velocities recovered from it.
    fn load_state(&self, scratch: &mut Scratch, t: f64, state: &[f64]) -> Result<(), SystemError> {
        self.load_with(scratch, t, state, |c| c.momentum);
        let n = self.coordinate_count();
        self.run(&self.velocities, scratch);
        // A table without a value is the cause of the NaNs below, not a singular M.
        if let Some(error) = scratch.outside.take() {
            return Err(error);
        }
        let Scratch { env, values, .. } = scratch;
        if self.numeric {
            let split = (n * n).min(values.len());
            let (matrix, offset) = values.split_at_mut(split);
            for (a, b) in offset.iter_mut().enumerate() {
                *b = component(state, n + a) - *b;
            }
            if !cholesky_solve(matrix, offset, n) {
                return Err(SystemError::SingularMassMatrix);
            }
            values.drain(..split);
        }
        let inputs_finite = state.iter().all(|x| x.is_finite());
        for (c, v) in self.d.coordinates.iter().zip(values.iter()) {
            // A closed-form q̇ that is not finite at a finite state divided by det M = 0.
            if inputs_finite && !v.is_finite() {
                return Err(SystemError::SingularMassMatrix);
            }
            set(env, c.velocity.index(), *v);
        }
        Ok(())
    }

    fn read_velocities(&self, env: &[f64], out: &mut [f64]) {
        for (o, c) in out.iter_mut().zip(&self.d.coordinates) {
            *o = env.get(c.velocity.index()).copied().unwrap_or(f64::NAN);
        }
    }
}

/// The environment with the parameter values in their slots (NaN elsewhere), after
/// checking the parameters against the model.
fn parameter_env(
    d: &Derivation,
    used: &[String],
    parameters: &[(&str, f64)],
) -> Result<Vec<f64>, ProgramError> {
    let names: Vec<String> = d.parameters.iter().map(|(n, _)| n.clone()).collect();
    let mut env = vec![f64::NAN; d.pool.symbols().len()];
    for (name, value) in parameters {
        let Some((_, symbol)) = d.parameters.iter().find(|(n, _)| n == name) else {
            let candidates: Vec<&str> = names.iter().map(String::as_str).collect();
            return Err(ProgramError::UnknownParameter {
                name: name.to_string(),
                suggestion: closest(name, &candidates).map(str::to_string),
                parameters: names,
            });
        };
        if !value.is_finite() {
            return Err(ProgramError::NonFiniteParameter {
                name: name.to_string(),
                value: *value,
            });
        }
        set(&mut env, symbol.index(), *value);
    }
    let missing: Vec<String> = used
        .iter()
        .filter(|used| !parameters.iter().any(|(name, _)| name == *used))
        .cloned()
        .collect();
    if missing.is_empty() {
        Ok(env)
    } else {
        Err(ProgramError::MissingParameters {
            missing,
            parameters: names,
        })
    }
}

/// The switching functions of `d` with their names: the non-smooth points of its
/// equations, then one anchored switch per call of a table of the state (its argument,
/// watched against the knot bracket it is anchored in), with those tables in call order.
fn switches(d: &mut Derivation) -> (Vec<Id>, Vec<String>, Vec<Vec<Arc<Table>>>) {
    let mut roots = varmass_symbolic::mechanics::switching_functions(d);
    let mut names: Vec<String> = roots
        .iter()
        .map(|g| d.pool.display(*g).to_string())
        .collect();
    let mut tables = Vec::new();
    for s in varmass_symbolic::mechanics::table_switches(d) {
        let orders = (0..=s.order).map(|order| d.pool.table(s.table, order).map(Arc::clone));
        let Some(orders) = orders.collect::<Option<Vec<_>>>() else {
            continue;
        };
        tables.push(orders);
        let name = d.pool.table_name(s.table);
        names.push(format!(
            "the knots of {name}({})",
            d.pool.display(s.argument)
        ));
        roots.push(s.argument);
    }
    (roots, names, tables)
}

/// The tables of t called by `roots` (each the orders read, 0 to the highest), and the
/// slope and offset of each one's argument (they are made of parameters only), slope then
/// offset per table.
fn stop_tables(d: &mut Derivation, roots: &[&[Id]]) -> (Vec<Vec<Arc<Table>>>, Vec<Id>) {
    let all: Vec<Id> = roots.iter().flat_map(|r| r.iter().copied()).collect();
    let mut tables = Vec::new();
    let mut arguments = Vec::new();
    for t in time_tables(d, &all) {
        let orders = (0..=t.order).map(|order| d.pool.table(t.table, order).map(Arc::clone));
        if let Some(orders) = orders.collect::<Option<Vec<_>>>() {
            tables.push(orders);
            arguments.extend([t.slope, t.offset]);
        }
    }
    (tables, arguments)
}

/// Each table of t with its argument's slope and offset at the parameter values of `env`.
fn stop_values(
    tables: &[Vec<Arc<Table>>],
    arguments: &Stage,
    env: &[f64],
) -> Vec<(Vec<Arc<Table>>, f64, f64)> {
    let mut values = vec![f64::NAN; arguments.roots.len()];
    arguments.tape.eval(env, &mut values);
    tables
        .iter()
        .zip(values.chunks_exact(2))
        .map(|(orders, v)| (orders.clone(), v[0], v[1]))
        .collect()
}

/// Remembers the first table lookup of `tape`'s last evaluation that had no value, as the
/// typed error generated code returns.
fn note_outside(tape: &Tape, outside: &mut Option<SystemError>) {
    if outside.is_some() {
        return;
    }
    if let Some((name, argument)) = tape.outside() {
        *outside = Some(SystemError::TableOutside {
            table: super::names::intern(name),
            argument,
        });
    }
}

fn set(env: &mut [f64], slot: usize, value: f64) {
    if let Some(s) = env.get_mut(slot) {
        *s = value;
    }
}

fn component(values: &[f64], index: usize) -> f64 {
    values.get(index).copied().unwrap_or(f64::NAN)
}

fn copy(from: &[f64], to: &mut [f64]) {
    for (t, f) in to.iter_mut().zip(from) {
        *t = *f;
    }
}

/// The tables and inputs a program cannot be made without: every runtime table's data and
/// every input's law must have been given (`--table`, `--input`, Python's arrays).
fn check_given(d: &Derivation) -> Result<(), ProgramError> {
    if let Some(table) = d.tables.iter().find(|t| t.runtime) {
        return Err(ProgramError::RuntimeTableWithoutData {
            name: table.name.clone(),
        });
    }
    let lawless = d.inputs.iter().find(|i| i.held.is_none());
    if let Some(input) = lawless.filter(|i| d.pool.input_law(i.index).is_none()) {
        return Err(ProgramError::InputWithoutLaw {
            name: input.name.clone(),
        });
    }
    Ok(())
}
