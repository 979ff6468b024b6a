//! Deciding whether two expressions are equal: by canonical form, then by expansion, then
//! by evaluation at random points (docs/dsl.md#checks: identities are decided by simplification and,
//! where that is not conclusive, by evaluation at many random points).

use super::node::Id;
use super::pool::ExprPool;
use super::symbol::Symbol;

/// The verdict of [`ExprPool::identical`].
#[derive(Clone, Debug, PartialEq)]
pub enum Identity {
    /// The canonical (or expanded) forms are equal: an identity for all values.
    Proven,
    /// Equal, within rounding, at this many random points; not proven symbolically.
    Numerical {
        /// Number of points where both sides agreed.
        points: usize,
    },
    /// The two sides differ clearly at this point.
    Refuted {
        /// The value of each symbol of either side.
        env: Vec<(Symbol, f64)>,
        /// The left side's value there.
        lhs: f64,
        /// The right side's value there.
        rhs: f64,
    },
    /// No conclusion: too few points where both sides are finite (or agreement only
    /// within a doubtful margin).
    Undecided,
}

/// Points to try to agree on.
const POINTS: usize = 32;
/// Attempts, counting points where a side is not finite (outside a domain).
const ATTEMPTS: usize = 128;
/// Fewer agreeing points than this is no evidence.
const MIN_POINTS: usize = 8;
/// Agreement: |lhs − rhs| ≤ AGREE × magnitude. Evaluation error is about
/// (operations × ε ≈ 1e-16) × magnitude, where the magnitude sums the absolute values of
/// the terms (so cancellation in the result does not shrink the scale); 1e-9 leaves many
/// orders of margin for thousands of operations and moderately ill-conditioned functions.
const AGREE: f64 = 1e-9;
/// Clear disagreement: two different expressions differ by O(1) relative at random
/// points; below 1e-6 × magnitude we prefer not to call it.
const DISAGREE: f64 = 1e-6;
/// Symbols are drawn from [LOW, LOW + WIDTH]: positive, away from 0, from the usual
/// singularities of ln, sqrt, 1/x, asin/acos at ±1 and tan at π/2 (≈ 1.57 is inside, but a
/// point there is non-finite or rejected like any other, and there are many points).
const LOW: f64 = 0.3;
const WIDTH: f64 = 1.4;

/// Seeded random points for numerical checks (the identity test here, the derivation's
/// singularity test): each symbol drawn from [0.3, 1.7] — positive, away from 0 and from
/// the usual singularities — by splitmix64 (Steele, Lea, Flood 2014), so runs repeat.
pub struct SamplePoints(SplitMix64);

impl SamplePoints {
    /// A generator with the given seed.
    pub fn new(seed: u64) -> SamplePoints {
        SamplePoints(SplitMix64(seed))
    }

    /// Draws a value for each of `symbols` into `env` (indexed by [`Symbol::index`]).
    pub fn fill(&mut self, env: &mut [f64], symbols: impl IntoIterator<Item = Symbol>) {
        for s in symbols {
            if let Some(slot) = env.get_mut(s.index()) {
                *slot = LOW + WIDTH * self.0.next_f64();
            }
        }
    }
}

/// splitmix64: a tiny, seeded, well-mixed generator.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

impl ExprPool {
    /// Whether `a` and `b` are the same function of their symbols: [`Identity::Proven`]
    /// when `a − b` simplifies (after inlining definitions, and if need be expanding) to 0,
    /// else decided numerically at seeded random points.
    pub fn identical(&mut self, a: Id, b: Id) -> Identity {
        let difference = self.sub(a, b);
        if self.is_zero(difference) {
            return Identity::Proven;
        }
        let (inlined_a, inlined_b) = (self.inline_definitions(a), self.inline_definitions(b));
        // Without definitions to inline, the difference is the one just built.
        let difference = if (inlined_a, inlined_b) == (a, b) {
            difference
        } else {
            self.sub(inlined_a, inlined_b)
        };
        let (a, b) = (inlined_a, inlined_b);
        let expanded = self.expand(difference);
        if self.is_zero(expanded) {
            return Identity::Proven;
        }
        self.identical_numerically(a, b)
    }

    fn identical_numerically(&self, a: Id, b: Id) -> Identity {
        let mut symbols = self.free_symbols(a);
        symbols.extend(self.free_symbols(b));
        let tape = self.compile(&[a, b]).extrapolating();
        let mut points = SamplePoints::new(0x7661_726D_6173_7321);
        let mut env = vec![f64::NAN; self.symbols().len()];
        let (mut scratch, mut magnitudes) = (Vec::new(), Vec::new());
        let (mut values, mut scales) = ([0.0; 2], [0.0; 2]);
        let mut agreed = 0;
        for _ in 0..ATTEMPTS {
            if agreed == POINTS {
                break;
            }
            points.fill(&mut env, symbols.iter().copied());
            tape.eval_with_magnitude(
                &env,
                &mut scratch,
                &mut magnitudes,
                &mut values,
                &mut scales,
            );
            if !values.iter().chain(&scales).all(|v| v.is_finite()) {
                continue;
            }
            let [lhs, rhs] = values;
            let gap = (lhs - rhs).abs();
            let scale = scales[0].max(scales[1]);
            if gap <= AGREE * scale {
                agreed += 1;
            } else if gap > DISAGREE * scale {
                let env = symbols
                    .iter()
                    .map(|s| (*s, env.get(s.index()).copied().unwrap_or(f64::NAN)))
                    .collect();
                return Identity::Refuted { env, lhs, rhs };
            }
        }
        if agreed >= MIN_POINTS {
            Identity::Numerical { points: agreed }
        } else {
            Identity::Undecided
        }
    }
}
