//! Common factors pulled out of sums (a greedy multivariate Horner scheme): the inverse of
//! expansion, for evaluating what expansion and the trigonometric reduction leave.
//!
//! An expanded sum repeats its factors term after term: the rigid body's angular momentum
//! rate in world components is forty products of five to seven factors, most of them
//! sharing `g_c m_p`, a velocity and an entry of the rotation matrix. Taking out the factor
//! that the most terms share, then recursing into what it multiplies and into the rest,
//! turns `a x y + a x z + a w` into `a (x (y + z) + w)`: three multiplications and two
//! additions instead of seven and two (Ceberio & Kreinovich, "Greedy algorithms for
//! optimizing multivariate Horner schemes", ACM SIGSAM Bulletin 38 (2004)). The value is
//! the same expression; only the order of the floating-point operations changes.

use super::node::{Id, Node};
use super::pool::ExprPool;
use rustc_hash::FxHashMap;

impl ExprPool {
    /// `e` with common factors pulled out of every sum, greedily: in each sum, the factor
    /// shared by the most terms (at least two) is taken out, then the same is done inside
    /// what it multiplies and among the terms without it. A factor is a base raised to a
    /// positive integer power (taken out once per round, so `x²` can go twice) or any
    /// other factor as a whole (`m^(-1)`, `sin(θ)`). Sums inside other nodes are left as
    /// they are: this is meant for the expanded sums of products that
    /// [`reduce_trig`](Self::reduce_trig) returns.
    pub fn factor_out(&mut self, e: Id) -> Id {
        let Node::Add(terms) = self.node(e) else {
            return e;
        };
        let terms = terms.to_vec();
        let Some(common) = self.most_shared_factor(&terms) else {
            return e;
        };
        let inverse = {
            let minus_one = self.int(-1);
            self.pow(common, minus_one)
        };
        let (mut with, mut without) = (Vec::new(), Vec::new());
        for t in terms {
            if self.factor_bases(t).contains(&common) {
                with.push(self.mul(&[t, inverse]));
            } else {
                without.push(t);
            }
        }
        let inner = self.add(&with);
        let inner = self.factor_out(inner);
        let taken = self.mul(&[common, inner]);
        let rest = self.add(&without);
        let rest = self.factor_out(rest);
        self.add(&[taken, rest])
    }

    /// The factor (see [`factor_out`](Self::factor_out)) that the most of `terms` contain,
    /// if two or more share one; ties go to the factor met first.
    fn most_shared_factor(&self, terms: &[Id]) -> Option<Id> {
        let mut counts: FxHashMap<Id, (usize, usize)> = FxHashMap::default();
        let mut order = 0;
        for t in terms {
            for f in self.factor_bases(*t) {
                let entry = counts.entry(f).or_insert((0, order));
                entry.0 += 1;
                order += 1;
            }
        }
        counts
            .into_iter()
            .filter(|(_, (count, _))| *count >= 2)
            .max_by(|(_, (c1, o1)), (_, (c2, o2))| c1.cmp(c2).then(o2.cmp(o1)))
            .map(|(f, _)| f)
    }

    /// The factors of a term that can be taken out: each base of a positive integer power,
    /// every other non-numeric factor as it is.
    fn factor_bases(&self, t: Id) -> Vec<Id> {
        let factors: &[Id] = match self.node(t) {
            Node::Mul(factors) => factors,
            _ => std::slice::from_ref(&t),
        };
        factors
            .iter()
            .filter(|f| self.node(**f).number().is_none())
            .map(|f| match self.node(*f) {
                Node::Pow(base, exponent)
                    if self
                        .as_rational(*exponent)
                        .and_then(|r| r.as_integer())
                        .is_some_and(|n| n > 0) =>
                {
                    *base
                }
                _ => *f,
            })
            .collect()
    }
}
