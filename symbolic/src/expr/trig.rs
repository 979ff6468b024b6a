//! Trigonometric reduction of an expanded sum: the identities that turn the kinetic energy
//! of a linkage into its textbook form.
//!
//! | rule          | terms (same coefficient c and rest R)      | becomes        |
//! |---------------|--------------------------------------------|----------------|
//! | Pythagoras    | c R sin(u)²  +  c R cos(u)²                | c R            |
//! | cos of a difference | c R cos(u) cos(v) + c R sin(u) sin(v) | c R cos(u − v) |
//! | cos of a sum  | c R cos(u) cos(v) − c R sin(u) sin(v)      | c R cos(u + v) |
//! | sin of a difference | c R sin(u) cos(v) − c R cos(u) sin(v) | c R sin(u − v) |
//! | sin of a sum  | c R sin(u) cos(v) + c R cos(u) sin(v)      | c R sin(u + v) |
//!
//! Canonical construction does not apply these (they need two terms at once and would slow
//! every sum); the derivation applies [`ExprPool::reduce_trig`] to the expanded Lagrangian,
//! so that every derived quantity starts from the simplest L.

use super::func::Func;
use super::node::{Id, Node};
use super::pool::ExprPool;
use rustc_hash::FxHashMap;

/// Two sine/cosine factors of one term, with a normal order: same-function arguments
/// sorted by id, a mixed pair always as (sine, cosine).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Pair {
    CosCos(Id, Id),
    SinSin(Id, Id),
    SinCos { sin: Id, cos: Id },
}

impl Pair {
    fn new((f, u): (Func, Id), (g, v): (Func, Id)) -> Pair {
        let (lo, hi) = if u <= v { (u, v) } else { (v, u) };
        match (f, g) {
            (Func::Cos, Func::Cos) => Pair::CosCos(lo, hi),
            (Func::Sin, Func::Sin) => Pair::SinSin(lo, hi),
            (Func::Sin, _) => Pair::SinCos { sin: u, cos: v },
            _ => Pair::SinCos { sin: v, cos: u },
        }
    }
}

/// The sine/cosine patterns of one term, each with the rest R of the term.
#[derive(Clone, Default)]
struct Patterns {
    /// `f(u)² R` as `(R, f, u)`.
    squares: Vec<(Id, Func, Id)>,
    /// `f(u) g(v) R` as `(R, pair)`.
    pairs: Vec<(Id, Pair)>,
}

/// What the rounds of one [`ExprPool::reduce_trig`] share: a term that survives a rewrite
/// has the same patterns in the next round, and a rest the same negation. Each is computed
/// once, where the first round needs it; recomputing would only re-intern existing nodes,
/// so the nodes created, and their order, are unchanged.
#[derive(Default)]
struct Rounds {
    patterns: FxHashMap<Id, Patterns>,
    negations: FxHashMap<Id, Id>,
}

impl ExprPool {
    /// `e` expanded, with the identities above applied to its terms until none applies.
    pub fn reduce_trig(&mut self, e: Id) -> Id {
        let mut current = self.expand(e);
        let mut rounds = Rounds::default();
        // Each rewrite removes at least one term, so this many rounds always suffice.
        for _ in 0..self.terms(current).len() {
            match self.reduce_once(current, &mut rounds) {
                Some(next) => current = next,
                None => break,
            }
        }
        current
    }

    /// `f(u)` with f = sin or cos, as `(func, u)`.
    fn trig_factor(&self, f: Id) -> Option<(Func, Id)> {
        match self.node(f) {
            Node::Call(func @ (Func::Sin | Func::Cos), args) if args.len() == 1 => {
                Some((*func, args[0]))
            }
            _ => None,
        }
    }

    /// `f(u)^2` with f = sin or cos.
    fn trig_square(&self, f: Id) -> Option<(Func, Id)> {
        match self.node(f) {
            Node::Pow(base, exponent)
                if self.as_rational(*exponent).and_then(|r| r.as_integer()) == Some(2) =>
            {
                self.trig_factor(*base)
            }
            _ => None,
        }
    }

    /// The product of `factors` without the ones at `skip`.
    fn rest(&mut self, factors: &[Id], skip: &[usize]) -> Id {
        let kept: Vec<Id> = factors
            .iter()
            .enumerate()
            .filter(|(i, _)| !skip.contains(i))
            .map(|(_, f)| *f)
            .collect();
        self.mul(&kept)
    }

    /// The patterns of term `t`, computed on its first round.
    fn patterns(&mut self, t: Id, rounds: &mut Rounds) -> Patterns {
        if let Some(known) = rounds.patterns.get(&t) {
            return known.clone();
        }
        let factors = self.factors(t);
        let mut found = Patterns::default();
        for (a, fa) in factors.iter().enumerate() {
            if let Some((func, u)) = self.trig_square(*fa) {
                let rest = self.rest(&factors, &[a]);
                found.squares.push((rest, func, u));
            }
            let Some(first) = self.trig_factor(*fa) else {
                continue;
            };
            for (b, fb) in factors.iter().enumerate().skip(a + 1) {
                if let Some(second) = self.trig_factor(*fb) {
                    let rest = self.rest(&factors, &[a, b]);
                    found.pairs.push((rest, Pair::new(first, second)));
                }
            }
        }
        rounds.patterns.insert(t, found.clone());
        found
    }

    /// One rewrite, if any applies.
    fn reduce_once(&mut self, sum: Id, rounds: &mut Rounds) -> Option<Id> {
        let terms = self.terms(sum);
        if terms.len() < 2 {
            return None;
        }
        // Candidate patterns per term, each with the rest R of the term.
        let mut squares = Vec::new(); // (R, func, u, term): f(u)² R
        let mut pairs = Vec::new(); // (R, pair, term)
        for (i, t) in terms.iter().enumerate() {
            let found = self.patterns(*t, rounds);
            squares.extend(found.squares.iter().map(|&(r, f, u)| (r, f, u, i)));
            pairs.extend(found.pairs.iter().map(|&(r, pair)| (r, pair, i)));
        }
        // Pythagoras: sin(u)² R + cos(u)² R = R.
        for &(rest, func, u, i) in &squares {
            if func != Func::Sin {
                continue;
            }
            let partner = squares
                .iter()
                .find(|(r, f, v, j)| *r == rest && *f == Func::Cos && *v == u && *j != i);
            if let Some(&(_, _, _, j)) = partner {
                return Some(self.replace_two(sum, i, j, rest));
            }
        }
        // Sums and differences of angles.
        for &(rest, pair, i) in &pairs {
            let negated = match rounds.negations.get(&rest) {
                Some(known) => *known,
                None => {
                    let negated = self.neg(rest);
                    rounds.negations.insert(rest, negated);
                    negated
                }
            };
            for &(other_rest, other, j) in &pairs {
                if j == i || !(other_rest == rest || other_rest == negated) {
                    continue;
                }
                let same_sign = other_rest == rest;
                let replacement = match (pair, other) {
                    // cos u cos v ± sin u sin v = cos(u ∓ v)
                    (Pair::CosCos(u, v), Pair::SinSin(x, y)) if (u, v) == (x, y) => {
                        let angle = if same_sign {
                            self.sub(u, v)
                        } else {
                            self.add(&[u, v])
                        };
                        self.call(Func::Cos, &[angle])
                    }
                    // sin u cos v ± sin v cos u = sin(u ± v)
                    (Pair::SinCos { sin: u, cos: v }, Pair::SinCos { sin: x, cos: y })
                        if x == v && y == u && u != v =>
                    {
                        let angle = if same_sign {
                            self.add(&[u, v])
                        } else {
                            self.sub(u, v)
                        };
                        self.call(Func::Sin, &[angle])
                    }
                    _ => continue,
                };
                let term = self.mul(&[rest, replacement]);
                return Some(self.replace_two(sum, i, j, term));
            }
        }
        None
    }

    /// `sum` with terms `i` and `j` replaced by `term`.
    fn replace_two(&mut self, sum: Id, i: usize, j: usize, term: Id) -> Id {
        let mut terms: Vec<Id> = self
            .terms(sum)
            .into_iter()
            .enumerate()
            .filter(|(k, _)| *k != i && *k != j)
            .map(|(_, t)| t)
            .collect();
        terms.push(term);
        self.add(&terms)
    }
}

impl ExprPool {
    /// `e` with every `sin(u ± v)` and `cos(u ± v)` of two symbols written as products of
    /// sines and cosines of the symbols: the inverse of the angle rules of
    /// [`ExprPool::reduce_trig`], for evaluation. A linkage's T in textbook form holds
    /// cos(θᵢ − θⱼ) for every pair, n(n−1)/2 calls; expanded, generated code computes the 2n
    /// values sin θᵢ, cos θᵢ once and shares them.
    pub fn expand_trig_arguments(&mut self, e: Id) -> Id {
        // Only the nodes no earlier call rewrote (the pool remembers every image): emission
        // rewrites hundreds of roots that share most of their nodes, and rewriting a node
        // again would only re-intern existing nodes, so skipping it changes neither the
        // result nor the order in which nodes are created.
        let todo = self.reachable_where(&[e], false, |id| !self.trig_images.contains_key(&id));
        for id in todo {
            let rebuilt = self.trig_image(id);
            self.trig_images.insert(id, rebuilt);
        }
        self.trig_images.get(&e).copied().unwrap_or(e)
    }

    /// The image of node `id` under [`expand_trig_arguments`](Self::expand_trig_arguments),
    /// from the images of its children.
    fn trig_image(&mut self, id: Id) -> Id {
        let node = self.node(id).clone();
        let children: Vec<Id> = node
            .children()
            .map(|c| self.trig_images.get(&c).copied().unwrap_or(c))
            .collect();
        let unchanged = node.children().eq(children.iter().copied());
        match (node, children.as_slice()) {
            (Node::Num(_) | Node::Float(_) | Node::Sym(_), _) => id,
            (Node::Call(func @ (Func::Sin | Func::Cos), _), &[argument]) => {
                match self.two_symbol_sum(argument) {
                    Some((u, v)) => {
                        let (su, cu) = (self.call(Func::Sin, &[u]), self.call(Func::Cos, &[u]));
                        let (sv, cv) = (self.call(Func::Sin, &[v]), self.call(Func::Cos, &[v]));
                        if func == Func::Sin {
                            // sin(u + v) = sin u cos v + cos u sin v
                            let (a, b) = (self.mul(&[su, cv]), self.mul(&[cu, sv]));
                            self.add(&[a, b])
                        } else {
                            // cos(u + v) = cos u cos v − sin u sin v
                            let (a, b) = (self.mul(&[cu, cv]), self.mul(&[su, sv]));
                            self.sub(a, b)
                        }
                    }
                    None if unchanged => id,
                    None => self.call(func, &children),
                }
            }
            // Nothing below changed: the node is already canonical.
            _ if unchanged => id,
            (Node::Add(_), _) => self.add(&children),
            (Node::Mul(_), _) => self.mul(&children),
            (Node::Pow(..), &[base, exponent]) => self.pow(base, exponent),
            (Node::Call(func, _), _) => self.call(func, &children),
            (Node::Pow(..), _) => id,
        }
    }

    /// `(u, v)` if `e` is `u + v` with each of u, v a symbol or minus a symbol.
    fn two_symbol_sum(&mut self, e: Id) -> Option<(Id, Id)> {
        let Node::Add(terms) = self.node(e) else {
            return None;
        };
        let [u, v] = terms[..] else { return None };
        let signed_symbol = |pool: &ExprPool, t: Id| match pool.node(t) {
            Node::Sym(_) => true,
            Node::Mul(f) => {
                f.len() == 2
                    && pool
                        .as_rational(f[0])
                        .is_some_and(|r| r.numer() == -1 && r.denom() == 1)
                    && matches!(pool.node(f[1]), Node::Sym(_))
            }
            _ => false,
        };
        (signed_symbol(self, u) && signed_symbol(self, v)).then_some((u, v))
    }
}
