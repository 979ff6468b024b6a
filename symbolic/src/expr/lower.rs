//! Lowering: from the parser's syntax tree ([`ExprNode`]) to a canonical expression.
//!
//! Names are resolved by a [`Resolver`] supplied by the caller (the mechanics stage knows
//! which names are coordinates, masses, parameters); every error of one expression is
//! collected, so the user sees them all at once.

use super::func::Func;
use super::input_call::substitute_arguments;
use super::node::Id;
use super::pool::ExprPool;
use super::symbol::{Symbol, SymbolKind};
use crate::parse::ast::{BinOp, Expr, ExprNode};
use crate::parse::keywords::FUNCTIONS;
use crate::parse::{Diagnostic, Span, Spanned};

/// A name as written in the DSL: `x`, `x'` or `x''`, and where.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Written<'a> {
    /// The name without its primes.
    pub name: &'a str,
    /// The number of primes after it (0, 1 or 2 in valid text).
    pub primes: u8,
    /// Where it is written.
    pub span: Span,
}

impl Written<'_> {
    /// The name with its primes, as written (`x''`).
    pub fn text(&self) -> String {
        format!("{}{}", self.name, "'".repeat(self.primes.into()))
    }
}

/// Turns a name written in the DSL into an expression.
pub trait Resolver {
    /// The expression for `written`: a name, a velocity `x'` or an acceleration `x''`.
    fn resolve(&mut self, pool: &mut ExprPool, written: Written<'_>) -> Result<Id, Diagnostic>;

    /// The pool's index of the table called `name` (a `table` statement), if it is one.
    fn table(&self, name: &str) -> Option<u16> {
        let _ = name;
        None
    }

    /// The pool's index of the input called `name` (an `input` statement) and its number
    /// of arguments, if it is one.
    fn input(&self, name: &str) -> Option<(u16, usize)> {
        let _ = name;
        None
    }
}

/// Resolves names already in the pool's symbol table: `x` to its symbol, `x'` and `x''`
/// to the velocity and acceleration of coordinate `x`. Handy for tests and `check` lines.
#[derive(Clone, Copy, Debug, Default)]
pub struct TableResolver;

impl Resolver for TableResolver {
    fn resolve(&mut self, pool: &mut ExprPool, written: Written<'_>) -> Result<Id, Diagnostic> {
        let Written { name, primes, span } = written;
        let table = pool.symbols();
        let Some(s) = table.lookup(name) else {
            return Err(Diagnostic::new(span, format!("unknown symbol `{name}`")));
        };
        let target = match primes {
            0 => Some(s),
            1 => table.velocity_of(s),
            2 => table.acceleration_of(s),
            _ => None,
        };
        match target {
            Some(t) => Ok(pool.sym(t)),
            None if table.kind(s) == SymbolKind::Coordinate => Err(Diagnostic::new(
                span,
                format!("`{}` has too many primes", written.text()),
            )
            .with_help("write `x'` for a velocity or `x''` for an acceleration")),
            None => Err(Diagnostic::new(
                span,
                format!(
                    "`{name}` is not a coordinate, so `{}` has no meaning",
                    written.text()
                ),
            )),
        }
    }
}

/// The names the DSL accepts as functions, for messages.
/// `sqrt` is a power, not a [`Func`].
const SQRT: &str = "sqrt";

/// The names of `keywords::FUNCTIONS`, the one list of the DSL's functions.
fn known_functions() -> String {
    let names: Vec<&str> = FUNCTIONS.iter().map(|(name, _)| *name).collect();
    names.join(", ")
}

/// Lowers `node` into `pool`, resolving names with `resolver`. Every error found is
/// returned, not just the first.
pub fn lower(
    pool: &mut ExprPool,
    node: &ExprNode,
    resolver: &mut dyn Resolver,
) -> Result<Id, Vec<Diagnostic>> {
    let mut errors = Vec::new();
    let id = lower_node(pool, node, resolver, &mut errors);
    match id {
        Some(id) if errors.is_empty() => Ok(id),
        _ => Err(errors),
    }
}

/// Recursion is bounded by the parser's nesting limit. On an error, `None` is returned
/// after recording it, and siblings are still lowered so that their errors are found too.
fn lower_node(
    pool: &mut ExprPool,
    node: &ExprNode,
    resolver: &mut dyn Resolver,
    errors: &mut Vec<Diagnostic>,
) -> Option<Id> {
    let span = node.span;
    match node.node.as_ref() {
        Expr::Number(text) => {
            let id = pool.literal(text);
            if id.is_none() {
                errors.push(Diagnostic::new(
                    span,
                    format!("`{text}` is not representable as an f64: it overflows to infinity or underflows to 0"),
                ));
            }
            id
        }
        Expr::Name(name) => {
            let written = Written {
                name,
                primes: 0,
                span,
            };
            record(resolver.resolve(pool, written), errors)
        }
        Expr::Derivative { name, order } => {
            let written = Written {
                name,
                primes: *order,
                span,
            };
            record(resolver.resolve(pool, written), errors)
        }
        Expr::Neg(inner) => {
            let inner = lower_node(pool, inner, resolver, errors)?;
            Some(pool.neg(inner))
        }
        Expr::Binary { op, lhs, rhs } => {
            let lhs = lower_node(pool, lhs, resolver, errors);
            let rhs = lower_node(pool, rhs, resolver, errors);
            let (a, b) = (lhs?, rhs?);
            Some(match op {
                BinOp::Add => pool.add(&[a, b]),
                BinOp::Sub => pool.sub(a, b),
                BinOp::Mul => pool.mul(&[a, b]),
                BinOp::Div => pool.div(a, b),
                BinOp::Pow => pool.pow(a, b),
            })
        }
        Expr::Call { func, args } => lower_call(pool, func, args, resolver, errors),
    }
}

/// A call `func(args…)`: an input with a law (its law, substituted), a held input, a
/// function of the DSL, a table or an input; its arguments lowered first, so that their
/// errors are found whatever the call's.
fn lower_call(
    pool: &mut ExprPool,
    func: &Spanned<String>,
    args: &[ExprNode],
    resolver: &mut dyn Resolver,
    errors: &mut Vec<Diagnostic>,
) -> Option<Id> {
    if let Some(swapped) = swapped_argument(pool, resolver, &func.node, args) {
        errors.push(swapped);
        return None;
    }
    if let Some((law, parameters)) = input_law(pool, resolver, &func.node, args.len()) {
        let law = substitute_arguments(&law, &parameters, args, func.span);
        return lower_node(pool, &law, resolver, errors);
    }
    if let Some((input, held)) = held_input(pool, resolver, &func.node) {
        return record(held_call(pool, (input, held), args, func.span), errors);
    }
    let lowered: Vec<Option<Id>> = args
        .iter()
        .map(|a| lower_node(pool, a, resolver, errors))
        .collect();
    // The name and arity from the one list; `sqrt` is no [`Func`] but the power ½.
    let known = FUNCTIONS.iter().find(|(name, _)| *name == func.node);
    let table = resolver.table(&func.node);
    let input = resolver.input(&func.node);
    let (expected, f) = if let Some(&(_, arity)) = known {
        (arity, Func::from_name(&func.node))
    } else if let Some(table) = table {
        (1, Some(Func::Table { table, order: 0 }))
    } else if let Some((input, arity)) = input {
        (arity, Some(Func::Input { input, partial: 0 }))
    } else {
        errors.push(
            Diagnostic::new(func.span, format!("unknown function `{}`", func.node))
                .with_help(format!("known functions: {}", known_functions())),
        );
        return None;
    };
    if args.len() != expected {
        errors.push(Diagnostic::new(
            func.span,
            format!(
                "`{}` takes {expected} argument{}, found {}",
                func.node,
                if expected == 1 { "" } else { "s" },
                args.len()
            ),
        ));
        return None;
    }
    let args: Vec<Id> = lowered.into_iter().collect::<Option<_>>()?;
    match (f, args.as_slice()) {
        (Some(Func::Table { table, order }), [u]) => Some(pool.table_call(table, order, *u)),
        (Some(f), _) => Some(pool.call(f, &args)),
        (None, [u]) if func.node == SQRT => Some(pool.sqrt(*u)),
        // A name of FUNCTIONS without a `Func` (tested not to exist).
        (None, _) => None,
    }
}

/// The law of input `name` and its declared arguments, when `name` is an input with a law
/// called with its number of arguments (otherwise the call is lowered, or refused, as any
/// other).
fn input_law(
    pool: &ExprPool,
    resolver: &dyn Resolver,
    name: &str,
    count: usize,
) -> Option<(ExprNode, Vec<String>)> {
    let (input, arity) = resolver.input(name)?;
    if arity != count {
        return None;
    }
    let law = pool.input_law(input)?.clone();
    Some((law, pool.input_arguments(input).to_vec()))
}

/// A call of input `name` that passes, as argument j, a bare name the input declares at
/// another position (`u(y, t)` for `input u(t, y)`): the Rust function (and a law) take
/// their arguments by position, so the values would arrive swapped, silently.
fn swapped_argument(
    pool: &ExprPool,
    resolver: &dyn Resolver,
    name: &str,
    args: &[ExprNode],
) -> Option<Diagnostic> {
    let (input, _) = resolver.input(name)?;
    let declared = pool.input_arguments(input);
    args.iter().enumerate().find_map(|(j, arg)| {
        let written = written_name(arg)?;
        let k = declared.iter().position(|d| *d == written)?;
        (k != j).then(|| {
            Diagnostic::new(
                arg.span,
                format!(
                    "input `{name}` is declared `{name}({})`: its argument {} is `{written}`, \
                     which the declaration puts at argument {}",
                    declared.join(", "),
                    j + 1,
                    k + 1
                ),
            )
            .with_help(
                "an input takes its arguments by position: pass them in the declared order \
                 (to evaluate it at other values on purpose, name them with a `let`)",
            )
        })
    })
}

/// The name an argument is written as when it is a bare name or a velocity (`y`, `y'`).
fn written_name(a: &ExprNode) -> Option<String> {
    match a.node.as_ref() {
        Expr::Name(n) => Some(n.clone()),
        Expr::Derivative { name, order } => {
            Some(format!("{name}{}", "'".repeat(usize::from(*order))))
        }
        _ => None,
    }
}

/// The index and held value of input `name` if it is a sampled input.
fn held_input(pool: &ExprPool, resolver: &dyn Resolver, name: &str) -> Option<(u16, Symbol)> {
    let (input, _) = resolver.input(name)?;
    Some((input, pool.input_held(input)?))
}

/// A call of a sampled input: its held value, the input's value at the last sample
/// (docs/inputs.md#sampled-inputs). The sample evaluates the input at its declared
/// arguments, so a call must pass exactly those (`u(t, y, y')`): any other argument would
/// ask for a value nothing sampled.
fn held_call(
    pool: &mut ExprPool,
    (input, held): (u16, Symbol),
    args: &[ExprNode],
    span: Span,
) -> Result<Id, Diagnostic> {
    let declared = pool.input_arguments(input);
    let same = args.len() == declared.len()
        && (args.iter().zip(declared)).all(|(a, d)| written_name(a).as_deref() == Some(d.as_str()));
    if same {
        return Ok(pool.sym(held));
    }
    let name = pool.input_name(input);
    Err(Diagnostic::new(
        span,
        format!(
            "sampled input `{name}` is called with its declared arguments only: `{name}({})`",
            declared.join(", ")
        ),
    )
    .with_help("its value is held from the last sample, taken at the declared arguments"))
}

fn record(result: Result<Id, Diagnostic>, errors: &mut Vec<Diagnostic>) -> Option<Id> {
    result.map_err(|e| errors.push(e)).ok()
}
