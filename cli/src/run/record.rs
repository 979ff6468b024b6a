//! What `--record` takes: the model's quantities by name (as `--stop-when` does), and beyond
//! them `mdot_<mass>`, the model's `let` names, its tables (`rho(y + h0)` at any argument,
//! `rho` alone at the argument the model calls it with), and any expression of these (with
//! the DSL's functions, `sqrt` among them), the parameters and `t`, named (`--record "E=1/2*m*x'^2"`) or not (`--record "x*sin(theta)"`, its
//! column named by its text).
//!
//! An expression is parsed by the DSL's own expression grammar, every name resolved once
//! when the run is planned (an unknown name is an error with the nearest one), and
//! evaluated at each recorded point from the quantities it reads.

use varmass::core::SystemError;
use varmass::interpret::{Program, Quantity};
use varmass::symbolic::compose::defaults;
use varmass::symbolic::expr::{Func, Node};
use varmass::symbolic::parse::ast::{BinOp, Expr, ExprNode, StatementKind, SystemAst};
use varmass::symbolic::parse::parse_expression;

use super::names::{evaluate, resolve, velocity_state, Observable};
use crate::args::Words;
use crate::error::CliError;

/// One recorded column's value.
#[derive(Clone, Debug)]
pub enum Recorded {
    /// A quantity of the model.
    Quantity(Observable),
    /// An expression of recordable names.
    Expression(Term),
}

/// A resolved expression.
#[derive(Clone, Debug)]
pub enum Term {
    /// A number or a parameter's value.
    Constant(f64),
    /// t.
    Time,
    /// A quantity of the model.
    Quantity(Observable),
    /// ṁ of mass `i`.
    MassRate(usize),
    /// −a.
    Neg(Box<Term>),
    /// a ∘ b.
    Binary(BinOp, Box<Term>, Box<Term>),
    /// f(a, …).
    Call(Func, Vec<Term>),
    /// √a.
    Sqrt(Box<Term>),
    /// The pool's table `.0` at `.1` (`Program::table_value`).
    Table(u16, Box<Term>),
}

/// A table of the model as a recorded expression reads it: its index in the derivation's
/// pool, and the arguments (DSL text) the model calls it with.
pub struct TableScope {
    /// The table's name.
    pub name: String,
    /// Its index in the pool.
    pub index: u16,
    /// The distinct arguments of the model's calls of the table itself (not its derivatives).
    pub calls: Vec<String>,
}

/// What an expression's names can be, besides the model's quantities.
pub struct Scope<'a> {
    /// The quantities, as [`super::names::observables`] lists them.
    pub quantities: &'a [(String, Observable)],
    /// The parameter values: those of the run, then the defaults of the model's
    /// `parameter`s that the run has no value for (a component's `let` may read one that no
    /// equation reads, `air_gamma` of a speed of sound: docs/components.md#defaults).
    pub parameters: Vec<(String, f64)>,
    /// The masses' names, in mass order (for `mdot_<mass>`).
    pub masses: Vec<String>,
    /// The model's `let` definitions, in order.
    pub lets: Vec<(String, ExprNode)>,
    /// The model's tables: `rho(y)` reads one at any argument, `rho` alone at the argument
    /// the model calls it with.
    pub tables: Vec<TableScope>,
}

impl<'a> Scope<'a> {
    /// The scope of `program`'s run with `parameters`, the lets taken from `ast`.
    pub fn new(
        program: &Program,
        ast: &SystemAst,
        quantities: &'a [(String, Observable)],
        parameters: &'a [(String, f64)],
    ) -> Self {
        let lets = ast
            .statements
            .iter()
            .filter_map(|s| match &s.kind {
                StatementKind::Let { name, value } => Some((name.node.clone(), value.clone())),
                _ => None,
            })
            .collect();
        let mut all = parameters.to_vec();
        for (name, value) in defaults(ast) {
            if !all.iter().any(|(n, _)| *n == name) {
                all.push((name, value));
            }
        }
        Self {
            quantities,
            parameters: all,
            masses: program.mass_names().map(str::to_string).collect(),
            lets,
            tables: tables(program),
        }
    }

    /// Every name an expression may use, for the "did you mean" of an unknown one.
    fn names(&self) -> Vec<(String, ())> {
        let mut names: Vec<String> = self.quantities.iter().map(|(n, _)| n.clone()).collect();
        names.extend(self.masses.iter().map(|m| format!("mdot_{m}")));
        names.extend(self.lets.iter().map(|(n, _)| n.clone()));
        names.extend(self.tables.iter().map(|t| t.name.clone()));
        names.extend(self.parameters.iter().map(|(n, _)| n.clone()));
        names.push("t".to_string());
        // `mdot_<mass>` is a registry quantity too where the model derives it: named once.
        let mut seen = std::collections::HashSet::new();
        names.retain(|n| seen.insert(n.clone()));
        names.into_iter().map(|n| (n, ())).collect()
    }
}

/// The tables of `program`, each with the arguments the derivation calls it with (printed as
/// DSL text, which reads back to the same expression): what `--record rho` records.
fn tables(program: &Program) -> Vec<TableScope> {
    let pool = &program.derivation().pool;
    let mut tables: Vec<TableScope> = (0..pool.table_count())
        .filter_map(|i| u16::try_from(i).ok())
        .map(|index| TableScope {
            name: pool.table_name(index).to_string(),
            index,
            calls: Vec::new(),
        })
        .collect();
    for id in pool.ids() {
        if let Node::Call(Func::Table { table, order: 0 }, args) = pool.node(id) {
            let (Some(entry), [argument]) = (tables.get_mut(usize::from(*table)), &args[..]) else {
                continue;
            };
            let text = pool.display(*argument).to_string();
            if !entry.calls.contains(&text) {
                entry.calls.push(text);
            }
        }
    }
    tables
}

/// The recorded columns of `values` (`--record`, a scene's `record`), each entry resolved by
/// [`recorded`]. Values that name nothing (`--record ''`) are refused, and so is a column
/// named twice or named `t` (the time is always the first column): a CSV with two columns
/// of one name is read wrongly by most tools.
pub fn columns(
    values: &[String],
    scope: &Scope<'_>,
    words: Words,
) -> Result<Vec<(String, Recorded)>, CliError> {
    let setting = words.setting("--record");
    let list = entries(values);
    if list.is_empty() && !values.is_empty() {
        return Err(CliError::Input(format!(
            "{setting} names no quantity: give NAME[, NAME …], or leave it out for the default \
             columns"
        )));
    }
    let mut columns: Vec<(String, Recorded)> = Vec::with_capacity(list.len());
    for entry in &list {
        let (name, what) = recorded(entry, scope, words)?;
        let why = match name.as_str() {
            "t" => "the time is always the first column",
            _ if columns.iter().any(|(n, _)| *n == name) => "it is recorded already",
            _ => {
                columns.push((name, what));
                continue;
            }
        };
        return Err(CliError::Input(format!(
            "{setting} `{entry}`: the column `{name}` cannot be recorded again: {why}"
        )));
    }
    Ok(columns)
}

/// Splits `--record` values at the commas outside parentheses (an expression may call
/// `atan2(y, x)`), trimmed, empty entries dropped.
pub fn entries(values: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    for value in values {
        let (mut depth, mut start) = (0_i32, 0);
        for (i, c) in value.char_indices() {
            match c {
                '(' | '[' => depth += 1,
                ')' | ']' => depth -= 1,
                ',' if depth <= 0 => {
                    out.push(value[start..i].trim().to_string());
                    start = i + 1;
                }
                _ => {}
            }
        }
        out.push(value[start..].trim().to_string());
    }
    out.retain(|e| !e.is_empty());
    out
}

/// One `--record` entry: a quantity's name, `NAME=EXPRESSION`, or an expression.
pub fn recorded(
    entry: &str,
    scope: &Scope<'_>,
    words: Words,
) -> Result<(String, Recorded), CliError> {
    if let Some((_, observable)) = scope.quantities.iter().find(|(n, _)| n == entry) {
        return Ok((entry.to_string(), Recorded::Quantity(*observable)));
    }
    let (name, text) = named_entry(entry);
    let setting = words.setting("--record");
    if name != text && scope.names().iter().any(|(n, _)| n == name) {
        // A column headed `x` holding x' would be read as the coordinate by whoever reads
        // the table, while expressions and `--stop-when` still mean the model's `x`.
        return Err(CliError::Input(format!(
            "{setting} `{entry}`: the column `{name}` would hide the model's own `{name}`: \
             name it something else"
        )));
    }
    let node = parse_expression(text).map_err(|d| {
        CliError::Input(format!(
            "{setting} `{entry}`: {} (at `{}`)",
            d.message,
            text.get(d.span.start..d.span.end).unwrap_or(text)
        ))
    })?;
    let term = resolve_term(&node, scope, 0).map_err(|e| match e {
        CliError::Input(message) => CliError::Input(format!("{setting} `{entry}`: {message}")),
        other => other,
    })?;
    Ok((name.to_string(), Recorded::Expression(term)))
}

/// The column name and the expression of a `--record` entry (or an ensemble's
/// observable): `NAME=EXPRESSION` is named `NAME`, anything else by its own text.
fn named_entry(entry: &str) -> (&str, &str) {
    match entry.split_once('=') {
        Some((name, text)) if is_identifier(name.trim()) => (name.trim(), text.trim()),
        _ => (entry, entry),
    }
}

/// The column `entry` is recorded under, as `--record` names it: `MU` for `MU=mu`.
pub fn column_name(entry: &str) -> &str {
    named_entry(entry).0
}

fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// How deep `let`s may refer to `let`s: far beyond any model, and a guard against a
/// definition that names itself.
const MAX_LET_DEPTH: usize = 64;

fn resolve_term(node: &ExprNode, scope: &Scope<'_>, depth: usize) -> Result<Term, CliError> {
    let resolve_box = |n: &ExprNode| resolve_term(n, scope, depth).map(Box::new);
    Ok(match &*node.node {
        Expr::Number(text) => Term::Constant(
            text.parse::<f64>()
                .map_err(|_| CliError::Input(format!("`{text}` is not a number")))?,
        ),
        Expr::Name(name) => name_term(name, scope, depth)?,
        Expr::Derivative { name, order } => {
            let written = format!("{name}{}", "'".repeat(usize::from(*order)));
            Term::Quantity(resolve(&written, scope.quantities, "a quantity")?)
        }
        Expr::Neg(a) => Term::Neg(resolve_box(a)?),
        Expr::Binary { op, lhs, rhs } => Term::Binary(*op, resolve_box(lhs)?, resolve_box(rhs)?),
        Expr::Call { func, args } if args.len() == 1 && func.node == "sqrt" => {
            Term::Sqrt(resolve_box(&args[0])?)
        }
        Expr::Call { func, args } if scope.table(&func.node).is_some() => {
            let table = scope.table(&func.node).map_or(0, |t| t.index);
            match &args[..] {
                [argument] => Term::Table(table, resolve_box(argument)?),
                _ => {
                    return Err(CliError::Input(format!(
                        "`{}` is a table: a function of one argument, given {}",
                        func.node,
                        args.len()
                    )))
                }
            }
        }
        Expr::Call { func, args } => {
            let f = dsl_function(&func.node, args.len())?;
            let args = args
                .iter()
                .map(|a| resolve_term(a, scope, depth))
                .collect::<Result<_, _>>()?;
            Term::Call(f, args)
        }
    })
}

/// The DSL's function `name` taking `arity` arguments (`sqrt` aside, which the callers
/// read first), or the message that there is none: the one lookup of recorded expressions
/// and of the values a scene sets at a change.
pub(crate) fn dsl_function(name: &str, arity: usize) -> Result<Func, CliError> {
    Func::from_name(name)
        .filter(|f| f.arity() == arity)
        .ok_or_else(|| {
            CliError::Input(format!(
                "`{name}` with {arity} argument(s) is not a function of the DSL"
            ))
        })
}

/// `a op b`, as the derivation's expressions compute it.
pub(crate) fn binary(op: BinOp, a: f64, b: f64) -> f64 {
    match op {
        BinOp::Add => a + b,
        BinOp::Sub => a - b,
        BinOp::Mul => a * b,
        BinOp::Div => a / b,
        BinOp::Pow => a.powf(b),
    }
}

/// A name: a quantity, `t`, `mdot_<mass>`, a parameter or a `let` (resolved in turn).
fn name_term(name: &str, scope: &Scope<'_>, depth: usize) -> Result<Term, CliError> {
    if let Some((_, o)) = scope.quantities.iter().find(|(n, _)| n == name) {
        return Ok(Term::Quantity(*o));
    }
    if name == "t" {
        return Ok(Term::Time);
    }
    if let Some(i) = name
        .strip_prefix("mdot_")
        .and_then(|m| scope.masses.iter().position(|n| n == m))
    {
        return Ok(Term::MassRate(i));
    }
    if let Some((_, value)) = scope.parameters.iter().find(|(n, _)| n == name) {
        return Ok(Term::Constant(*value));
    }
    if let Some(table) = scope.table(name) {
        return table_at_its_call(table, scope, depth);
    }
    if let Some((_, value)) = scope.lets.iter().find(|(n, _)| n == name) {
        if depth >= MAX_LET_DEPTH {
            return Err(CliError::Input(format!(
                "the definition of `{name}` refers to itself"
            )));
        }
        return resolve_term(value, scope, depth + 1);
    }
    match resolve(name, &scope.names(), "a quantity") {
        Err(unknown) => Err(unknown),
        // Every name of the list was tried above; this is for completeness.
        Ok(()) => Err(CliError::Input(format!("`{name}` cannot be recorded"))),
    }
}

/// Table `table` alone: read at the argument the model calls it with, if that is one
/// expression; else the message says to give the argument.
fn table_at_its_call(
    table: &TableScope,
    scope: &Scope<'_>,
    depth: usize,
) -> Result<Term, CliError> {
    let name = &table.name;
    let [call] = &table.calls[..] else {
        let calls = match table.calls.len() {
            0 => "the model does not call it".to_string(),
            _ => format!("the model calls it at {}", table.calls.join(", ")),
        };
        return Err(CliError::Input(format!(
            "`{name}` is a table: {calls}; record it at an argument, as `{name}(ARGUMENT)`"
        )));
    };
    let node = parse_expression(call).map_err(|d| {
        CliError::Input(format!(
            "the argument `{call}` of table `{name}`: {}",
            d.message
        ))
    })?;
    let argument = resolve_term(&node, scope, depth)?;
    Ok(Term::Table(table.index, Box::new(argument)))
}

impl Scope<'_> {
    /// The model's table `name`.
    fn table(&self, name: &str) -> Option<&TableScope> {
        self.tables.iter().find(|t| t.name == name)
    }
}

impl Recorded {
    /// The value at `(t, state)`, `state` = `[q, p, m_s]`.
    pub fn value(&self, program: &Program, t: f64, state: &[f64]) -> Result<f64, SystemError> {
        match self {
            Recorded::Quantity(o) => evaluate(program, *o, t, state),
            Recorded::Expression(term) => term.value(program, t, state),
        }
    }
}

impl Term {
    fn value(&self, program: &Program, t: f64, state: &[f64]) -> Result<f64, SystemError> {
        let of = |term: &Term| term.value(program, t, state);
        Ok(match self {
            Term::Constant(c) => *c,
            Term::Time => t,
            Term::Quantity(o) => evaluate(program, *o, t, state)?,
            Term::MassRate(i) => {
                let velocity_state = velocity_state(program, t, state)?;
                let mut rates = vec![f64::NAN; program.derivation().masses.len()];
                program.evaluate(Quantity::MassRates, t, &velocity_state, &mut rates);
                rates.get(*i).copied().unwrap_or(f64::NAN)
            }
            Term::Neg(a) => -of(a)?,
            Term::Binary(op, a, b) => binary(*op, of(a)?, of(b)?),
            Term::Call(f, args) => {
                let args = args.iter().map(of).collect::<Result<Vec<f64>, _>>()?;
                f.apply(&args)
            }
            Term::Sqrt(a) => of(a)?.sqrt(),
            Term::Table(table, argument) => program.table_value(*table, of(argument)?)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_split_at_top_level_commas_only() {
        let values = ["x, E=1/2*m*x'^2".to_string(), "atan2(y, x),H".to_string()];
        assert_eq!(entries(&values), ["x", "E=1/2*m*x'^2", "atan2(y, x)", "H"]);
    }

    #[test]
    fn an_assignment_is_named_by_its_name_and_an_expression_by_its_text() {
        assert_eq!(column_name("MU=mu"), "MU");
        assert_eq!(column_name(" E = 1/2*m*x'^2"), "E");
        assert_eq!(column_name("x*sin(theta)"), "x*sin(theta)");
        // Not an identifier before `=`: the whole text (the parser then refuses it).
        assert_eq!(column_name("2x=y"), "2x=y");
    }
}
