//! Values a `[[phase]]` sets at the time of its change: `set = { drogue_t_open = "t + 1.5" }`
//! (docs/scenes.md#a-value-set-at-the-change). The expression is an expression of `t`, the
//! time of the change, numbers and the parameters of the phase's model, with the DSL's
//! functions; it is parsed and its names resolved before the first step, and evaluated when
//! the run reaches the change, with the values in force there. The phase's program (and
//! the program that watches its end condition) then gets the value before the phase's first
//! step, so the parameter is exact from the change on, and it carries over to the later
//! phases as a number set there would.
//!
//! The run itself ([`run`]): the phases up to the first such phase run as one list, as
//! before; each phase that takes a value at its change begins a new list, continued from
//! the last point by the core's `continue_phases_keeping` once its parameters are set.

use std::cell::RefCell;
use std::ops::Range;

use varmass::core::{PhasedSolution, StepError, StopReason, Supported};
use varmass::interpret::Program;
use varmass::symbolic::expr::Func;
use varmass::symbolic::parse::ast::{BinOp, Expr, ExprNode};
use varmass::symbolic::parse::parse_expression;

use super::system::SceneSystem;
use crate::error::CliError;
use crate::run::names::{resolve, shown};
use crate::run::record::{binary, dsl_function};

type Phase<'a, Sys, const S: usize> = varmass::core::Phase<'a, Supported<Sys>, S>;

/// An expression of `t` and the parameters, its constant parts folded.
#[derive(Clone, Debug)]
enum Term {
    Number(f64),
    Time,
    Parameter(String),
    Neg(Box<Term>),
    Binary(BinOp, Box<Term>, Box<Term>),
    Call(Func, Vec<Term>),
    Sqrt(Box<Term>),
}

/// A value set at a change: the expression as written and resolved.
#[derive(Clone, Debug)]
pub struct SetExpression {
    /// As written, for messages.
    pub text: String,
    term: Term,
}

impl SetExpression {
    /// Parses `text` and resolves its names: `t`, or a parameter among `known` (the phase
    /// model's, each with a value in force before the run); every part that reads neither is
    /// evaluated now and must be finite (`"t + 1/0"` is refused here, not at the change).
    pub fn new(text: &str, known: &[(String, f64)]) -> Result<Self, CliError> {
        let node = parse_expression(text).map_err(|d| {
            CliError::Input(format!(
                "`{text}`: {} (at `{}`)",
                d.message,
                text.get(d.span.start..d.span.end).unwrap_or(text)
            ))
        })?;
        let term = resolved(&node, known).map_err(|e| match e {
            CliError::Input(m) => CliError::Input(format!("`{text}`: {m}")),
            other => other,
        })?;
        let term = folded(term);
        if let Some(bad) = non_finite_constant(&term) {
            return Err(CliError::Input(format!(
                "`{text}`: a part of it that does not depend on the run is {bad}: a \
                 parameter's value must be a finite number"
            )));
        }
        Ok(Self {
            text: text.to_string(),
            term,
        })
    }

    /// The value at the change's time `t` with the parameter values `values`.
    pub fn value(&self, t: f64, values: &[(String, f64)]) -> f64 {
        evaluate(&self.term, t, values)
    }
}

/// `node` with its names resolved: `t`, or a parameter of `known`.
fn resolved(node: &ExprNode, known: &[(String, f64)]) -> Result<Term, CliError> {
    let boxed = |n: &ExprNode| resolved(n, known).map(Box::new);
    Ok(match &*node.node {
        Expr::Number(text) => Term::Number(
            text.parse::<f64>()
                .map_err(|_| CliError::Input(format!("`{text}` is not a number")))?,
        ),
        Expr::Name(name) if name == "t" => Term::Time,
        Expr::Name(name) => {
            resolve(name, known, "a parameter")?;
            Term::Parameter(name.clone())
        }
        Expr::Derivative { name, .. } => {
            return Err(CliError::Input(format!(
                "`{name}'` is a quantity of the motion: a value set at a change reads `t` (the \
                 change's time), numbers and parameters (stop on the quantity with a `when`)"
            )))
        }
        Expr::Neg(a) => Term::Neg(boxed(a)?),
        Expr::Binary { op, lhs, rhs } => Term::Binary(*op, boxed(lhs)?, boxed(rhs)?),
        Expr::Call { func, args } if args.len() == 1 && func.node == "sqrt" => {
            Term::Sqrt(boxed(&args[0])?)
        }
        Expr::Call { func, args } => {
            let f = dsl_function(&func.node, args.len())?;
            let args = args.iter().map(|a| resolved(a, known));
            Term::Call(f, args.collect::<Result<_, _>>()?)
        }
    })
}

/// `term` with every part that reads no `t` and no parameter replaced by its value.
fn folded(term: Term) -> Term {
    let term = match term {
        Term::Neg(a) => Term::Neg(Box::new(folded(*a))),
        Term::Binary(op, a, b) => Term::Binary(op, Box::new(folded(*a)), Box::new(folded(*b))),
        Term::Call(f, args) => Term::Call(f, args.into_iter().map(folded).collect()),
        Term::Sqrt(a) => Term::Sqrt(Box::new(folded(*a))),
        leaf => leaf,
    };
    let constant = match &term {
        Term::Neg(a) | Term::Sqrt(a) => matches!(**a, Term::Number(_)),
        Term::Binary(_, a, b) => matches!((&**a, &**b), (Term::Number(_), Term::Number(_))),
        Term::Call(_, args) => args.iter().all(|a| matches!(a, Term::Number(_))),
        _ => false,
    };
    match constant {
        true => Term::Number(evaluate(&term, f64::NAN, &[])),
        false => term,
    }
}

/// The first number of `term` (after folding) that is not finite.
fn non_finite_constant(term: &Term) -> Option<f64> {
    match term {
        Term::Number(v) => (!v.is_finite()).then_some(*v),
        Term::Time | Term::Parameter(_) => None,
        Term::Neg(a) | Term::Sqrt(a) => non_finite_constant(a),
        Term::Binary(_, a, b) => non_finite_constant(a).or_else(|| non_finite_constant(b)),
        Term::Call(_, args) => args.iter().find_map(non_finite_constant),
    }
}

fn evaluate(term: &Term, t: f64, values: &[(String, f64)]) -> f64 {
    let of = |a: &Term| evaluate(a, t, values);
    match term {
        Term::Number(v) => *v,
        Term::Time => t,
        Term::Parameter(name) => values
            .iter()
            .rev()
            .find(|(n, _)| n == name)
            .map_or(f64::NAN, |(_, v)| *v),
        Term::Neg(a) => -of(a),
        Term::Binary(op, a, b) => binary(*op, of(a), of(b)),
        Term::Call(f, args) => f.apply(&args.iter().map(of).collect::<Vec<f64>>()),
        Term::Sqrt(a) => of(a).sqrt(),
    }
}

/// What a phase takes from the run at its change: its own values set by expressions, and
/// the values it carries over from such sets of the phases before.
#[derive(Clone, Debug)]
pub struct Timed {
    /// Every parameter value of the phase's program (defaults included) as built, before
    /// the run: those set by an expression hold a stand-in until the change.
    pub values: Vec<(String, f64)>,
    /// The phase's own sets by expression.
    pub sets: Vec<(String, SetExpression)>,
    /// The parameters whose value comes from an expression of an earlier phase.
    pub carried: Vec<String>,
}

/// The values a phase set at its change (the scene's phase index, from 0), when, and
/// every value of its program then.
#[derive(Clone, Debug, PartialEq)]
pub struct SetAt {
    /// The phase (in the scene's numbering from 0).
    pub phase: usize,
    /// The time of the change.
    pub time: f64,
    /// The values its expressions gave.
    pub set: Vec<(String, f64)>,
    /// Every parameter value of its program from the change on.
    pub values: Vec<(String, f64)>,
}

impl Timed {
    /// The phase's values at a change at `t`: the carried ones from `latest` (the values
    /// set by expressions so far, later ones last), then its own expressions evaluated on
    /// those (each reads the values before this change's expressions), `latest` updated.
    /// A value that is not finite is the message `Err`.
    fn at(&self, t: f64, latest: &mut Vec<(String, f64)>) -> Result<SetAt, String> {
        let mut values = self.values.clone();
        for (name, value) in &mut values {
            let carried = self.carried.contains(name);
            if let Some((_, v)) = latest.iter().rev().find(|(n, _)| carried && n == name) {
                *value = *v;
            }
        }
        let mut set = Vec::new();
        for (name, expression) in &self.sets {
            let value = expression.value(t, &values);
            if !value.is_finite() {
                return Err(format!(
                    "`{name} = \"{}\"` is {value} at the change (t = {}): a parameter's value \
                     must be a finite number",
                    expression.text,
                    shown(t)
                ));
            }
            set.push((name.clone(), value));
        }
        for (name, value) in &set {
            values.retain(|(n, _)| n != name);
            values.push((name.clone(), *value));
            latest.push((name.clone(), *value));
        }
        Ok(SetAt {
            phase: 0,
            time: t,
            set,
            values,
        })
    }
}

/// The runs of [`run`]: the phases' solution, the run's failure, a value refused at a
/// change (the run ends there), and the values each change set.
pub struct Ran<const N: usize, const S: usize> {
    pub phased: PhasedSolution<N, S>,
    pub error: Option<StepError<S>>,
    pub refused: Option<CliError>,
    pub sets: Vec<SetAt>,
}

/// Runs `phases` (`timed` and `watches`, the programs watching their end conditions,
/// aligned with them): `segment(phases, range, before)` runs the phases of `range`, from
/// the start (`before` `None`) or continued from the phases run `before`; a phase with
/// values set at its change begins a range, its values given to its programs first.
/// `offset` is the index of the scene's first phase in `phases` (1 behind a held phase).
pub fn run<'a, Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phases: &mut [Phase<'a, Sys, S>],
    timed: &[Option<Timed>],
    watches: &[Option<&RefCell<Program>>],
    offset: usize,
    mut segment: impl FnMut(
        &[Phase<'a, Sys, S>],
        Range<usize>,
        Option<PhasedSolution<N, S>>,
    ) -> (PhasedSolution<N, S>, Option<StepError<S>>),
) -> Ran<N, S> {
    let mut starts: Vec<usize> = (1..phases.len())
        .filter(|&j| timed.get(j).is_some_and(Option::is_some))
        .collect();
    starts.push(phases.len());
    let (mut phased, mut error) = segment(phases, 0..starts[0], None);
    let (mut latest, mut sets) = (Vec::new(), Vec::new());
    for range in starts.windows(2) {
        let j = range[0];
        let reached = error.is_none()
            && phased.solution.stop == (StopReason::EventFound { index: 0 })
            && phased.phase.last() == Some(&(j - 1));
        let (Some((time, _)), Some(Some(timed)), true) =
            (phased.solution.last(), timed.get(j), reached)
        else {
            break;
        };
        let entered = timed
            .at(time, &mut latest)
            .and_then(|set| give(&mut phases[j], watches.get(j).copied().flatten(), set));
        match entered {
            Ok(mut set) => {
                set.phase = j - offset;
                sets.push(set);
            }
            Err(message) => {
                phased.solution.stop = StopReason::Failed;
                let refused = CliError::Run(format!(
                    "phase {}: {message}\nhelp: write a value set at the change that is finite \
                     there (docs/scenes.md#a-value-set-at-the-change)",
                    j - offset + 1
                ));
                return Ran {
                    phased,
                    error: None,
                    refused: Some(refused),
                    sets,
                };
            }
        }
        (phased, error) = segment(phases, j..range[1], Some(phased));
    }
    Ran {
        phased,
        error,
        refused: None,
        sets,
    }
}

/// Gives `set`'s values to the phase's program and to the program watching its end.
fn give<Sys: SceneSystem<N, S>, const N: usize, const S: usize>(
    phase: &mut Phase<'_, Sys, S>,
    watch: Option<&RefCell<Program>>,
    set: SetAt,
) -> Result<SetAt, String> {
    let values: Vec<(&str, f64)> = set.values.iter().map(|(n, v)| (n.as_str(), *v)).collect();
    let Some(program) = phase.system.system.program_mut() else {
        return Err("a value set at a change has no sensitivities yet".to_string());
    };
    program.set_parameters(&values).map_err(|e| e.to_string())?;
    if let Some(watch) = watch {
        watch
            .borrow_mut()
            .set_parameters(&values)
            .map_err(|e| e.to_string())?;
    }
    Ok(set)
}
