//! The frozen-mass calculus (docs/mechanics.md#the-frozen-mass-rule): ∂*/∂s and d*/dt.
//!
//! Both are one bottom-up pass over the DAG (ascending ids are a topological order), so
//! a shared subexpression is differentiated once and deep expressions cost no stack.
//! `Frozen` (masses, inertias) and `Parameter` symbols have zero derivative even where a
//! mass law makes them depend on q or t; that is the paper's ∂*, d*/dt (eq. 6, 14).
//! Defined symbols are looked through: ∂w/∂x is ∂(value of w)/∂x.

use super::func::Func;
use super::node::{Id, Node};
use super::pool::{symbol_bit, ExprPool};
use super::rational::Rational;
use super::symbol::{Symbol, SymbolKind};

/// d*/dt was asked of an expression containing a symbol whose rate is not a symbol:
/// an acceleration (there is no q''') or a momentum (ṗ comes from the canonical equations,
/// not from a symbol).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the time derivative of `{name}` is not available: {reason}")]
pub struct UnsupportedDerivative {
    /// The symbol without a rate.
    pub symbol: Symbol,
    /// Its name, for messages.
    pub name: String,
    /// Why it has none.
    pub reason: &'static str,
}

/// What the derivative of a bare symbol is; also what a derivative was taken with respect
/// to, in the pool's memo of derivatives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Leaf {
    /// ∂*/∂s: 1 for `s`, 0 for every other symbol.
    Partial(Symbol),
    /// d*/dt: q → q', q' → q'', t → 1; parameters, frozen symbols and definitions
    /// without a value → 0.
    Time,
}

impl ExprPool {
    /// ∂*e/∂wrt: the partial derivative with every other symbol held fixed, frozen masses
    /// included. Total: every expression has one.
    pub fn diff(&mut self, e: Id, wrt: Symbol) -> Id {
        match self.derivative(e, Leaf::Partial(wrt)) {
            Ok(d) => d,
            // Partial derivatives of leaves never fail.
            Err(_) => self.int(0),
        }
    }

    /// d*e/dt = Σ_q (∂e/∂q q' + ∂e/∂q' q'') + ∂e/∂t, masses frozen.
    ///
    /// Fails if `e` contains an acceleration or a momentum symbol, whose rates are not
    /// symbols of the system.
    pub fn time_derivative(&mut self, e: Id) -> Result<Id, UnsupportedDerivative> {
        self.derivative(e, Leaf::Time)
    }

    fn leaf_derivative(&mut self, s: Symbol, leaf: Leaf) -> Result<Id, UnsupportedDerivative> {
        let unsupported = |pool: &ExprPool, reason| UnsupportedDerivative {
            symbol: s,
            name: pool.symbols().name(s).to_owned(),
            reason,
        };
        let rate = match leaf {
            Leaf::Partial(wrt) => return Ok(self.int(i64::from(s == wrt))),
            Leaf::Time => match self.symbols().kind(s) {
                SymbolKind::Coordinate => self.symbols().velocity_of(s),
                SymbolKind::Velocity { coordinate } => self.symbols().acceleration_of(coordinate),
                SymbolKind::Time => return Ok(self.int(1)),
                SymbolKind::Parameter | SymbolKind::Frozen | SymbolKind::Definition => None,
                SymbolKind::Acceleration { .. } => {
                    return Err(unsupported(self, "there is no third derivative q'''"))
                }
                SymbolKind::Momentum { .. } => {
                    return Err(unsupported(
                        self,
                        "the rate of a momentum comes from the canonical equations",
                    ))
                }
            },
        };
        Ok(match rate {
            Some(r) => self.sym(r),
            None => self.int(0),
        })
    }

    /// The symbols (as a filter, see [`symbol_bit`]) whose leaf derivative is not 0 or fails:
    /// an expression free of them has derivative 0 and needs no visit.
    fn leaf_symbols(&self, leaf: Leaf) -> u64 {
        match leaf {
            Leaf::Partial(wrt) => symbol_bit(wrt),
            Leaf::Time => self
                .symbols()
                .iter()
                .filter(|s| {
                    !matches!(
                        self.symbols().kind(*s),
                        SymbolKind::Parameter | SymbolKind::Frozen | SymbolKind::Definition
                    )
                })
                .fold(0, |mask, s| mask | symbol_bit(s)),
        }
    }

    /// One bottom-up pass over the nodes below `e` whose derivative is not known yet.
    ///
    /// Skipped: the nodes free of every symbol with a nonzero rate (their derivative is 0,
    /// and computing it would build no node) and the nodes whose derivative an earlier
    /// call remembered (recomputing it would build the same nodes again, which all exist).
    /// So skipping changes neither the results nor the order in which nodes are created.
    fn derivative(&mut self, e: Id, leaf: Leaf) -> Result<Id, UnsupportedDerivative> {
        let zero = self.int(0);
        let symbols = self.leaf_symbols(leaf);
        let todo = self.reachable_where(&[e], true, |id| {
            self.symbol_mask(id) & symbols != 0 && !self.derivatives.contains_key(&(id, leaf))
        });
        for id in todo {
            let value = self.derivative_of_node(id, leaf, zero)?;
            self.derivatives.insert((id, leaf), value);
        }
        Ok(self.known_derivative(e, leaf, zero))
    }

    /// The remembered derivative of `id`, else 0 (for a node free of the leaf's symbols).
    fn known_derivative(&self, id: Id, leaf: Leaf, zero: Id) -> Id {
        self.derivatives.get(&(id, leaf)).copied().unwrap_or(zero)
    }

    /// The derivative of the node `id` from the known derivatives of its children.
    fn derivative_of_node(
        &mut self,
        id: Id,
        leaf: Leaf,
        zero: Id,
    ) -> Result<Id, UnsupportedDerivative> {
        let of = |pool: &ExprPool, c: &Id| pool.known_derivative(*c, leaf, zero);
        Ok(match self.node(id).clone() {
            Node::Num(_) | Node::Float(_) => zero,
            Node::Sym(s) => match (self.definition(s), leaf) {
                // ∂w/∂w = 1 even for a defined w; otherwise look through its value.
                (Some(v), Leaf::Partial(wrt)) if wrt != s => of(self, &v),
                (Some(v), Leaf::Time) => of(self, &v),
                _ => self.leaf_derivative(s, leaf)?,
            },
            Node::Add(terms) => {
                let dt: Vec<Id> = terms.iter().map(|c| of(self, c)).collect();
                self.add(&dt)
            }
            Node::Mul(factors) => {
                let df: Vec<Id> = factors.iter().map(|c| of(self, c)).collect();
                self.product_rule(&factors, &df)
            }
            Node::Pow(u, v) => {
                let (du, dv) = (of(self, &u), of(self, &v));
                self.power_rule(id, u, v, du, dv)
            }
            Node::Call(f, args) => {
                let da: Vec<Id> = args.iter().map(|c| of(self, c)).collect();
                self.chain_rule(id, f, &args, &da)
            }
        })
    }

    /// (Π fᵢ)' = Σᵢ fᵢ' Π_{j≠i} fⱼ
    fn product_rule(&mut self, factors: &[Id], df: &[Id]) -> Id {
        let mut terms = Vec::new();
        for (i, dfi) in df.iter().enumerate() {
            if self.is_zero(*dfi) {
                continue;
            }
            let mut product: Vec<Id> = factors.to_vec();
            if let Some(slot) = product.get_mut(i) {
                *slot = *dfi;
            }
            terms.push(self.mul(&product));
        }
        self.add(&terms)
    }

    /// (u^v)' = v u^(v−1) u' when v is constant, else u^v (v' ln u + v u'/u).
    fn power_rule(&mut self, power: Id, u: Id, v: Id, du: Id, dv: Id) -> Id {
        if self.is_zero(dv) {
            if self.is_zero(du) {
                return du;
            }
            let minus_one = self.int(-1);
            let v_minus_one = self.add(&[v, minus_one]);
            let lowered = self.pow(u, v_minus_one);
            return self.mul(&[v, lowered, du]);
        }
        let ln_u = self.call(Func::Ln, &[u]);
        let through_exponent = self.mul(&[dv, ln_u]);
        let minus_one = self.int(-1);
        let inverse_u = self.pow(u, minus_one);
        let through_base = self.mul(&[v, du, inverse_u]);
        let inner = self.add(&[through_exponent, through_base]);
        self.mul(&[power, inner])
    }

    /// f(u)' = f'(u) u' for every [`Func`]; the two-argument ones by their partials.
    fn chain_rule(&mut self, call: Id, f: Func, args: &[Id], da: &[Id]) -> Id {
        let zero = self.int(0);
        if da.iter().all(|d| self.is_zero(*d)) {
            return zero;
        }
        if let Func::Input { input, partial } = f {
            return self.input_chain_rule(input, partial, args, da);
        }
        let (u, du) = match (args.first(), da.first()) {
            (Some(u), Some(du)) => (*u, *du),
            _ => return zero,
        };
        if let Func::Table { table, order } = f {
            // The interpolant's own derivative, a table of the same kind.
            let derivative = match order.checked_add(1) {
                Some(next) => self.table_call(table, next, u),
                None => self.float(f64::NAN),
            };
            return self.mul(&[derivative, du]);
        }
        let one = self.int(1);
        let minus_one = self.int(-1);
        let two = self.int(2);
        // f'(u) for the one-argument functions.
        let outer = match f {
            Func::Sin => self.call(Func::Cos, &[u]),
            Func::Cos => {
                let s = self.call(Func::Sin, &[u]);
                self.neg(s)
            }
            // 1 + tan² rather than sec²: no new function, and tan(u) is shared with f.
            Func::Tan => {
                let sq = self.pow(call, two);
                self.add(&[one, sq])
            }
            Func::Exp => call,
            Func::Ln => self.pow(u, minus_one),
            Func::Abs => self.call(Func::Sign, &[u]),
            Func::Sign => return zero,
            Func::Tanh => {
                let sq = self.pow(call, two);
                self.sub(one, sq)
            }
            Func::Sinh => self.call(Func::Cosh, &[u]),
            Func::Cosh => self.call(Func::Sinh, &[u]),
            Func::Asin | Func::Acos => {
                let sq = self.pow(u, two);
                let rest = self.sub(one, sq);
                let minus_half = self.rational(Rational::MINUS_HALF);
                let root = self.pow(rest, minus_half);
                if f == Func::Asin {
                    root
                } else {
                    self.neg(root)
                }
            }
            Func::Atan => {
                let sq = self.pow(u, two);
                let rest = self.add(&[one, sq]);
                self.pow(rest, minus_one)
            }
            Func::Atan2 | Func::Min | Func::Max => {
                return self.binary_chain_rule(f, args, da);
            }
            // Differentiated above, before the constants.
            Func::Table { .. } | Func::Input { .. } => return zero,
        };
        self.mul(&[outer, du])
    }

    /// u(a)' = Σⱼ ∂ⱼu(a) aⱼ' for an input (`input_call.rs`); a partial of an input has no
    /// known derivative: NaN, which `mechanics/inputs.rs` turns into a diagnostic.
    fn input_chain_rule(&mut self, input: u16, partial: u8, args: &[Id], da: &[Id]) -> Id {
        if partial > 0 {
            return self.float(f64::NAN);
        }
        let mut terms = Vec::new();
        for (j, d) in da.iter().enumerate() {
            if self.is_zero(*d) {
                continue;
            }
            let Some(j) = u8::try_from(j + 1).ok() else {
                return self.float(f64::NAN);
            };
            let partial = self.input_call(input, j, args);
            terms.push(self.mul(&[partial, *d]));
        }
        self.add(&terms)
    }

    /// atan2(y, x)' = (x y' − y x')/(x² + y²);
    /// min, max = (a + b ∓ |a − b|)/2, so their rates are (a' + b' ∓ sign(a − b)(a' − b'))/2.
    fn binary_chain_rule(&mut self, f: Func, args: &[Id], da: &[Id]) -> Id {
        let ([a, b], [d_a, d_b]) = (args, da) else {
            return self.int(0);
        };
        let (a, b, d_a, d_b) = (*a, *b, *d_a, *d_b);
        let two = self.int(2);
        match f {
            Func::Atan2 => {
                let (y, x, dy, dx) = (a, b, d_a, d_b);
                let x_dy = self.mul(&[x, dy]);
                let y_dx = self.mul(&[y, dx]);
                let num = self.sub(x_dy, y_dx);
                let x2 = self.pow(x, two);
                let y2 = self.pow(y, two);
                let den = self.add(&[x2, y2]);
                self.div(num, den)
            }
            _ => {
                let gap = self.sub(a, b);
                let sign = self.call(Func::Sign, &[gap]);
                let d_gap = self.sub(d_a, d_b);
                let mut switch = self.mul(&[sign, d_gap]);
                if f == Func::Min {
                    switch = self.neg(switch);
                }
                let sum = self.add(&[d_a, d_b, switch]);
                let half = self.rational(Rational::HALF);
                self.mul(&[half, sum])
            }
        }
    }
}
