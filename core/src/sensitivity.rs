//! Forward sensitivities (docs/sensitivities.md): the derivatives of the state with respect
//! to parameters and to entries of the initial state, integrated with it.
//!
//! For y' = f(t, y, θ) with y(t₀) = y₀(θ), a column s = ∂y/∂w of the sensitivity matrix (w a
//! parameter θ_j or an initial entry y₀,i) obeys the variational equation
//!
//! ```text
//! s' = J_y s + ∂f/∂w,     s(t₀) = ∂y₀/∂w
//! ```
//!
//! with ∂f/∂w = column j of [`VariableMassSystem::parameter_jacobian`] for a parameter and 0
//! for an initial entry, and s(t₀) = 0 for a parameter (the initial state is given as a
//! state `[q, p, m_s]`, fixed) and the unit vector e_i for the initial entry i. [`Sensitive`]
//! makes the system whose state is `[y, s₁, …, s_K]` (`SA = S (1 + K)`, K columns), so that
//! the Runge–Kutta steppers, explicit and implicit, integrate both with one step-size
//! control, the error control covering the sensitivities too (CVODES's `errconS = true`;
//! [`Sensitive::with_error_control`] leaves them out).
//!
//! At a switch of the equations (`sign`, `abs`, `min`, `max`, a table of the state's knots)
//! whose time moves with a column, the run hands the crossing to
//! [`VariableMassSystem::cross_switches`] and the columns jump (`switches.rs`), from the
//! switches' gradients the system gives ([`VariableMassSystem::switch_gradient`]).
//!
//! What is not handled yet is refused, never integrated wrongly: at construction a system
//! with switching functions but no gradients of them (a hand-written system), sampled
//! inputs (a sample replaces state entries) or what its [`VariableMassSystem::sensitivity_obstacle`]
//! names (no symbolic Jacobians, inputs, a table of t whose knots move with a parameter, a
//! support); the Taylor stepper on a system without recurrences over tangents and the
//! variational one (it integrates the Lagrange side) at theirs; a run of phases at a change
//! it cannot carry the columns across (`phases.rs`: an event without a gradient).
//! Knots of tables of t at fixed times
//! (their slope and offset free of the parameters) leave s continuous.

use alloc::vec::Vec;
use core::cell::{RefCell, RefMut};

use nalgebra::{SMatrix, SVector};

use crate::system::{SystemError, VariableMassSystem};
use crate::tangent::Tangent;

mod phases;
mod switches;
mod taylor;

/// A column of the sensitivity matrix: what the state is differentiated with respect to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// A parameter, by its name in [`VariableMassSystem::parameter_names`].
    Parameter(&'static str),
    /// An entry of the initial state, by its index: of `[q, p, m_s]` for
    /// [`Sensitive::start`] (p₀ given), of the velocity state `[q, q̇, m_s]` for
    /// [`Sensitive::start_at_velocities`] (q̇₀ given).
    Initial(usize),
    /// A parameter of another phase's system that this system's equations do not hold
    /// (∂f/∂w = 0 here): the burn rate in a coast that follows the burn, say, whose own
    /// `mu` is 0 and not the burn's (`Sensitive::across` carries the column over).
    Elsewhere,
}

/// The derivatives at a crossing with respect to one column w ([`Sensitive::at_crossing`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AtCrossing<const S: usize> {
    /// dτ/dw, the crossing time's.
    pub time: f64,
    /// d y(τ)/dw, the state's there (the crossing's motion included).
    pub state: SVector<f64, S>,
}

/// Why [`Sensitive::across`] cannot carry the sensitivities over a switch.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum CrossingError {
    /// A system could not be evaluated at the crossing.
    #[error(transparent)]
    System(#[from] SystemError),
    /// The crossing is tangent (f_i = 0): its time has no derivative.
    #[error("the crossing is tangent: its time has no derivative")]
    Tangent,
    /// The two systems' columns differ in number.
    #[error("the systems have {0} and {1} columns")]
    Columns(usize, usize),
    /// The entry is past the state.
    #[error("entry {0} is past the state")]
    Entry(usize),
}

/// Why a [`Sensitive`] system cannot be made.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SensitivityError {
    /// `SA` is not `S · (1 + K)` for the K columns asked.
    #[error("the augmented state has {augmented} entries, but {columns} columns of a state of {state} need {}", state * (1 + columns))]
    Size {
        /// The system's S.
        state: usize,
        /// K.
        columns: usize,
        /// The SA given.
        augmented: usize,
    },
    /// A parameter the system does not name.
    #[error("no parameter `{name}` (the system's parameters with sensitivities: {known:?})")]
    UnknownParameter {
        /// The name asked for.
        name: &'static str,
        /// The names the system has.
        known: &'static [&'static str],
    },
    /// An initial entry past the state.
    #[error("initial entry {index} is past the state's {state} entries")]
    UnknownEntry {
        /// The index asked for.
        index: usize,
        /// S.
        state: usize,
    },
    /// The system has what the sensitivities do not follow yet: switching functions,
    /// sampled inputs, or what its [`VariableMassSystem::sensitivity_obstacle`] names.
    #[error("sensitivities across {0} are not supported yet")]
    Unsupported(&'static str),
}

/// A column as the system resolves it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Resolved {
    /// The parameter's column of the parameter Jacobian.
    Parameter(usize),
    /// The initial entry.
    Initial(usize),
    /// A parameter held elsewhere: nothing here.
    Elsewhere,
}

impl Resolved {
    /// The parameter's column, if the column is a parameter's.
    fn parameter(self) -> Option<usize> {
        match self {
            Resolved::Parameter(j) => Some(j),
            Resolved::Initial(_) | Resolved::Elsewhere => None,
        }
    }
}

/// `Sys` with the sensitivity columns after its state: `[y, s₁, …, s_K]`, `SA = S (1 + K)`.
/// Every method but the state rate, the Taylor coefficients, the crossings of switches and
/// phases (and the Jacobian, left to the trait's differences) reads the first S entries and
/// forwards to `Sys`.
pub struct Sensitive<Sys, const S: usize> {
    system: Sys,
    /// The columns, resolved against the system's parameters.
    columns: Vec<Resolved>,
    /// The parameters' columns of the parameter Jacobian the columns read, increasing.
    wanted: Vec<usize>,
    /// The parameter Jacobian's S × P, kept between calls.
    scratch: RefCell<Vec<f64>>,
    /// Whether the adaptive steppers' error control weighs the columns too (the default).
    error_control: bool,
    /// The Taylor passes' working memory (`sensitivity/taylor.rs`).
    taylor: taylor::TaylorPasses<S>,
}

/// A copy with its own, fresh working memory (what a run of phases needs: a support's
/// phases, `support::phases` and `rail::phases`, each hold a copy).
impl<Sys: Clone, const S: usize> Clone for Sensitive<Sys, S> {
    fn clone(&self) -> Self {
        Sensitive {
            system: self.system.clone(),
            columns: self.columns.clone(),
            wanted: self.wanted.clone(),
            scratch: RefCell::new(alloc::vec![0.0; self.scratch.borrow().len()]),
            error_control: self.error_control,
            taylor: Default::default(),
        }
    }
}

impl<Sys, const S: usize> Sensitive<Sys, S> {
    /// The system itself.
    pub fn system(&self) -> &Sys {
        &self.system
    }

    /// Gives the system back.
    pub fn into_system(self) -> Sys {
        self.system
    }

    /// The number of columns K.
    pub fn columns(&self) -> usize {
        self.columns.len()
    }
}

/// A pass's tangents into the augmented vector `out`: the values into its first S
/// entries, lane `l` into the entries of column `columns.start + l`.
fn scatter<const W: usize, const S: usize, const SA: usize>(
    tangents: &[Tangent<W>; S],
    columns: core::ops::Range<usize>,
    out: &mut SVector<f64, SA>,
) {
    for (i, x) in tangents.iter().enumerate() {
        out[i] = x.v;
        for (lane, c) in columns.clone().enumerate() {
            out[S * (1 + c) + i] = x.d[lane];
        }
    }
}

/// The first S entries of an augmented state.
fn head<const S: usize, const SA: usize>(state: &SVector<f64, SA>) -> SVector<f64, S> {
    state.fixed_rows::<S>(0).into_owned()
}

/// Column `c` of an augmented state, s_c = ∂y/∂w_c.
fn column<const S: usize, const SA: usize>(state: &SVector<f64, SA>, c: usize) -> SVector<f64, S> {
    state.fixed_rows::<S>(S * (1 + c)).into_owned()
}

impl<Sys, const S: usize> Sensitive<Sys, S> {
    /// `system` with the sensitivity `columns`, checked against `SA` (the augmented state's
    /// length) and what the system provides.
    pub fn new<const N: usize, const SA: usize>(
        system: Sys,
        columns: &[Column],
    ) -> Result<Self, SensitivityError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if SA != S * (1 + columns.len()) {
            return Err(SensitivityError::Size {
                state: S,
                columns: columns.len(),
                augmented: SA,
            });
        }
        if system.switch_count() > 0 && !system.has_switch_gradients() {
            return Err(SensitivityError::Unsupported("switches"));
        }
        if let Some(reason) = system.sensitivity_obstacle() {
            return Err(SensitivityError::Unsupported(reason));
        }
        if Sys::HELD > 0 {
            return Err(SensitivityError::Unsupported("sampled inputs"));
        }
        let known = system.parameter_names();
        let resolve = |column: &Column| match *column {
            Column::Parameter(name) => (known.iter().position(|k| *k == name))
                .map(Resolved::Parameter)
                .ok_or(SensitivityError::UnknownParameter { name, known }),
            Column::Initial(index) if index < S => Ok(Resolved::Initial(index)),
            Column::Initial(index) => Err(SensitivityError::UnknownEntry { index, state: S }),
            Column::Elsewhere => Ok(Resolved::Elsewhere),
        };
        let columns: Vec<Resolved> = columns.iter().map(resolve).collect::<Result<_, _>>()?;
        let mut wanted: Vec<usize> = columns.iter().filter_map(|c| c.parameter()).collect();
        wanted.sort_unstable();
        wanted.dedup();
        let scratch = RefCell::new(alloc::vec![0.0; S * known.len()]);
        Ok(Sensitive {
            system,
            columns,
            wanted,
            scratch,
            error_control: true,
            taylor: Default::default(),
        })
    }

    /// This system with the columns in the adaptive steppers' error control (`true`, the
    /// default: CVODES's `errconS = true`) or left out of it (`false`: the steps are those
    /// of the state alone, the columns' own error unchecked — cheaper where the columns
    /// would ask for smaller steps than the state, which docs/sensitivities.md#cost
    /// measures).
    pub fn with_error_control(self, columns: bool) -> Self {
        Self {
            error_control: columns,
            ..self
        }
    }

    /// The augmented initial state of `state`: s(t₀) = 0 for a parameter (the state
    /// `[q, p, m_s]` held fixed: a start given by its velocities, whose momenta move with a
    /// mass parameter, is [`Self::start_at_velocities`]), e_i for the initial entry i.
    pub fn start<const SA: usize>(&self, state: &SVector<f64, S>) -> SVector<f64, SA> {
        let mut out = SVector::<f64, SA>::zeros();
        out.fixed_rows_mut::<S>(0).copy_from(state);
        for (c, resolved) in self.columns.iter().enumerate() {
            if let Resolved::Initial(i) = resolved {
                out[S * (1 + c) + i] = 1.0;
            }
        }
        out
    }

    /// The augmented initial state from a velocity state `[q, q̇, m_s]` held fixed: the
    /// momenta p₀ = P(q, q̇, θ) then move with what moves the start. For a parameter,
    /// ∂p₀/∂θ = P_θ = −M (∂q̇/∂θ at a fixed state), from the mass matrix and the parameter
    /// Jacobian's q̇ rows (q̇ = M⁻¹ (p − b(θ)) gives ∂q̇/∂θ = −M⁻¹ P_θ). For an initial
    /// entry, [`Column::Initial`]`(i)` is entry i of the *velocity* state: a velocity q̇_a
    /// moves p₀ by M e_a; a coordinate or a state mass moves itself and p₀ by
    /// −M (∂q̇/∂y_i at fixed p), the Jacobian's q̇ rows. ([`Self::start`] holds p₀ fixed
    /// instead, its entries those of `[q, p, m_s]`.)
    pub fn start_at_velocities<const N: usize, const SA: usize>(
        &self,
        t: f64,
        velocity_state: &SVector<f64, S>,
    ) -> Result<SVector<f64, SA>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let state = self.system.momentum_state(t, velocity_state);
        let mut out = SVector::<f64, SA>::zeros();
        out.fixed_rows_mut::<S>(0).copy_from(&state);
        let (jacobian, scratch) = self.jacobians::<N, SA>(t, &out)?;
        let mass = self.system.mass_matrix(t, &state);
        for c in 0..self.columns() {
            // The entry the column moves directly, and ∂q̇/∂w at a fixed state `[q, p, m_s]`.
            let mut dv = SVector::<f64, N>::zeros();
            let mut own = None;
            match self.columns[c] {
                Resolved::Initial(i) if (N..2 * N).contains(&i) => dv[i - N] = -1.0,
                Resolved::Initial(i) => {
                    own = Some(i);
                    dv = jacobian.fixed_view::<N, 1>(0, i).into_owned();
                }
                Resolved::Parameter(_) | Resolved::Elsewhere => {
                    self.add_parameter(c, &scratch, dv.iter_mut())
                }
            }
            let first = S * (1 + c);
            if let Some(i) = own {
                out[first + i] = 1.0;
            }
            let dp = -(mass * dv);
            for (a, value) in dp.iter().enumerate() {
                out[first + N + a] = *value;
            }
        }
        Ok(out)
    }

    /// ∂y_i/∂w_c of an augmented state: entry `i` of column `c`; `None` past the state or
    /// the columns.
    pub fn sensitivity<const SA: usize>(
        &self,
        state: &SVector<f64, SA>,
        i: usize,
        c: usize,
    ) -> Option<f64> {
        (i < S && c < self.columns()).then(|| state[S * (1 + c) + i])
    }

    /// ∂q̇/∂w for every column at an augmented state: q̇ = q̇(y, θ) (q̇ = M⁻¹ (p − b)), so
    /// ∂q̇/∂w = (∂q̇/∂y) s + ∂q̇/∂w|_y, the first N rows of the Jacobian and of the parameter
    /// Jacobian (0 for an initial entry or a parameter held elsewhere).
    pub fn velocity_sensitivities<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
    ) -> Result<Vec<SVector<f64, N>>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let (jacobian, scratch) = self.jacobians::<N, SA>(t, state)?;
        let rows = jacobian.fixed_rows::<N>(0);
        let columns = (0..self.columns()).map(|c| {
            let mut dv: SVector<f64, N> = rows * column::<S, SA>(state, c);
            self.add_parameter(c, &scratch, dv.iter_mut());
            dv
        });
        Ok(columns.collect())
    }

    /// J_y and, when a column is a parameter's, the parameter Jacobian (S × P, row-major,
    /// in the scratch) at the state part of `state`.
    fn jacobians<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
    ) -> Result<(SMatrix<f64, S, S>, RefMut<'_, Vec<f64>>), SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let y = head::<S, SA>(state);
        let mut scratch = self.scratch.borrow_mut();
        let (jacobian, given) = (self.system).jacobians(t, &y, &self.wanted, &mut scratch)?;
        if !given {
            return Err(SystemError::NoParameterJacobian);
        }
        Ok((jacobian, scratch))
    }

    /// Adds ∂f/∂w_c (column c's parameter's column of the parameter Jacobian in `scratch`,
    /// nothing for another column) to the rows `rows` iterates, from the first on.
    fn add_parameter<'a>(
        &self,
        c: usize,
        scratch: &[f64],
        rows: impl Iterator<Item = &'a mut f64>,
    ) {
        let Some(j) = self.columns[c].parameter() else {
            return;
        };
        let count = scratch.len() / S.max(1);
        for (i, d) in rows.enumerate() {
            *d += scratch[i * count + j];
        }
    }

    /// At a crossing of state entry `i` through a fixed value at `(t, state)` — where an
    /// [`Event::state_reaches`](crate::Event::state_reaches) ended a run, say the apogee
    /// (a vertical momentum reaching 0) — for each column w the crossing time's derivative
    /// and the state's there: with g = y_i − value (g_y = e_i, g_w = 0),
    ///
    /// ```text
    /// dτ/dw = −s_i / f_i,     d y(τ)/dw = s + f dτ/dw
    /// ```
    ///
    /// (g(τ(w), y(τ(w); w)) = 0 differentiated). `Ok(None)` where f_i = 0 (the crossing is
    /// tangent and τ has no derivative) or `i` is past the state.
    pub fn at_crossing<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
        i: usize,
    ) -> Result<Option<Vec<AtCrossing<S>>>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if i >= S {
            return Ok(None);
        }
        let rate = self.system.state_rate(t, &head::<S, SA>(state))?;
        if rate[i] == 0.0 {
            return Ok(None);
        }
        let columns = (0..self.columns()).map(|c| {
            let s = column::<S, SA>(state, c);
            let time = -s[i] / rate[i];
            AtCrossing {
                time,
                state: s + rate * time,
            }
        });
        Ok(Some(columns.collect()))
    }

    /// Across a switch from this system to `next` where state entry `i` crosses a fixed
    /// value at `(t, state)` — a phase change on an event, the state carried unchanged, as
    /// a burn that ends when the propellant (a state mass) reaches 0 — the augmented state
    /// to start `next` from: the switch time moves with w (dτ/dw = −s_i⁻/f_i⁻, f⁻ this
    /// system's rate there), and the state after it with it, so each column jumps:
    ///
    /// ```text
    /// s⁺ = s⁻ + (f⁻ − f⁺) dτ/dw
    /// ```
    ///
    /// (y(τ + δ) before and after the switch differ by (f⁻ − f⁺) δ to first order). The
    /// columns must mean the same in both systems (the same list, a parameter that `next`
    /// does not hold given as [`Column::Elsewhere`] there).
    pub fn across<Next, const N: usize, const SA: usize>(
        &self,
        next: &Sensitive<Next, S>,
        t: f64,
        state: &SVector<f64, SA>,
        i: usize,
    ) -> Result<SVector<f64, SA>, CrossingError>
    where
        Sys: VariableMassSystem<N, S>,
        Next: VariableMassSystem<N, S>,
    {
        if self.columns() != next.columns() {
            return Err(CrossingError::Columns(self.columns(), next.columns()));
        }
        if i >= S {
            return Err(CrossingError::Entry(i));
        }
        let y = head::<S, SA>(state);
        let before = self.system.state_rate(t, &y)?;
        let after = next.system.state_rate(t, &y)?;
        if before[i] == 0.0 {
            return Err(CrossingError::Tangent);
        }
        let mut out = *state;
        for c in 0..self.columns() {
            let s = column::<S, SA>(state, c);
            let dt = -s[i] / before[i];
            let jumped = s + (before - after) * dt;
            out.fixed_rows_mut::<S>(S * (1 + c)).copy_from(&jumped);
        }
        Ok(out)
    }

    /// [y', J_y s_c + ∂f/∂w_c for each column]: over tangents when the system has them
    /// ([`VariableMassSystem::state_rate_tangents`], one or two columns a pass), else
    /// through the whole Jacobians ([`Self::rate_by_jacobians`]).
    fn augmented_rate<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
    ) -> Result<SVector<f64, SA>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        if self.columns() == 0 {
            let mut out = SVector::<f64, SA>::zeros();
            let rate = self.system.state_rate(t, &head::<S, SA>(state))?;
            out.fixed_rows_mut::<S>(0).copy_from(&rate);
            return Ok(out);
        }
        match self.rate_by_tangents::<N, SA>(t, state) {
            Some(rate) => rate,
            None => self.rate_by_jacobians::<N, SA>(t, state),
        }
    }

    /// The augmented rate over tangents, `None` without them (or without columns): one
    /// column in one pass of 1, more in passes of 2 (the last with a lane unseeded when K is
    /// odd). One width per run: the state rate over tangents is a large function, and two
    /// widths called in turn evict each other from the instruction cache (6-dof rocket,
    /// `benches/sensitivities.rs`: K = 3 in passes of 2 + 1 took 640 ns a rate, in 2 + 2
    /// 490 ns; K = 6 in one pass of 8 1110 ns, in three of 2 720 ns, one of 1 200 ns).
    fn rate_by_tangents<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
    ) -> Option<Result<SVector<f64, SA>, SystemError>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let k = self.columns();
        if k == 0 {
            return None;
        }
        let mut out = SVector::<f64, SA>::zeros();
        let mut first = 0;
        while first < k {
            let pass = match k {
                1 => self.pass::<N, SA, 1>(t, state, first, &mut out),
                _ => self.pass::<N, SA, 2>(t, state, first, &mut out),
            };
            match pass? {
                Ok(done) => first += done,
                Err(error) => return Some(Err(error)),
            }
        }
        Some(Ok(out))
    }

    /// One pass over `Tangent<W>`: the columns from `first` on (at most W) into `out`, and
    /// the state's rate (the same in every pass); how many columns it took.
    fn pass<const N: usize, const SA: usize, const W: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
        first: usize,
        out: &mut SVector<f64, SA>,
    ) -> Option<Result<usize, SystemError>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let columns = first..(first + W).min(self.columns());
        let (y, seeds) = self.seeded::<SA, W>(state, columns.clone());
        let rates = match self.system.state_rate_tangents::<W>(t, &y, &seeds)? {
            Ok(rates) => rates,
            Err(error) => return Some(Err(error)),
        };
        scatter(&rates, columns.clone(), out);
        Some(Ok(columns.count()))
    }

    /// The state's entries as tangents whose lanes are the `columns`' entries, and the
    /// parameter each lane seeds: the input of a pass over `Tangent<W>` (the state rate's,
    /// the Taylor recurrences').
    fn seeded<const SA: usize, const W: usize>(
        &self,
        state: &SVector<f64, SA>,
        columns: core::ops::Range<usize>,
    ) -> ([Tangent<W>; S], [Option<usize>; W]) {
        let mut y: [Tangent<W>; S] = core::array::from_fn(|i| Tangent::constant(state[i]));
        let mut seeds = [None; W];
        for (lane, c) in columns.enumerate() {
            seeds[lane] = self.columns[c].parameter();
            for (i, entry) in y.iter_mut().enumerate() {
                entry.d[lane] = state[S * (1 + c) + i];
            }
        }
        (y, seeds)
    }

    /// The augmented rate through the whole Jacobians: J_y (S × S) times each column plus
    /// the parameter's column of ∂f/∂θ (S × P). What the tangents are held to
    /// (`tests/sensitivities.rs`), and the path of a system without them.
    pub fn rate_by_jacobians<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
    ) -> Result<SVector<f64, SA>, SystemError>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let rate = self.system.state_rate(t, &head::<S, SA>(state))?;
        let (jacobian, scratch) = self.jacobians::<N, SA>(t, state)?;
        let mut out = SVector::<f64, SA>::zeros();
        out.fixed_rows_mut::<S>(0).copy_from(&rate);
        for c in 0..self.columns() {
            let mut ds = jacobian * column::<S, SA>(state, c);
            self.add_parameter(c, &scratch, ds.iter_mut());
            out.fixed_rows_mut::<S>(S * (1 + c)).copy_from(&ds);
        }
        Ok(out)
    }
}

/// Methods that read the first S entries of a state or velocity state, forwarded to `Sys`.
macro_rules! on_head {
    ($($(#[$doc:meta])* fn $name:ident(&self $(, $arg:ident: $ty:ty)*; $vector:ident) -> $out:ty;)*) => {$(
        $(#[$doc])*
        fn $name(&self $(, $arg: $ty)*, $vector: &SVector<f64, SA>) -> $out {
            self.system.$name($($arg,)* &head::<S, SA>($vector))
        }
    )*};
}

/// `Sys` on the first S entries; the state rate augmented with the variational equations.
/// The trait's finite-difference Jacobian serves the implicit steppers over all SA entries;
/// the Taylor stepper expands it by the system's recurrences over tangents.
impl<Sys, const N: usize, const S: usize, const SA: usize> VariableMassSystem<N, SA>
    for Sensitive<Sys, S>
where
    Sys: VariableMassSystem<N, S>,
{
    const COORDINATES: [&'static str; N] = Sys::COORDINATES;
    const MASSES: &'static [&'static str] = Sys::MASSES;
    /// The sensitivity columns sit where held values would, after the state masses, so that
    /// `STATE_MASSES` stays the system's; no sample ever replaces them (`new` refuses a
    /// system with sampled inputs).
    const HELD: usize = SA - S;

    on_head! {
        fn mass(&self, index: usize, t: f64; state) -> f64;
        fn mass_rate(&self, index: usize, t: f64; velocity_state) -> f64;
        fn mass_matrix(&self, t: f64; state) -> SMatrix<f64, N, N>;
        fn momenta(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn lagrangian(&self, t: f64; velocity_state) -> f64;
        fn lagrangian_gradient(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn active_force(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn reactive_thrust(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn impact_force(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn mass_flux_force(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn accelerations(&self, t: f64; velocity_state) -> Result<SVector<f64, N>, SystemError>;
        fn singular_attitude_distance(&self, t: f64; state) -> Option<f64>;
        fn flow_rate(&self, index: usize, t: f64; velocity_state) -> f64;
        fn frozen_force(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn generalized_force(&self, t: f64; velocity_state) -> SVector<f64, N>;
        fn check_masses(&self, t: f64; state) -> Result<(), SystemError>;
        fn velocities(&self, t: f64; state) -> Result<SVector<f64, N>, SystemError>;
        fn hamiltonian(&self, t: f64; state) -> Result<f64, SystemError>;
        fn canonical_rates(&self, t: f64; state)
            -> Result<(SVector<f64, N>, SVector<f64, N>), SystemError>;
        fn power(&self, t: f64; state) -> Result<f64, SystemError>;
    }

    fn next_stop_time(&self, after: f64) -> Option<f64> {
        self.system.next_stop_time(after)
    }

    fn switch_count(&self) -> usize {
        self.system.switch_count()
    }

    /// SA, or without the columns' error control ([`Sensitive::with_error_control`]) the
    /// system's own (S unless it leaves some out too).
    fn controlled_entries(&self) -> usize {
        match self.error_control {
            true => SA,
            false => self.system.controlled_entries().min(S),
        }
    }

    fn switch_name(&self, index: usize) -> Option<&str> {
        self.system.switch_name(index)
    }

    /// The mechanics' state and each column apart (the Taylor stepper's step rule).
    fn measured_block(&self) -> usize {
        S
    }

    fn switching_functions(&self, t: f64, velocity_state: &SVector<f64, SA>, values: &mut [f64]) {
        (self.system).switching_functions(t, &head::<S, SA>(velocity_state), values);
    }

    fn switch_anchors(&self, t: f64, velocity_state: &SVector<f64, SA>, anchors: &mut [f64]) {
        (self.system).switch_anchors(t, &head::<S, SA>(velocity_state), anchors);
    }

    fn anchored_switching_functions(
        &self,
        t: f64,
        velocity_state: &SVector<f64, SA>,
        anchors: &[f64],
        values: &mut [f64],
    ) {
        let head = head::<S, SA>(velocity_state);
        (self.system).anchored_switching_functions(t, &head, anchors, values);
    }

    /// The columns jump where a switch's time moves with them (`switches.rs`).
    fn cross_switches(
        &self,
        crossed: &[usize],
        before: (f64, &SVector<f64, SA>, &SVector<f64, SA>),
        after: (f64, &mut SVector<f64, SA>),
    ) -> Result<(), SystemError> {
        self.jump_at_switches::<N, SA>(crossed, before, after)
    }

    fn flow_count(&self) -> usize {
        self.system.flow_count()
    }

    fn flow_name(&self, index: usize) -> Option<&str> {
        self.system.flow_name(index)
    }

    fn velocity_state(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
    ) -> Result<SVector<f64, SA>, SystemError> {
        let mut out = *state;
        let head = self.system.velocity_state(t, &head::<S, SA>(state))?;
        out.fixed_rows_mut::<S>(0).copy_from(&head);
        Ok(out)
    }

    fn momentum_state(&self, t: f64, velocity_state: &SVector<f64, SA>) -> SVector<f64, SA> {
        let mut out = *velocity_state;
        let head = (self.system).momentum_state(t, &head::<S, SA>(velocity_state));
        out.fixed_rows_mut::<S>(0).copy_from(&head);
        out
    }

    fn state_rate(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
    ) -> Result<SVector<f64, SA>, SystemError> {
        self.augmented_rate(t, state)
    }

    /// The Taylor coefficients of the augmented state, by the system's recurrences over
    /// tangents (`sensitivity/taylor.rs`); `None` (the Taylor stepper refuses the system)
    /// where it has none.
    fn taylor_coefficients(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
        coefficients: &mut [SVector<f64, SA>],
        _scratch: &mut crate::scratch::Scratch,
    ) -> Option<Result<(), SystemError>> {
        self.augmented_taylor::<N, SA>(t, state, coefficients)
    }

    /// The variational stepper would hold the columns (it integrates the Lagrange side);
    /// a run of phases carries them by [`Self::depart`] and [`Self::arrive`].
    fn has_rate_only_state(&self) -> bool {
        true
    }

    /// The columns leaving a phase (`sensitivity/phases.rs`).
    fn depart(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
        end: &crate::departure::PhaseEnd<'_>,
    ) -> Option<Result<crate::departure::Departure, SystemError>> {
        use crate::departure::PhaseEnd;
        match end {
            // An event on a column's entry has no gradient here: refused by the run.
            PhaseEnd::Linear(gradient) if gradient.iter().any(|&(i, _)| i >= S) => None,
            PhaseEnd::Linear(_) => Some(self.departure::<N, SA>(t, state, *end)),
            PhaseEnd::Velocity { coordinate } if *coordinate >= N => None,
            PhaseEnd::Velocity { .. } => Some(self.departure::<N, SA>(t, state, *end)),
            // Only a support knows that its end is smooth or where its rail runs: it
            // resolves these first (`support.rs`); a free system's phase is refused.
            PhaseEnd::Smooth | PhaseEnd::RailTravel => None,
        }
    }

    /// The columns entering a phase (`sensitivity/phases.rs`).
    fn arrive(
        &self,
        t: f64,
        state: &mut SVector<f64, SA>,
        departure: &crate::departure::Departure,
        keep_momenta: bool,
        reset: &[usize],
    ) -> Option<Result<(), SystemError>> {
        Some(self.arrival::<N, SA>(t, state, departure, keep_momenta, reset))
    }
}
