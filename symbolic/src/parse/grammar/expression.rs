//! Expressions: the recursive descent (see the grammar in `mod.rs`).
//!
//! The functions here recurse once per nesting level, so each keeps a small frame: it
//! prepares with a helper, recurses, and hands the result to a finishing helper (in
//! `building.rs`), whose locals are gone before the next level starts. Unoptimized builds
//! give every local its own stack slot, and each byte here is multiplied by
//! [`MAX_NESTING`](super::MAX_NESTING).

use super::building::{Chain, ListStep, Named, Sign};
use super::{Context, Grammar, PResult};
use crate::parse::ast::{ExprNode, VectorNode};
use crate::parse::span::{Span, Spanned};

/// An expression and the depth of its tree (a leaf has depth 1).
pub(super) type Parsed = (ExprNode, u32);

/// The items of a bracketed list, their greatest depth, and the closing bracket's span.
pub(super) type Items = (Vec<ExprNode>, u32, Span);

/// What an operand is called in "expected … after `+`".
pub(super) const EXPRESSION: &str = "an expression";

impl<'a> Grammar<'a> {
    /// A whole expression: `product { (+|-) product }` with `product := unary { (*|/)
    /// unary }`, both left-associative, folded in one loop by [`Chain`]. Backtracks (a
    /// plain nom error) only if no expression starts at `input`; any other problem is a
    /// diagnostic.
    pub(super) fn expression(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let first = self.unary(input, context)?;
        let mut chain = Chain::new(first);
        loop {
            let Some((after, op)) = self.operator(&chain, context) else {
                return self.finish_chain(chain);
            };
            let operand = self.unary(after, context);
            chain = self.extend_chain(chain, op, operand, after, context)?;
        }
    }

    /// An expression that must be there, after `after`.
    pub(super) fn required_expression(
        &self,
        input: &'a str,
        context: Context,
        after: &str,
    ) -> PResult<'a, Parsed> {
        let result = self.expression(input, context);
        self.or_missing(result, input, context.nested, EXPRESSION, after)
    }

    /// `- unary | power`.
    fn unary(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        match self.sign(input, context)? {
            Sign::None(input) => self.power(input, context),
            Sign::Minus(after, minus, inner) => {
                let operand = self.unary(after, inner);
                self.negate(operand, after, minus, context)
            }
        }
    }

    /// `atom [^ unary]`: the exponent is a `unary`, so `2^3^2` is 2^(3^2) and `x^-2` is
    /// x^(-2), while the base is an atom, so `-x^2` is -(x^2).
    fn power(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (rest, base) = self.atom(input, context)?;
        match self.caret(rest, context)? {
            None => Ok((rest, base)),
            Some((after, inner)) => {
                let exponent = self.unary(after, inner);
                self.raise(base, exponent, after, context)
            }
        }
    }

    /// A number, a name, a derivative `x'`/`x''`, a call, or a parenthesized expression.
    fn atom(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let input = self.skip_blanks(input, context.nested);
        if input.starts_with('(') {
            return self.parenthesized(input, context);
        }
        if input.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
            return self.number(input).map(|(rest, node)| (rest, (node, 1)));
        }
        match self.named(input, context)? {
            Named::Done(rest, parsed) => Ok((rest, parsed)),
            Named::Callee(func, open_at) => self.call(func, open_at, context),
        }
    }

    /// `( expr )` at `input`: the node is the inner expression, its span widened over the
    /// parentheses (so that the span of `(a+b)*c` starts at the `(`).
    fn parenthesized(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (after, (open, inner)) = self.open(input, '(', context)?;
        let inside = self.expression(after, inner);
        self.finish_parenthesized(inside, after, open)
    }

    /// `name( args )` with the `(` at `input`; the name is not checked against the known
    /// functions here.
    fn call(&self, func: Spanned<String>, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (after, (open, inner)) = self.open(input, '(', context)?;
        let items = self.list(after, open, ')', inner);
        self.finish_call(func, items)
    }

    /// A vector `[e1, e2?, e3?]` with the span of its brackets. Backtracks if no `[` is
    /// here; 0 or more than 3 components is an error over the brackets.
    pub(super) fn vector(&self, input: &'a str, context: Context) -> PResult<'a, VectorNode> {
        let input = self.skip_blanks(input, context.nested);
        let (after, (open, inner)) = self.open(input, '[', context)?;
        let items = self.list(after, open, ']', inner);
        self.finish_vector(items, open)
    }

    /// Comma-separated expressions up to `close` (the opening bracket, at `open`, is
    /// already read). An empty list is allowed here; callers decide whether it makes sense.
    fn list(
        &self,
        after_open: &'a str,
        open: Span,
        close: char,
        context: Context,
    ) -> PResult<'a, Items> {
        if let Some(empty) = self.empty_list(after_open, close) {
            return Ok(empty);
        }
        let mut items = Vec::new();
        let mut depth = 0;
        let mut rest = after_open;
        loop {
            let item = self.expression(rest, context);
            match self.list_step(&mut items, &mut depth, item, rest, open, close)? {
                ListStep::More(next) => rest = next,
                ListStep::Done(next, close_span) => return Ok((next, (items, depth, close_span))),
            }
        }
    }
}
