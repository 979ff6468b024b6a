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
        let Some(sizes) = self.jacobian_sizes() else {
            return Ok(false);
        };
        let (n, k, c, _) = sizes;
        let len = self.state_len();
        let values = self.jacobian_values(t, state)?;
        let blocks = Blocks::split(&values, sizes).ok_or(SystemError::NoParameterJacobian)?;
        let minus_identity: Vec<f64> = (0..n * n)
            .map(|i| if i / n == i % n { -1.0 } else { 0.0 })
            .collect();
        let parts = [
            (blocks.columns(blocks.pq, Some(blocks.fq), (n, k), n)?, n, 0),
            (blocks.columns(&minus_identity, None, (n, k), n)?, n, n),
            (
                blocks.columns(blocks.pm, Some(blocks.fm), (n, k), c)?,
                c,
                2 * n,
            ),
        ];
        out.iter_mut().take(len * len).for_each(|x| *x = 0.0);
        for (part, width, first) in parts {
            place(out, len, &part, width, first);
        }
        Ok(true)
    }

    /// ∂(state rate)/∂θ at a fixed state `(t, state)`, row-major `len × P` into `out` (θ
    /// as [`Program::parameter_names`]); `Ok(false)` without the Jacobians.
    pub fn parameter_jacobian(
        &self,
        t: f64,
        state: &[f64],
        out: &mut [f64],
    ) -> Result<bool, SystemError> {
        let Some(sizes) = self.jacobian_sizes() else {
            return Ok(false);
        };
        let (n, k, _, p) = sizes;
        let values = self.jacobian_values(t, state)?;
        let blocks = Blocks::split(&values, sizes).ok_or(SystemError::NoParameterJacobian)?;
        let part = blocks.columns(blocks.pt, Some(blocks.ft), (n, k), p)?;
        out.iter_mut()
            .take(self.state_len() * p)
            .for_each(|x| *x = 0.0);
        place(out, p, &part, p, 0);
        Ok(true)
    }

    /// (n, k, state-mass columns, P), if the program has the Jacobians.
    fn jacobian_sizes(&self) -> Option<(usize, usize, usize, usize)> {
        let j = self.jacobians.as_ref()?;
        let n = self.coordinate_count();
        Some((n, self.state_mass_count(), j.mass_columns, j.names.len()))
    }

    /// The Jacobian stage's values at `(t, state)`.
    fn jacobian_values(&self, t: f64, state: &[f64]) -> Result<Vec<f64>, SystemError> {
        let stage = match &self.jacobians {
            Some(j) => &j.stage,
            None => return Ok(Vec::new()),
        };
        let scratch = &mut *self.scratch.borrow_mut();
        self.load_state(scratch, t, state)?;
        self.run(stage, scratch);
        if let Some(error) = scratch.outside.take() {
            return Err(error);
        }
        Ok(scratch.values.clone())
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
