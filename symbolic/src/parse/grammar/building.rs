//! The non-recursive steps of expression parsing: operators and signs, node building with
//! the depth limits, brackets and their errors. They run between the recursive calls of
//! `expression.rs`, so their locals never pile up on the stack.

use super::expression::{Items, Parsed, EXPRESSION};
use super::{Context, Grammar, PResult, ParseError, MAX_DEPTH, MAX_NESTING};
use crate::parse::ast::{BinOp, Expr, ExprNode, VectorNode};
use crate::parse::span::{Diagnostic, Span, Spanned};
use nom::bytes::complete::take_while;
use nom::character::complete::one_of;
use nom::Parser;

/// Either a value or a syntax error.
type Step<T> = Result<T, nom::Err<ParseError>>;

/// A sum of products being folded left to right: the product being built is `term`, the
/// sum before it is `sum` with the operator that will join them.
pub(super) struct Chain<'a> {
    rest: &'a str,
    term: Parsed,
    sum: Option<(Parsed, BinOp)>,
}

impl<'a> Chain<'a> {
    pub(super) fn new((rest, term): (&'a str, Parsed)) -> Self {
        Chain {
            rest,
            term,
            sum: None,
        }
    }
}

/// A leading minus sign, or none.
pub(super) enum Sign<'a> {
    /// No sign; the input after blanks.
    None(&'a str),
    /// A sign: the input after it, its span, and the context of its operand.
    Minus(&'a str, Span, Context),
}

/// A name that is complete, or the name of a call whose `(` is at the given input.
pub(super) enum Named<'a> {
    Done(&'a str, Parsed),
    Callee(Spanned<String>, &'a str),
}

/// After an item of a list: more items follow (from the input given), or the list closed
/// (input after it, span of the closing bracket).
pub(super) enum ListStep<'a> {
    More(&'a str),
    Done(&'a str, Span),
}

impl<'a> Grammar<'a> {
    /// The next `+ - * /` after the chain, with the input after it.
    pub(super) fn operator(&self, chain: &Chain<'a>, context: Context) -> Option<(&'a str, BinOp)> {
        let at = self.skip_blanks(chain.rest, context.nested);
        let found: PResult<'a, char> = one_of("+-*/").parse(at);
        let (after, symbol) = found.ok()?;
        let op = match symbol {
            '+' => BinOp::Add,
            '-' => BinOp::Sub,
            '*' => BinOp::Mul,
            _ => BinOp::Div,
        };
        Some((after, op))
    }

    /// The chain extended by `op operand`: a product binds at once, a sum waits for the
    /// product that follows it.
    pub(super) fn extend_chain(
        &self,
        chain: Chain<'a>,
        op: BinOp,
        operand: PResult<'a, Parsed>,
        after: &'a str,
        context: Context,
    ) -> Step<Chain<'a>> {
        let written = op.to_string();
        let (rest, operand) =
            self.or_missing(operand, after, context.nested, EXPRESSION, &written)?;
        let Chain { term, sum, .. } = chain;
        if matches!(op, BinOp::Mul | BinOp::Div) {
            let term = self.binary(op, term, operand, rest)?;
            return Ok(Chain { rest, term, sum });
        }
        let left = match sum {
            Some((left, pending)) => self.binary(pending, left, term, rest)?,
            None => term,
        };
        Ok(Chain {
            rest,
            term: operand,
            sum: Some((left, op)),
        })
    }

    /// The folded chain.
    pub(super) fn finish_chain(&self, chain: Chain<'a>) -> PResult<'a, Parsed> {
        match chain.sum {
            Some((left, pending)) => Ok((
                chain.rest,
                self.binary(pending, left, chain.term, chain.rest)?,
            )),
            None => Ok((chain.rest, chain.term)),
        }
    }

    /// A leading `-`, within [`MAX_NESTING`].
    pub(super) fn sign(&self, input: &'a str, context: Context) -> Step<Sign<'a>> {
        let input = self.skip_blanks(input, context.nested);
        match self.punct(input, '-') {
            Ok((after, minus)) => Ok(Sign::Minus(after, minus, self.deeper(context, input)?)),
            Err(_) => Ok(Sign::None(input)),
        }
    }

    /// `-operand`.
    pub(super) fn negate(
        &self,
        operand: PResult<'a, Parsed>,
        after: &'a str,
        minus: Span,
        context: Context,
    ) -> PResult<'a, Parsed> {
        let (rest, (operand, depth)) =
            self.or_missing(operand, after, context.nested, EXPRESSION, "-")?;
        let span = minus.join(operand.span);
        let depth = self.limit_depth(depth + 1, span, rest)?;
        Ok((
            rest,
            (Spanned::new(Box::new(Expr::Neg(operand)), span), depth),
        ))
    }

    /// A `^` after a base, with the input after it and the exponent's context.
    pub(super) fn caret(
        &self,
        rest: &'a str,
        context: Context,
    ) -> Step<Option<(&'a str, Context)>> {
        let at = self.skip_blanks(rest, context.nested);
        match self.punct(at, '^') {
            Ok((after, _)) => Ok(Some((after, self.deeper(context, at)?))),
            Err(_) => Ok(None),
        }
    }

    /// `base ^ exponent`.
    pub(super) fn raise(
        &self,
        base: Parsed,
        exponent: PResult<'a, Parsed>,
        after: &'a str,
        context: Context,
    ) -> PResult<'a, Parsed> {
        let (rest, exponent) = self.or_missing(exponent, after, context.nested, EXPRESSION, "^")?;
        Ok((rest, self.binary(BinOp::Pow, base, exponent, rest)?))
    }

    /// A name, `x'` or `x''`, or the name of a call.
    pub(super) fn named(&self, input: &'a str, context: Context) -> Step<Named<'a>> {
        let (rest, name) = self.identifier(input)?;
        let primes: PResult<'a, &'a str> = take_while(|c: char| c == '\'')(rest);
        let (after_primes, primes) = primes.unwrap_or((rest, ""));
        if !primes.is_empty() {
            let (rest, parsed) = self.derivative(name, primes.len(), after_primes)?;
            return Ok(Named::Done(rest, parsed));
        }
        let at = self.skip_blanks(rest, context.nested);
        if at.starts_with('(') {
            return Ok(Named::Callee(name, at));
        }
        let span = name.span;
        let node = Spanned::new(Box::new(Expr::Name(name.node)), span);
        Ok(Named::Done(rest, (node, 1)))
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

    /// The bracket `bracket` at `input`: the input after it, its span, and the context
    /// inside it (one level deeper, where newlines are blanks).
    pub(super) fn open(
        &self,
        input: &'a str,
        bracket: char,
        context: Context,
    ) -> PResult<'a, (Span, Context)> {
        let (after, open) = self.punct(input, bracket)?;
        let inner = Context {
            nested: true,
            ..self.deeper(context, input)?
        };
        Ok((after, (open, inner)))
    }

    /// `( inside )`, the node widened over the parentheses.
    pub(super) fn finish_parenthesized(
        &self,
        inside: PResult<'a, Parsed>,
        after: &'a str,
        open: Span,
    ) -> PResult<'a, Parsed> {
        let (rest, (mut node, depth)) = self.or_missing(inside, after, true, EXPRESSION, "(")?;
        let (rest, close) = self.close(rest, ')', open, "an operator or `)`")?;
        node.span = open.join(close);
        Ok((rest, (node, depth)))
    }

    /// `func(items)`.
    pub(super) fn finish_call(
        &self,
        func: Spanned<String>,
        items: PResult<'a, Items>,
    ) -> PResult<'a, Parsed> {
        let (rest, (args, depth, close)) = items?;
        let span = func.span.join(close);
        let depth = self.limit_depth(depth + 1, span, rest)?;
        let node = Spanned::new(Box::new(Expr::Call { func, args }), span);
        Ok((rest, (node, depth)))
    }

    /// `[items]`, with 1 to 3 components.
    pub(super) fn finish_vector(
        &self,
        items: PResult<'a, Items>,
        open: Span,
    ) -> PResult<'a, VectorNode> {
        let (rest, (components, _depth, close)) = items?;
        let span = open.join(close);
        if !(1..=3).contains(&components.len()) {
            let found = components.len();
            let message = format!("a vector has 1 to 3 components, found {found}");
            return Err(self.fail(rest, Diagnostic::new(span, message)));
        }
        Ok((rest, Spanned::new(components, span)))
    }

    /// The list closed right after its opening bracket.
    pub(super) fn empty_list(&self, after_open: &'a str, close: char) -> Option<(&'a str, Items)> {
        let at = self.skip_blanks(after_open, true);
        let (rest, close_span) = self.punct(at, close).ok()?;
        Some((rest, (Vec::new(), 0, close_span)))
    }

    /// Takes the item just parsed (from `input`), raising the list's greatest `depth`,
    /// and reads the `,` or closing bracket after it.
    pub(super) fn list_step(
        &self,
        items: &mut Vec<ExprNode>,
        depth: &mut u32,
        item: PResult<'a, Parsed>,
        input: &'a str,
        open: Span,
        close: char,
    ) -> Step<ListStep<'a>> {
        let after = match items.len() {
            0 if close == ')' => "(",
            0 => "[",
            _ => ",",
        };
        let (rest, (item, item_depth)) = self.or_missing(item, input, true, EXPRESSION, after)?;
        items.push(item);
        *depth = (*depth).max(item_depth);
        let at = self.skip_blanks(rest, true);
        if let Ok((next, _)) = self.punct(at, ',') {
            return Ok(ListStep::More(next));
        }
        let expected = format!("an operator, `,` or `{close}`");
        let (next, close_span) = self.close(rest, close, open, &expected)?;
        Ok(ListStep::Done(next, close_span))
    }

    /// The closing `close` of the bracket opened at `open`. If the statement visibly ended
    /// first (end of input, `;`, or a new statement on a later line), the error is
    /// "unclosed `(` opened here" at the `(` and recovery resumes where the parse stopped;
    /// otherwise it is "unexpected …" at the stray text.
    pub(super) fn close(
        &self,
        input: &'a str,
        close: char,
        open: Span,
        expected: &str,
    ) -> PResult<'a, Span> {
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
    fn binary(&self, op: BinOp, lhs: Parsed, rhs: Parsed, rest: &'a str) -> Step<Parsed> {
        let ((lhs, lhs_depth), (rhs, rhs_depth)) = (lhs, rhs);
        let span = lhs.span.join(rhs.span);
        let depth = self.limit_depth(lhs_depth.max(rhs_depth) + 1, rhs.span, rest)?;
        let node = Spanned::new(Box::new(Expr::Binary { op, lhs, rhs }), span);
        Ok((node, depth))
    }

    /// `depth` if within [`MAX_DEPTH`], else an error pointing at `span`.
    fn limit_depth(&self, depth: u32, span: Span, rest: &'a str) -> Step<u32> {
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
    fn deeper(&self, context: Context, at: &'a str) -> Step<Context> {
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
