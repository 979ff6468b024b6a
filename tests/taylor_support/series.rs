//! The series arithmetic of `symbolic/src/expr/taylor/reference.rs` (shared with the
//! recurrences' unit tests, included by path) and an expression evaluator walking the
//! pool's nodes: an independent reference for the Taylor coefficients of whole systems.

use std::collections::HashMap;

use varmass::symbolic::expr::{ExprPool, Func, Id, Node, Symbol};

#[path = "../../symbolic/src/expr/taylor/reference.rs"]
mod reference;

pub use reference::*;

/// The series of `roots`, with the symbols of `inputs` given as series and every other
/// symbol a constant `env[index]` (defined symbols through their values).
pub fn evaluate(
    pool: &ExprPool,
    roots: &[Id],
    inputs: &HashMap<Symbol, Series>,
    env: &[f64],
) -> Vec<Series> {
    let mut memo: HashMap<Id, Series> = HashMap::new();
    // Children before parents: ids ascend topologically, so evaluate the reachable ids in
    // ascending order.
    let mut reachable = Vec::new();
    let mut stack: Vec<Id> = roots.to_vec();
    let mut seen = std::collections::HashSet::new();
    while let Some(id) = stack.pop() {
        if !seen.insert(id) {
            continue;
        }
        reachable.push(id);
        stack.extend(pool.node(id).children());
        if let Node::Sym(s) = pool.node(id) {
            stack.extend(pool.definition(*s));
        }
    }
    reachable.sort_by_key(|id| id.index());
    for id in reachable {
        let value = node(pool, id, &memo, inputs, env);
        memo.insert(id, value);
    }
    roots.iter().map(|r| memo[r].clone()).collect()
}

fn node(
    pool: &ExprPool,
    id: Id,
    memo: &HashMap<Id, Series>,
    inputs: &HashMap<Symbol, Series>,
    env: &[f64],
) -> Series {
    let of = |c: &Id| memo[c].clone();
    match pool.node(id) {
        Node::Num(r) => constant(r.to_f64()),
        Node::Float(bits) => constant(f64::from_bits(*bits)),
        Node::Sym(s) => match (pool.definition(*s), inputs.get(s)) {
            (Some(value), _) => memo
                .get(&value)
                .cloned()
                .unwrap_or_else(|| constant(f64::NAN)),
            (None, Some(series)) => series.clone(),
            (None, None) => constant(env[s.index()]),
        },
        Node::Add(terms) => terms
            .iter()
            .fold(constant(0.0), |total, t| add(&total, &of(t))),
        Node::Mul(factors) => factors
            .iter()
            .fold(constant(1.0), |total, f| mul(&total, &of(f))),
        Node::Pow(b, e) => {
            let (b, e) = (of(b), of(e));
            if e[1..].iter().any(|x| *x != 0.0) {
                exp_of_product(&e, &b)
            } else if e[0].fract() == 0.0 && e[0] > 0.0 {
                (0..e[0] as usize).fold(constant(1.0), |total, _| mul(&total, &b))
            } else {
                power(&b, e[0])
            }
        }
        Node::Call(f, args) => {
            let args: Vec<Series> = args.iter().map(of).collect();
            call(*f, &args)
        }
    }
}

fn exp_of_product(e: &[f64], b: &[f64]) -> Series {
    exp(&mul(e, &ln(b)))
}

/// Solves M v = r for series by Gaussian elimination without pivoting (M symmetric positive
/// definite at order 0), with series quotients.
#[allow(clippy::needless_range_loop)] // row i is written while row j is read
pub fn solve(mut m: Vec<Vec<Series>>, mut r: Vec<Series>) -> Vec<Series> {
    let n = r.len();
    for j in 0..n {
        for i in j + 1..n {
            let factor = divide(&m[i][j], &m[j][j]);
            for k in j..n {
                let product = mul(&factor, &m[j][k]);
                m[i][k] = add(&m[i][k], &scale(&product, -1.0));
            }
            let product = mul(&factor, &r[j]);
            r[i] = add(&r[i], &scale(&product, -1.0));
        }
    }
    let mut v = vec![constant(0.0); n];
    for i in (0..n).rev() {
        let mut rest = r[i].clone();
        for k in i + 1..n {
            rest = add(&rest, &scale(&mul(&m[i][k], &v[k]), -1.0));
        }
        v[i] = divide(&rest, &m[i][i]);
    }
    v
}
