//! Expressions: precedence climbing written as one nom parser per level (see the grammar in
//! `mod.rs`), with every node's span and the tree's depth.

use super::{Context, Grammar, PResult, MAX_DEPTH, MAX_NESTING};
use crate::parse::ast::{BinOp, Expr, ExprNode, VectorNode};
use crate::parse::span::{Diagnostic, Span, Spanned};
use nom::bytes::complete::take_while;
use nom::character::complete::one_of;
use nom::Parser;

/// An expression and the depth of its tree (a leaf has depth 1).
pub(super) type Parsed = (ExprNode, u32);

/// What an operand is called in "expected … after `+`".
const EXPRESSION: &str = "an expression";

impl<'a> Grammar<'a> {
    /// A whole expression: `product { (+|-) product }` with `product := unary { (*|/)
    /// unary }`, both left-associative. Backtracks (a plain nom error) only if no
    /// expression starts at `input`; any other problem is a diagnostic.
    ///
    /// Both levels are one loop: the product being built is `term`, the sum so far is
    /// `sum` with its pending operator. Together with the other functions from here to
    /// [`Grammar::parenthesized`], this recurses once per nesting level, so they keep few
    /// frames and leave error building to cold functions: in unoptimized builds every
    /// local gets its own stack slot, and each byte is multiplied by [`MAX_NESTING`].
    pub(super) fn expression(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (mut rest, mut term) = self.unary(input, context)?;
        let mut sum: Option<(Parsed, BinOp)> = None;
        loop {
            let at = self.skip_blanks(rest, context.nested);
            let found: PResult<'a, char> = one_of("+-*/").parse(at);
            let Ok((after, symbol)) = found else {
                break;
            };
            let (op, written) = match symbol {
                '+' => (BinOp::Add, "+"),
                '-' => (BinOp::Sub, "-"),
                '*' => (BinOp::Mul, "*"),
                _ => (BinOp::Div, "/"),
            };
            let operand = self.unary(after, context);
            let (after, operand) =
                self.or_missing(operand, after, context.nested, EXPRESSION, written)?;
            if matches!(op, BinOp::Mul | BinOp::Div) {
                term = self.binary(op, term, operand, after)?;
            } else {
                let left = match sum.take() {
                    Some((left, pending)) => self.binary(pending, left, term, after)?,
                    None => term,
                };
                sum = Some((left, op));
                term = operand;
            }
            rest = after;
        }
        match sum {
            Some((left, pending)) => Ok((rest, self.binary(pending, left, term, rest)?)),
            None => Ok((rest, term)),
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
        let input = self.skip_blanks(input, context.nested);
        let Ok((after, minus)) = self.punct(input, '-') else {
            return self.power(input, context);
        };
        let inner = self.deeper(context, input)?;
        let operand = self.unary(after, inner);
        let (rest, (operand, depth)) =
            self.or_missing(operand, after, context.nested, EXPRESSION, "-")?;
        let span = minus.join(operand.span);
        let depth = self.limit_depth(depth + 1, span, rest)?;
        Ok((
            rest,
            (Spanned::new(Box::new(Expr::Neg(operand)), span), depth),
        ))
    }

    /// `atom [^ unary]`: the exponent is a `unary`, so `2^3^2` is 2^(3^2) and `x^-2` is
    /// x^(-2), while the base is an atom, so `-x^2` is -(x^2).
    fn power(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (rest, base) = self.atom(input, context)?;
        let at = self.skip_blanks(rest, context.nested);
        let Ok((after, _)) = self.punct(at, '^') else {
            return Ok((rest, base));
        };
        let inner = self.deeper(context, at)?;
        let exponent = self.unary(after, inner);
        let (rest, exponent) = self.or_missing(exponent, after, context.nested, EXPRESSION, "^")?;
        let tree = self.binary(BinOp::Pow, base, exponent, rest)?;
        Ok((rest, tree))
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
        self.named(input, context)
    }

    /// `( expr )` at `input`: the node is the inner expression, its span widened over the
    /// parentheses (so that the span of `(a+b)*c` starts at the `(`).
    fn parenthesized(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (after, open) = self.punct(input, '(')?;
        let inner = Context {
            nested: true,
            ..self.deeper(context, input)?
        };
        let inside = self.expression(after, inner);
        let (rest, (mut node, depth)) = self.or_missing(inside, after, true, EXPRESSION, "(")?;
        let (rest, close) = self.close(rest, ')', open, "an operator or `)`")?;
        node.span = open.join(close);
        Ok((rest, (node, depth)))
    }

    /// A name, `x'`, `x''` or a call `f(…)`.
    fn named(&self, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (rest, name) = self.identifier(input)?;
        let primes: PResult<'a, &'a str> = take_while(|c: char| c == '\'')(rest);
        let (after_primes, primes) = primes.unwrap_or((rest, ""));
        if !primes.is_empty() {
            return self.derivative(name, primes.len(), after_primes);
        }
        let at = self.skip_blanks(rest, context.nested);
        if at.starts_with('(') {
            return self.call(name, at, context);
        }
        let span = name.span;
        Ok((
            rest,
            (Spanned::new(Box::new(Expr::Name(name.node)), span), 1),
        ))
    }

    /// `x'` or `x''`; more primes are an error over the whole `x'''`.
    fn derivative(
        &self,
        name: Spanned<String>,
        order: usize,
        rest: &'a str,
    ) -> PResult<'a, Parsed> {
        let span = self.span(name.span.start, self.offset(rest));
        let base = &name.node;
        let Some(order @ (1 | 2)) = u8::try_from(order).ok() else {
            let written = self.source.get(span.start..span.end).unwrap_or("");
            let diagnostic = Diagnostic::new(
                span,
                format!("`{written}`: only {base}' and {base}'' are allowed"),
            )
            .with_help(format!(
                "{base}' is the velocity of {base} and {base}'' its acceleration; \
                 higher derivatives never enter the equations"
            ));
            return Err(self.fail(rest, diagnostic));
        };
        let node = Expr::Derivative {
            name: name.node,
            order,
        };
        Ok((rest, (Spanned::new(Box::new(node), span), 1)))
    }

    /// `name( args )`; the name is not checked against the known functions here.
    fn call(&self, func: Spanned<String>, input: &'a str, context: Context) -> PResult<'a, Parsed> {
        let (after, open) = self.punct(input, '(')?;
        let inner = Context {
            nested: true,
            ..self.deeper(context, input)?
        };
        let (rest, (args, depth, close)) = self.list(after, open, ')', inner)?;
        let span = func.span.join(close);
        let depth = self.limit_depth(depth + 1, span, rest)?;
        Ok((
            rest,
            (
                Spanned::new(Box::new(Expr::Call { func, args }), span),
                depth,
            ),
        ))
    }

    /// A vector `[e1, e2?, e3?]` with the span of its brackets. Backtracks if no `[` is
    /// here; 0 or more than 3 components is an error over the brackets.
    pub(super) fn vector(&self, input: &'a str, context: Context) -> PResult<'a, VectorNode> {
        let input = self.skip_blanks(input, context.nested);
        let (after, open) = self.punct(input, '[')?;
        let inner = Context {
            nested: true,
            ..self.deeper(context, input)?
        };
        let (rest, (components, _depth, close)) = self.list(after, open, ']', inner)?;
        let span = open.join(close);
        if !(1..=3).contains(&components.len()) {
            let message = format!("a vector has 1 to 3 components, found {}", components.len());
            return Err(self.fail(rest, Diagnostic::new(span, message)));
        }
        Ok((rest, Spanned::new(components, span)))
    }

    /// Comma-separated expressions up to `close` (the opening bracket is already read):
    /// the items, their greatest depth and the span of the closing bracket. An empty list
    /// is allowed here; callers decide whether it makes sense.
    fn list(
        &self,
        after_open: &'a str,
        open: Span,
        close: char,
        context: Context,
    ) -> PResult<'a, (Vec<ExprNode>, u32, Span)> {
        let expected = format!("an operator, `,` or `{close}`");
        let at = self.skip_blanks(after_open, true);
        if let Ok((rest, close_span)) = self.punct(at, close) {
            return Ok((rest, (Vec::new(), 0, close_span)));
        }
        let mut items = Vec::new();
        let mut depth = 0;
        let mut rest = after_open;
        let mut after = if close == ')' { "(" } else { "[" };
        loop {
            let (next, (item, item_depth)) = self.required_expression(rest, context, after)?;
            items.push(item);
            depth = depth.max(item_depth);
            let at = self.skip_blanks(next, true);
            if let Ok((next, _)) = self.punct(at, ',') {
                rest = next;
                after = ",";
                continue;
            }
            let (next, close_span) = self.close(next, close, open, &expected)?;
            return Ok((next, (items, depth, close_span)));
        }
    }

    /// The closing `close` of the bracket opened at `open`. If the statement visibly ended
    /// first (end of input, `;`, or a new statement on a later line), the error is
    /// "unclosed `(` opened here" at the `(` and recovery resumes where the parse stopped;
    /// otherwise it is "unexpected …" at the stray text.
    fn close(&self, input: &'a str, close: char, open: Span, expected: &str) -> PResult<'a, Span> {
        let at = self.skip_blanks(input, true);
        if let Ok(closed) = self.punct(at, close) {
            return Ok(closed);
        }
        let opener = if close == ')' { '(' } else { '[' };
        let skipped = input.get(..input.len() - at.len()).unwrap_or("");
        let statement_ended = at.is_empty()
            || at.starts_with(';')
            || (skipped.contains('\n') && super::recovery::looks_like_statement(at));
        if statement_ended {
            let (found, _) = self.found(at);
            let diagnostic = Diagnostic::new(open, format!("unclosed `{opener}` opened here"))
                .with_help(format!("expected `{close}` before {found}"));
            return Err(self.fail(at, diagnostic));
        }
        let diagnostic = self.unexpected_diagnostic(at, expected).with_help(format!(
            "the `{opener}` opened at {}:{} is still open",
            open.line, open.column
        ));
        Err(self.fail(at, diagnostic))
    }

    /// A binary node over `lhs` and `rhs`, within [`MAX_DEPTH`].
    fn binary(
        &self,
        op: BinOp,
        lhs: Parsed,
        rhs: Parsed,
        rest: &'a str,
    ) -> Result<Parsed, nom::Err<super::ParseError>> {
        let ((lhs, lhs_depth), (rhs, rhs_depth)) = (lhs, rhs);
        let span = lhs.span.join(rhs.span);
        let depth = self.limit_depth(lhs_depth.max(rhs_depth) + 1, rhs.span, rest)?;
        Ok((
            Spanned::new(Box::new(Expr::Binary { op, lhs, rhs }), span),
            depth,
        ))
    }

    /// `depth` if within [`MAX_DEPTH`], else an error pointing at `span`.
    fn limit_depth(
        &self,
        depth: u32,
        span: Span,
        rest: &'a str,
    ) -> Result<u32, nom::Err<super::ParseError>> {
        if depth <= MAX_DEPTH {
            return Ok(depth);
        }
        let diagnostic = Diagnostic::new(
            span,
            format!("expression too deep: more than {MAX_DEPTH} nested operations"),
        )
        .with_help("split it into parts with `let`");
        Err(self.fail(rest, diagnostic))
    }

    /// The context one level deeper, within [`MAX_NESTING`]; `at` is the opening token.
    fn deeper(
        &self,
        context: Context,
        at: &'a str,
    ) -> Result<Context, nom::Err<super::ParseError>> {
        if context.nesting < MAX_NESTING {
            return Ok(Context {
                nesting: context.nesting + 1,
                ..context
            });
        }
        let (_, span) = self.found(at);
        let diagnostic = Diagnostic::new(
            span,
            format!(
                "expression nested too deeply: more than {MAX_NESTING} levels of \
                 parentheses, brackets, signs or powers"
            ),
        )
        .with_help("split it into parts with `let`");
        Err(self.fail(at, diagnostic))
    }
}
