//! Numeric evaluation of an expression at one point (for checks and tests). There is one
//! evaluator: [`ExprPool::eval`] compiles a one-root [`Tape`](super::Tape) and runs it, so
//! a value at a point and a tape's value agree bit for bit by construction.

use super::node::Id;
use super::pool::ExprPool;

impl ExprPool {
    /// The value of `e` with symbol `s` worth `env[s.index()]`; NaN where a value is
    /// missing (an index past the end of `env`). Defined symbols evaluate their value.
    /// Tables extrapolate their end pieces: values at a point test algebra, not data.
    pub fn eval(&self, e: Id, env: &[f64]) -> f64 {
        let mut out = [f64::NAN];
        self.compile(&[e])
            .extrapolating()
            .eval_with(env, &mut Vec::new(), &mut out);
        out[0]
    }
}
