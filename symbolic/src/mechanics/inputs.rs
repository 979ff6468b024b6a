//! `input` statements (docs/inputs.md): each input is registered in the pool under its name
//! with its declared arguments, so that calls lower to `Call(Func::Input { .. })`. Its
//! arguments must be `t`, coordinates or their velocities (a diagnostic at the argument
//! otherwise), and the period of a sampled input a positive number of seconds.
//!
//! The equations never differentiate an input: an input inside a position, a mass law or
//! the Lagrangian would make the derivation differentiate the user's function, and its
//! derivative would only be a finite difference in equations that must be exact. That is a
//! diagnostic at the input's declaration ([`check_not_differentiated`]). Only the Jacobian
//! (which steers the Newton iterations of the implicit steppers, not the solution) uses the
//! partials `u_partials` of the generated trait.

use super::build::Builder;
use super::derivation::Derivation;
use super::resolve::Binding;
use crate::expr::{Func, Id, Node, Symbol, SymbolKind};
use crate::parse::ast::{Expr, ExprNode, InputDecl};
use crate::parse::{keywords, Diagnostic, Span};

/// An input of the model.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelInput {
    /// Its name, called as a function.
    pub name: String,
    /// Its arguments as declared (`t`, `y`, `y'`).
    pub arguments: Vec<String>,
    /// `every h`: the sample period in seconds of a sampled (zero-order-hold) input.
    pub every: Option<f64>,
    /// The symbol of a sampled input's held value, which its calls lower to: constant in
    /// the calculus, read from the state's entry after the state masses.
    pub held: Option<Symbol>,
    /// The law given for a sampled input (`varmass run --input`), an expression of its
    /// declared arguments (t, coordinates, velocities) and the parameters: what the
    /// interpreter's sample evaluates. `None` under the macro (the trait's method serves).
    pub law: Option<Id>,
    /// Its index in the pool ([`crate::expr::ExprPool::input_name`]).
    pub index: u16,
    /// Where the statement names it.
    pub span: Span,
}

impl ModelInput {
    /// The Rust name of argument `j` in the generated trait: `y_dot` for `y'`.
    pub fn rust_argument(&self, j: usize) -> String {
        let argument = self.arguments.get(j).map_or("", String::as_str);
        match argument.strip_suffix('\'') {
            Some(name) => format!("{name}_dot"),
            None => argument.to_owned(),
        }
    }
}

impl Builder {
    /// Binds the name of `decl` (first pass; the arguments are checked by
    /// [`check_input_arguments`](Self::check_input_arguments) once every coordinate is known).
    pub(super) fn declare_input(&mut self, decl: &InputDecl) {
        if !self.check_new_name(&decl.name.node, decl.name.span, "input") {
            return;
        }
        let arguments: Vec<String> = decl
            .arguments
            .iter()
            .map(|(name, primes)| format!("{}{}", name.node, "'".repeat(usize::from(*primes))))
            .collect();
        let every = decl
            .every
            .as_ref()
            .and_then(|period| match period.node.parse::<f64>() {
                // A subnormal period has no exact grid k·T (and no step a run could take).
                Ok(h) if h.is_normal() && h > 0.0 => Some(h),
                parsed => {
                    let why = match parsed {
                        Ok(h) if h > 0.0 && h.is_finite() => {
                            "is below the smallest normal f64 (2.2e-308): no grid k·T of it \
                             can be computed"
                        }
                        _ => "is not a positive number of seconds",
                    };
                    let message = format!("the sample period `{}` {why}", period.node);
                    self.errors.push(Diagnostic::new(period.span, message));
                    None
                }
            });
        let arity = arguments.len();
        let Some(index) = self
            .model
            .pool
            .add_input(&decl.name.node, arguments.clone())
        else {
            self.errors
                .push(Diagnostic::new(decl.name.span, "too many inputs"));
            return;
        };
        self.model
            .names
            .insert(decl.name.node.clone(), Binding::Input(index, arity));
        // A sampled input keeps its held value even with a law: the law is what the sample
        // evaluates (the run-time interpreter's hook), lowered once the model is known.
        if every.is_none() && self.attach_law(decl, index) {
            return;
        }
        // The held value of a sampled input: a constant of the equations between samples,
        // read from the state (docs/inputs.md#sampled-inputs).
        let held = every.map(|_| {
            let symbol =
                (self.model.pool.symbols_mut()).add(&decl.name.node, SymbolKind::Parameter);
            self.model.pool.set_input_held(index, symbol);
            symbol
        });
        self.model.inputs.push(ModelInput {
            name: decl.name.node.clone(),
            arguments,
            every,
            held,
            law: None,
            index,
            span: decl.name.span,
        });
    }

    /// Gives input `decl` (pool index `index`) the law the caller gave for its name, if
    /// any, and says whether it did: its calls are then replaced by the law when lowered,
    /// so it is no input of the derivation. A law that calls an input (itself or another)
    /// would never end: a diagnostic at the declaration.
    fn attach_law(&mut self, decl: &InputDecl, index: u16) -> bool {
        let Some((_, law)) = self.laws.iter().find(|(name, _)| *name == decl.name.node) else {
            return false;
        };
        let law = law.clone();
        if let Some(called) = first_input_called(&law, &self.laws) {
            self.errors.push(
                Diagnostic::new(
                    decl.name.span,
                    format!(
                        "the law given for input `{}` calls input `{called}`",
                        decl.name.node
                    ),
                )
                .with_help("a law is an expression of the input's arguments and the parameters"),
            );
            return true;
        }
        self.model.pool.set_input_law(index, law);
        true
    }

    /// Lowers the law given for each sampled input (its declared arguments are the model's
    /// own t, coordinates and velocities, so the law is lowered as written). A law that calls
    /// an input is refused as for a continuous input.
    pub(super) fn lower_sampled_laws(&mut self) {
        for k in 0..self.model.inputs.len() {
            let input = &self.model.inputs[k];
            if input.every.is_none() {
                continue;
            }
            let Some((_, law)) = self.laws.iter().find(|(name, _)| *name == input.name) else {
                continue;
            };
            let (law, name, span) = (law.clone(), input.name.clone(), input.span);
            if let Some(called) = first_input_called(&law, &self.laws) {
                self.errors.push(Diagnostic::new(
                    span,
                    format!("the law given for input `{name}` calls input `{called}`"),
                ));
                continue;
            }
            let lowered = self.lower(&law);
            self.model.inputs[k].law = lowered;
        }
    }

    /// Every argument of `decl` is `t`, a coordinate or a coordinate's velocity, and
    /// appears once.
    pub(super) fn check_input_arguments(&mut self, decl: &InputDecl) {
        for (k, (name, primes)) in decl.arguments.iter().enumerate() {
            let binding = self.model.names.get(&name.node);
            let fits = matches!(
                (binding, primes),
                (Some(Binding::Time(_)), 0) | (Some(Binding::Coordinate { .. }), 0 | 1)
            );
            if !fits {
                let written = format!("{}{}", name.node, "'".repeat(usize::from(*primes)));
                self.errors.push(
                    Diagnostic::new(
                        name.span,
                        format!(
                            "`{written}` cannot be an argument of input `{}`",
                            decl.name.node
                        ),
                    )
                    .with_help(format!(
                        "an input's arguments are `{}`, coordinates and their velocities (`y'`)",
                        keywords::TIME
                    )),
                );
                continue;
            }
            let repeated = decl.arguments[..k]
                .iter()
                .any(|(other, p)| other.node == name.node && p == primes);
            if repeated {
                self.errors.push(Diagnostic::new(
                    name.span,
                    format!("input `{}` names `{}` twice", decl.name.node, name.node),
                ));
            }
        }
    }
}

/// The first call in `law` of a name that has a law in `laws` (an input: only inputs
/// have laws).
fn first_input_called(law: &ExprNode, laws: &[(String, ExprNode)]) -> Option<String> {
    match law.node.as_ref() {
        Expr::Number(_) | Expr::Name(_) | Expr::Derivative { .. } => None,
        Expr::Neg(inner) => first_input_called(inner, laws),
        Expr::Binary { lhs, rhs, .. } => {
            first_input_called(lhs, laws).or_else(|| first_input_called(rhs, laws))
        }
        Expr::Call { func, args } => {
            if laws.iter().any(|(name, _)| *name == func.node) {
                return Some(func.node.clone());
            }
            args.iter().find_map(|a| first_input_called(a, laws))
        }
    }
}

/// A diagnostic at each sampled input whose held value is in the Lagrangian or a mass law:
/// a sample would make a position, an energy or a mass jump, which the frozen-mass
/// equations between samples do not describe.
fn held_in_energies(d: &Derivation) -> Vec<Diagnostic> {
    let mut roots = vec![d.lagrangian, d.energy];
    roots.extend(d.closed_laws.iter().flatten());
    let free: std::collections::BTreeSet<_> =
        roots.iter().flat_map(|r| d.pool.free_symbols(*r)).collect();
    let sampled = (d.inputs.iter()).filter(|i| i.held.is_some_and(|h| free.contains(&h)));
    sampled
        .map(|input| {
            Diagnostic::new(
                input.span,
                format!(
                    "sampled input `{}` is inside a position, a mass law or an energy: each \
                     sample would make it jump",
                    input.name
                ),
            )
            .with_help("a sampled input may appear in forces, thrusts, impacts, torques, flows and mass rates")
        })
        .collect()
}

/// Every equation of `d` but the Jacobian.
pub(crate) fn equation_roots(d: &Derivation) -> Vec<Id> {
    let mut head = vec![d.lagrangian, d.energy, d.power];
    head.extend(d.hamiltonian);
    d.equation_roots(head, true)
}

/// A diagnostic at the declaration of each input whose partial the equations (not the
/// Jacobian) would need: the derivation differentiated it.
pub(crate) fn check_not_differentiated(d: &Derivation) -> Vec<Diagnostic> {
    if d.inputs.is_empty() {
        return Vec::new();
    }
    let roots = equation_roots(d);
    let roots = roots.as_slice();
    let mut differentiated: Vec<u16> = Vec::new();
    for id in d.pool.reachable(roots, false) {
        if let Node::Call(Func::Input { input, partial }, _) = d.pool.node(id) {
            if *partial > 0 && !differentiated.contains(input) {
                differentiated.push(*input);
            }
        }
    }
    let mut diagnostics = held_in_energies(d);
    for input in &d.inputs {
        if differentiated.contains(&input.index) {
            diagnostics.push(
                Diagnostic::new(
                    input.span,
                    format!(
                        "the derivation would differentiate input `{}`: it is inside a position, a \
                         mass law or an energy",
                        input.name
                    ),
                )
                .with_help(
                    "an input may appear in forces, thrusts, impacts, torques, flows and mass \
                     rates; write a function the equations differentiate as a DSL expression or a table",
                ),
            );
        }
    }
    diagnostics
}
