//! The working memory of a Taylor expansion and the length of its coefficient arrays: a
//! leaf below the trait (`VariableMassSystem::taylor_coefficients` takes a scratch), the
//! Taylor stepper that owns one and the recurrences (`steppers::taylor::series`) that
//! generated code calls on its rows, which name both here too.

use core::any::TypeId;

use crate::steppers::taylor::series::Coefficient;

/// The highest order the stepper expands to (a tolerance of 1e-16 asks for 20).
pub const MAX_ORDER: usize = 32;

/// The length of every coefficient array of generated code: orders 0 … [`MAX_ORDER`].
pub const LEN: usize = MAX_ORDER + 1;

/// The working memory of generated `taylor_coefficients`: one coefficient array (a row) per
/// subexpression, and M\[0\]'s factor when q̇ is solved order by order. The caller keeps it
/// between expansions (the `Taylor` stepper owns one), so that an
/// expansion neither allocates nor clears its rows: zeroing every row of a stack buffer of
/// `LEN`-long arrays at each expansion was two thirds of the instructions of the 3-link
/// pendulum's step.
///
/// Why no row needs clearing: generated code writes every row it reads at orders
/// 0 ..= k before reading it at order k, except the rows set at order 0 alone (time, held
/// inputs, constants), whose higher coefficients must read 0. Those it zeroes when the
/// scratch is new to it ([`Scratch::parts`] says so: the scratch remembers which
/// generated code used it last), and nothing writes their higher coefficients afterwards.
/// So what a scratch held before, another system's rows included, never reaches a result
/// (`tests/taylor_emitted.rs` and `tests/taylor_tables.rs` run on scratches filled with
/// NaN, reused).
///
/// Its rows are of `f64` for the scalar stepper, of [`Lanes<W>`](crate::lanes::Lanes) for
/// the Taylor stepper in lanes (`emit = [..., "taylor", "lanes"]`).
#[derive(Clone, Debug)]
pub struct Scratch<T = f64> {
    rows: Vec<[T; LEN]>,
    factor: Vec<f64>,
    /// The generated code that used the rows last (a type of its own, local to it).
    owner: Option<TypeId>,
    /// The bits of the parameters its constants were last computed from
    /// ([`Scratch::same_constants`]).
    constants: Vec<u64>,
}

impl<T> Default for Scratch<T> {
    fn default() -> Self {
        Self {
            rows: Vec::new(),
            factor: Vec::new(),
            owner: None,
            constants: Vec::new(),
        }
    }
}

impl Scratch {
    /// An empty scratch; the first expansion sizes it (the only allocation).
    pub fn new() -> Self {
        Self::default()
    }

    /// A scratch of `rows` rows and a factor of `factor` entries, every entry `value`: for
    /// tests that what a scratch held never reaches a result.
    #[doc(hidden)]
    pub fn filled(rows: usize, factor: usize, value: f64) -> Self {
        Self {
            rows: vec![[value; LEN]; rows],
            factor: vec![value; factor],
            owner: None,
            constants: Vec::new(),
        }
    }
}

impl<T: Coefficient> Scratch<T> {
    /// Whether `key`, the parameters generated code computes its constants from (the rows
    /// of its order-0 instructions, which read no input: sin θ of a parameter θ, say), is
    /// bit for bit the key of its last call; the key is kept for the next. When it is, and
    /// the rows are not fresh ([`Scratch::parts`]), the rows still hold those constants
    /// and generated code does not recompute them: the sled's sin θ and cos θ were 6 % of
    /// its run (issue 38). A NaN parameter never matches (its constants are recomputed).
    /// Over lanes the key is every lane's parameters: one lane's change (a lane refilled
    /// with another member) recomputes them all, to the same bits for the others.
    #[inline]
    pub fn same_constants(&mut self, key: &[T]) -> bool {
        let mut same = self.constants.len() == key.len() * T::WIDTH;
        if same {
            for (kept, x) in self.constants.chunks_exact(T::WIDTH).zip(key) {
                for (i, a) in kept.iter().enumerate() {
                    let b = x.lane(i);
                    same &= *a == b.to_bits() && !b.is_nan();
                }
            }
        }
        if !same {
            self.constants.clear();
            for x in key {
                self.constants
                    .extend((0..T::WIDTH).map(|i| x.lane(i).to_bits()));
            }
        }
        same
    }

    /// The first `F` rows and `factor` entries of the factor, grown if shorter, for the
    /// generated code `owner`; `true` when that code did not use them last (its rows set
    /// at order 0 alone must then be zeroed).
    #[inline]
    pub fn parts<const F: usize>(
        &mut self,
        factor: usize,
        owner: TypeId,
    ) -> (&mut [[T; LEN]; F], &mut [f64], bool) {
        let fresh = self.owner != Some(owner) || self.rows.len() < F;
        if self.rows.len() < F {
            self.rows.resize(F, [T::splat(0.0); LEN]);
        }
        if self.factor.len() < factor {
            self.factor.resize(factor, 0.0);
        }
        self.owner = Some(owner);
        let rows = self.rows.first_chunk_mut::<F>();
        // `rows` holds at least F rows now.
        let rows = rows.unwrap_or_else(|| unreachable!("the rows were grown to {F}"));
        (rows, &mut self.factor[..factor], fresh)
    }
}
