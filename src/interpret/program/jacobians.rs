//! The symbolic Jacobians of the state rate as tapes, for forward sensitivities
//! (docs/sensitivities.md) and the implicit steppers: the blocks generated code assembles
//! (`emit/methods.rs`, `jacobian` and `parameter_jacobian`), here evaluated by one tape and
//! assembled at run time.
//!
//! With v = q̇ = M⁻¹ (p − b) and the blocks at fixed q̇ (mass laws followed) F_x of
//! [ṗ; ṁ_s] and P_x of p, a change dx moves q̇ by dv = −M⁻¹ P_x dx (at fixed p), so
//!
//! ```text
//! ∂[q̇; ṗ, ṁ_s]/∂x = [V_x; F_x + F_v V_x],   V_x = −M⁻¹ P_x,
//! ```
//!
//! for x = q, the state masses (and held inputs), and θ; for x = p, P_p = −I and F_p = 0.
//! The held inputs' rows are 0 (constant between samples), as are a padded state's.

use std::cell::RefCell;

use varmass_core::SystemError;
use varmass_symbolic::mechanics::{sensitivity_obstacle, time_tables, Derivation, Outputs};

use super::super::cholesky::{cholesky_factor, cholesky_substitute};
use super::super::names::intern_list;
use super::{Program, Stage};

/// The Jacobian blocks' tape and what it says of the model.
#[derive(Debug)]
pub(super) struct Jacobians {
    /// F_q, F_v, F_m, P_q, P_m, M, F_θ, P_θ, each row-major, in one stage.
    stage: Stage,
    /// The stages of the blocks with some parameters' columns of F_θ and P_θ only, by those
    /// columns, each compiled when first asked for ([`Program::jacobians`]): the tape holds
    /// only what they read.
    subsets: RefCell<Vec<(Vec<usize>, Stage)>>,
    /// The columns of the state-mass blocks: state masses, then held inputs.
    mass_columns: usize,
    /// The parameters θ, [`Derivation::parameters`] order.
    names: &'static [&'static str],
    /// Why sensitivities cannot follow the model, if they cannot.
    obstacle: Option<&'static str>,
}

impl Jacobians {
    /// The blocks of `d`, if it was derived with the parameter Jacobian
    /// (`Outputs::sensitivities`).
    pub(super) fn new(d: &mut Derivation) -> Option<Self> {
        let j = d.jacobian.as_ref().filter(|j| j.with_parameters)?;
        let roots: Vec<_> = [
            &j.rate_wrt_q,
            &j.rate_wrt_velocity,
            &j.rate_wrt_state_mass,
            &j.momentum_wrt_q,
            &j.momentum_wrt_state_mass,
            &d.mass_matrix,
            &j.rate_wrt_parameter,
            &j.momentum_wrt_parameter,
        ]
        .into_iter()
        .flat_map(|block| block.iter().flatten().copied())
        .collect();
        let mass_columns = j.momentum_wrt_state_mass.first().map_or(0, Vec::len);
        let names: Vec<&str> = d.parameters.iter().map(|(n, _)| n.as_str()).collect();
        let names = intern_list(&names);
        let code = d.code_roots(Outputs::FULL);
        let tables = time_tables(d, &code);
        let obstacle = sensitivity_obstacle(d, &tables);
        Some(Self {
            stage: Stage {
                tape: d.pool.compile(&roots),
                roots,
            },
            subsets: RefCell::new(Vec::new()),
            mass_columns,
            names,
            obstacle,
        })
    }
}

/// The evaluated blocks, as row-major slices.
struct Blocks<'a> {
    fq: &'a [f64],
    fv: &'a [f64],
    fm: &'a [f64],
    pq: &'a [f64],
    pm: &'a [f64],
    mass: &'a [f64],
    ft: &'a [f64],
    pt: &'a [f64],
}

impl<'a> Blocks<'a> {
    /// Splits the stage's values by the sizes of a model of `n` coordinates, `k` state
    /// masses, `c` state-mass columns and `p` parameters.
    fn split(values: &'a [f64], (n, k, c, p): (usize, usize, usize, usize)) -> Option<Self> {
        let mut rest = values;
        let mut take = |len: usize| {
            let (head, tail) = rest.split_at_checked(len)?;
            rest = tail;
            Some(head)
        };
        Some(Self {
            fq: take((n + k) * n)?,
            fv: take((n + k) * n)?,
            fm: take((n + k) * c)?,
            pq: take(n * n)?,
            pm: take(n * c)?,
            mass: take(n * n)?,
            ft: take((n + k) * p)?,
            pt: take(n * p)?,
        })
    }

    /// `[V_x; F_x + F_v V_x]` with V_x = −M⁻¹ P_x, (2n + k) × `columns` row-major, for
    /// the blocks `px` (n × columns) and `fx` ((n + k) × columns; `None`: 0).
    fn columns(
        &self,
        px: &[f64],
        fx: Option<&[f64]>,
        (n, k): (usize, usize),
        columns: usize,
    ) -> Result<Vec<f64>, SystemError> {
        // M factored once, each column substituted.
        let mut factor = self.mass.to_vec();
        if !cholesky_factor(&mut factor, n) {
            return Err(SystemError::SingularMassMatrix);
        }
        let mut v = vec![0.0; n * columns];
        let mut column = vec![0.0; n];
        for c in 0..columns {
            for a in 0..n {
                column[a] = -px[a * columns + c];
            }
            if !cholesky_substitute(&factor, &mut column, n) {
                return Err(SystemError::SingularMassMatrix);
            }
            for a in 0..n {
                v[a * columns + c] = column[a];
            }
        }
        let mut out = v.clone();
        for row in 0..n + k {
            for c in 0..columns {
                let direct = fx.map_or(0.0, |f| f[row * columns + c]);
                let through: f64 = (0..n)
                    .map(|b| self.fv[row * n + b] * v[b * columns + c])
                    .sum();
                out.push(direct + through);
            }
        }
        Ok(out)
    }
}

impl Blocks<'_> {
    /// ∂(state rate)/∂[q, p, m_s, held] of a model of sizes `(n, k, c)`, row-major
    /// `len × len` into `out`: the columns of q, of p (P_p = −I, F_p = 0) and of the state
    /// masses, the padding 0.
    fn state_jacobian(
        &self,
        (n, k, c): (usize, usize, usize),
        len: usize,
        out: &mut [f64],
    ) -> Result<(), SystemError> {
        let minus_identity: Vec<f64> = (0..n * n)
            .map(|i| if i / n == i % n { -1.0 } else { 0.0 })
            .collect();
        let parts = [
            (self.columns(self.pq, Some(self.fq), (n, k), n)?, n, 0),
            (self.columns(&minus_identity, None, (n, k), n)?, n, n),
            (self.columns(self.pm, Some(self.fm), (n, k), c)?, c, 2 * n),
        ];
        out.iter_mut().take(len * len).for_each(|x| *x = 0.0);
        for (part, width, first) in parts {
            place(out, len, &part, width, first);
        }
        Ok(())
    }
}

impl Program {
    /// Whether the program has the symbolic Jacobians (its derivation was made with
    /// `Outputs::sensitivities`): then [`Program::jacobian`] and
    /// [`Program::parameter_jacobian`] evaluate them.
    pub fn has_jacobians(&self) -> bool {
        self.jacobians.is_some()
    }

    /// The parameters θ of [`Program::parameter_jacobian`]'s columns (every parameter of
    /// the derivation, in its order); empty without the Jacobians.
    pub fn parameter_names(&self) -> &'static [&'static str] {
        self.jacobians.as_ref().map_or(&[], |j| j.names)
    }

    /// What of the model forward sensitivities cannot follow, if anything: no Jacobians
    /// (derived without `Outputs::sensitivities`), sampled inputs, switches, an input, a
    /// table of t whose knots move with a parameter.
    pub fn sensitivity_obstacle(&self) -> Option<&'static str> {
        let Some(j) = &self.jacobians else {
            return Some("a model derived without its parameter Jacobian (Outputs::sensitivities)");
        };
        if self.held_count() > 0 {
            return Some("sampled inputs");
        }
        j.obstacle
    }

    /// ∂(state rate)/∂[q, p, m_s, held] at `(t, state)`, row-major `len × len` into `out`
    /// (`len` the state's length); `Ok(false)` without the Jacobians.
    pub fn jacobian(&self, t: f64, state: &[f64], out: &mut [f64]) -> Result<bool, SystemError> {
        self.jacobians(t, state, &[], out, &mut [])
    }

    /// ∂(state rate)/∂θ at a fixed state `(t, state)`, row-major `len × P` into `out` (θ
    /// as [`Program::parameter_names`]); `Ok(false)` without the Jacobians.
    pub fn parameter_jacobian(
        &self,
        t: f64,
        state: &[f64],
        out: &mut [f64],
    ) -> Result<bool, SystemError> {
        let every: Vec<usize> = (0..self.parameter_names().len()).collect();
        self.jacobians(t, state, &every, &mut [], out)
    }

    /// [`Program::jacobian`] into `jacobian` (unless empty) and the columns `wanted`
    /// (increasing) of [`Program::parameter_jacobian`] into `parameters` (`len × P`, the
    /// other columns NaN in the rows of q̇, ṗ and ṁ_s; the held inputs' rows 0), from one
    /// evaluation of a tape that holds only those columns;
    /// `Ok(false)` without the Jacobians.
    pub fn jacobians(
        &self,
        t: f64,
        state: &[f64],
        wanted: &[usize],
        jacobian: &mut [f64],
        parameters: &mut [f64],
    ) -> Result<bool, SystemError> {
        let Some((n, k, c, p)) = self.jacobian_sizes() else {
            return Ok(false);
        };
        if wanted.iter().any(|&j| j >= p) || !wanted.is_sorted_by(|a, b| a < b) {
            return Err(SystemError::NoParameterJacobian);
        }
        let values = self.jacobian_values(t, state, wanted)?;
        let sizes = (n, k, c, wanted.len());
        let blocks = Blocks::split(&values, sizes).ok_or(SystemError::NoParameterJacobian)?;
        if !jacobian.is_empty() {
            blocks.state_jacobian((n, k, c), self.state_len(), jacobian)?;
        }
        // The mechanics' rows NaN in the columns not computed; the held inputs' rows 0.
        let moved = 2 * n + k;
        let rows = parameters.iter_mut().take(self.state_len() * p).enumerate();
        rows.for_each(|(i, x)| *x = if i / p.max(1) < moved { f64::NAN } else { 0.0 });
        if !wanted.is_empty() {
            let part = blocks.columns(blocks.pt, Some(blocks.ft), (n, k), wanted.len())?;
            place_columns(parameters, p, &part, wanted);
        }
        Ok(true)
    }

    /// (n, k, state-mass columns, P), if the program has the Jacobians.
    fn jacobian_sizes(&self) -> Option<(usize, usize, usize, usize)> {
        let j = self.jacobians.as_ref()?;
        let n = self.coordinate_count();
        Some((n, self.state_mass_count(), j.mass_columns, j.names.len()))
    }

    /// The values at `(t, state)` of the Jacobian stage with the parameters' columns
    /// `wanted` (every parameter's: the whole stage).
    fn jacobian_values(
        &self,
        t: f64,
        state: &[f64],
        wanted: &[usize],
    ) -> Result<Vec<f64>, SystemError> {
        let Some(j) = &self.jacobians else {
            return Ok(Vec::new());
        };
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_state(scratch, t, state)?;
        if wanted.len() == j.names.len() {
            self.run(&j.stage, scratch);
        } else {
            let index = self.subset_stage(j, wanted);
            self.run(&j.subsets.borrow()[index].1, scratch);
        }
        if let Some(error) = scratch.outside.take() {
            return Err(error);
        }
        Ok(scratch.values.clone())
    }

    /// The index in `j.subsets` of the stage with the parameters' columns `wanted`,
    /// compiled now if it is not there: the whole stage's roots of J, then F_θ's and P_θ's
    /// entries in those columns, row by row.
    fn subset_stage(&self, j: &Jacobians, wanted: &[usize]) -> usize {
        if let Some(i) = j.subsets.borrow().iter().position(|(w, _)| w == wanted) {
            return i;
        }
        let (n, k, c, p) = self.jacobian_sizes().unwrap_or_default();
        let state_blocks = 2 * (n + k) * n + (n + k) * c + n * c + 2 * n * n;
        let all = &j.stage.roots;
        let (head, theta) = all.split_at(state_blocks.min(all.len()));
        let picked = theta
            .chunks(p.max(1))
            .flat_map(|row| wanted.iter().filter_map(|&w| row.get(w).copied()));
        let roots: Vec<_> = head.iter().copied().chain(picked).collect();
        let stage = Stage {
            tape: self.d.pool.compile(&roots),
            roots,
        };
        let mut subsets = j.subsets.borrow_mut();
        subsets.push((wanted.to_vec(), stage));
        subsets.len() - 1
    }
}

/// Writes the row-major `part` (`width` columns) into the row-major `out` of `stride`
/// columns, from its column `first` and row 0.
fn place(out: &mut [f64], stride: usize, part: &[f64], width: usize, first: usize) {
    for (row, values) in part
        .chunks(width.max(1))
        .enumerate()
        .take_while(|_| width > 0)
    {
        for (c, value) in values.iter().enumerate() {
            if let Some(slot) = out.get_mut(row * stride + first + c) {
                *slot = *value;
            }
        }
    }
}

/// Writes the row-major `part` (a column per entry of `wanted`) into the row-major `out` of
/// `stride` columns, each in the column `wanted` names, from row 0.
fn place_columns(out: &mut [f64], stride: usize, part: &[f64], wanted: &[usize]) {
    for (row, values) in part.chunks(wanted.len().max(1)).enumerate() {
        for (value, &column) in values.iter().zip(wanted) {
            if let Some(slot) = out.get_mut(row * stride + column) {
                *slot = *value;
            }
        }
    }
}
