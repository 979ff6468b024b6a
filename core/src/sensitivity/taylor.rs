//! Forward sensitivities on the Taylor stepper (docs/sensitivities.md#taylor): the Taylor
//! coefficients of the augmented state [y, s₁, …, s_K] by the system's own recurrences over
//! tangents ([`VariableMassSystem::taylor_coefficients_tangents`]). Coefficient k of y is a
//! smooth function of the state and the parameters, and its derivative in a column's
//! direction is coefficient k of that column's s (s = ∂y/∂w, and d/dw commutes with d/dt):
//! the expansion over tangents seeded with the columns gives both, exactly, in passes of
//! one width per run: 1 for one column, 2 for two, 4 for more (the state's recurrences are
//! computed once a pass: Kepler's four columns over three orbits at 1e-12 took 318 µs in
//! two passes of 2 and 270 µs in one of 4, interleaved, `benches/peers/ours_sensitivities.rs`,
//! before the step rule measured each column apart).

use alloc::vec::Vec;
use core::cell::RefCell;

use nalgebra::SVector;

use super::{scatter, Sensitive};
use crate::scratch::Scratch;
use crate::system::{SystemError, VariableMassSystem};
use crate::tangent::Tangent;

/// A pass's working memory, kept between expansions: the recurrences' scratch over tangents
/// and the coefficients of y over them.
pub(super) struct TaylorPass<const W: usize, const S: usize> {
    scratch: Scratch<Tangent<W>>,
    coefficients: Vec<[Tangent<W>; S]>,
}

impl<const W: usize, const S: usize> Default for TaylorPass<W, S> {
    fn default() -> Self {
        Self {
            scratch: Scratch::default(),
            coefficients: Vec::new(),
        }
    }
}

/// The working memory of the passes of width 1, 2 and 4.
#[derive(Default)]
pub(super) struct TaylorPasses<const S: usize> {
    one: RefCell<TaylorPass<1, S>>,
    two: RefCell<TaylorPass<2, S>>,
    four: RefCell<TaylorPass<4, S>>,
}

impl<Sys, const S: usize> Sensitive<Sys, S> {
    /// The Taylor coefficients of the augmented state through `(t, state)` into
    /// `coefficients`, `None` where the system has no recurrences over tangents.
    pub(super) fn augmented_taylor<const N: usize, const SA: usize>(
        &self,
        t: f64,
        state: &SVector<f64, SA>,
        coefficients: &mut [SVector<f64, SA>],
    ) -> Option<Result<(), SystemError>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let k = self.columns();
        let mut first = 0;
        loop {
            let pass = match k {
                0 | 1 => {
                    self.taylor_pass::<N, SA, 1>(&self.taylor.one, t, state, first, coefficients)
                }
                2 => self.taylor_pass::<N, SA, 2>(&self.taylor.two, t, state, first, coefficients),
                _ => self.taylor_pass::<N, SA, 4>(&self.taylor.four, t, state, first, coefficients),
            };
            match pass? {
                Ok(done) => first += done,
                Err(error) => return Some(Err(error)),
            }
            if first >= k {
                return Some(Ok(()));
            }
        }
    }

    /// One expansion over `Tangent<W>`: the columns from `first` on (at most W) into
    /// `coefficients`, and y's (the same in every pass); how many columns it took.
    fn taylor_pass<const N: usize, const SA: usize, const W: usize>(
        &self,
        memory: &RefCell<TaylorPass<W, S>>,
        t: f64,
        state: &SVector<f64, SA>,
        first: usize,
        coefficients: &mut [SVector<f64, SA>],
    ) -> Option<Result<usize, SystemError>>
    where
        Sys: VariableMassSystem<N, S>,
    {
        let columns = first..(first + W).min(self.columns());
        let (seeded, seeds) = self.seeded::<SA, W>(state, columns.clone());
        let mut memory = memory.borrow_mut();
        let TaylorPass {
            scratch,
            coefficients: expanded,
        } = &mut *memory;
        expanded.resize(coefficients.len(), [Tangent::constant(0.0); S]);
        let system = &self.system;
        if let Err(error) =
            system.taylor_coefficients_tangents::<W>(t, &seeded, &seeds, expanded, scratch)?
        {
            return Some(Err(error));
        }
        for (out, series) in coefficients.iter_mut().zip(expanded.iter()) {
            scatter(series, columns.clone(), out);
        }
        Some(Ok(columns.count().max(1)))
    }
}
