//! Inputs in the expression engine (docs/inputs.md#in-the-derivation): the pool keeps each
//! `input` of the model by name with its declared arguments, and a call is an opaque
//! [`Func::Input`] node. Differentiation is the chain rule over the arguments,
//! ∂/∂s u(a₁…a_k) = Σⱼ ∂ⱼu(a) · ∂aⱼ/∂s, with ∂ⱼu the node `Input { partial: j }` (computed
//! in generated code from the user's `u_partials`); a partial is not differentiated again
//! (`diff.rs` gives NaN, and the derivation refuses it with a diagnostic:
//! `mechanics/inputs.rs`).
//!
//! An input may instead be given a *law*, an expression of its declared arguments and the
//! parameters (`varmass run --input 'u=kp*(10 - y) - kd*y''`): lowering then replaces each
//! call by the law with the arguments substituted ([`substitute_arguments`]), before any
//! derivative is taken, so the equations, the Jacobian and the Taylor recurrences see an
//! ordinary expression and no [`Func::Input`] node.

use super::func::Func;
use super::node::Id;
use super::pool::ExprPool;
use super::symbol::Symbol;
use crate::parse::ast::{Expr, ExprNode};
use crate::parse::Span;

/// One input of the pool: its name in the model and its arguments as declared (`y'` for a
/// velocity).
#[derive(Clone, Debug)]
pub(crate) struct PoolInput {
    pub(crate) name: String,
    pub(crate) arguments: Vec<String>,
    /// The expression that replaces each call, if one was given.
    pub(crate) law: Option<ExprNode>,
    /// The held value of a sampled input, the symbol each call lowers to.
    pub(crate) held: Option<Symbol>,
}

impl ExprPool {
    /// Registers the input `name` with its declared `arguments` and returns the index calls
    /// use; `None` past `u16::MAX` inputs.
    pub fn add_input(&mut self, name: &str, arguments: Vec<String>) -> Option<u16> {
        let index = u16::try_from(self.inputs.len()).ok()?;
        self.inputs.push(PoolInput {
            name: name.to_owned(),
            arguments,
            law: None,
            held: None,
        });
        Some(index)
    }

    /// Gives input `input` the law `law`: lowering replaces each of its calls by `law`
    /// with the declared arguments bound to the call's (see the module docs).
    pub fn set_input_law(&mut self, input: u16, law: ExprNode) {
        if let Some(entry) = self.inputs.get_mut(usize::from(input)) {
            entry.law = Some(law);
        }
    }

    /// Makes input `input` sampled: each call lowers to `held`, its held value
    /// (docs/inputs.md#sampled-inputs).
    pub fn set_input_held(&mut self, input: u16, held: Symbol) {
        if let Some(entry) = self.inputs.get_mut(usize::from(input)) {
            entry.held = Some(held);
        }
    }

    /// The held value of input `input` if it is sampled.
    pub fn input_held(&self, input: u16) -> Option<Symbol> {
        self.inputs.get(usize::from(input)).and_then(|i| i.held)
    }

    /// The law of input `input`, if it has one.
    pub fn input_law(&self, input: u16) -> Option<&ExprNode> {
        self.inputs
            .get(usize::from(input))
            .and_then(|i| i.law.as_ref())
    }

    /// The call `u(args)` of input `input` (`partial` 0), or its partial with respect to
    /// argument `partial` (1-based). Never folded, even at constant arguments.
    pub fn input_call(&mut self, input: u16, partial: u8, args: &[Id]) -> Id {
        self.call(Func::Input { input, partial }, args)
    }

    /// The model's name of input `input` (empty if unknown).
    pub fn input_name(&self, input: u16) -> &str {
        self.inputs
            .get(usize::from(input))
            .map_or("", |i| i.name.as_str())
    }

    /// The declared arguments of input `input` (`t`, `y`, `y'`).
    pub fn input_arguments(&self, input: u16) -> &[String] {
        self.inputs
            .get(usize::from(input))
            .map_or(&[], |i| i.arguments.as_slice())
    }

    /// Number of inputs registered.
    pub fn input_count(&self) -> usize {
        self.inputs.len()
    }

    /// How a call of `Input{input, partial}` is written: `u`, then `∂_y u` for a partial
    /// (`∂_y' u` with respect to a velocity).
    pub fn input_call_name(&self, input: u16, partial: u8) -> String {
        let name = self.input_name(input);
        match partial.checked_sub(1) {
            None => name.to_owned(),
            Some(j) => {
                let argument = self
                    .input_arguments(input)
                    .get(usize::from(j))
                    .map_or("?", String::as_str);
                format!("∂_{argument} {name}")
            }
        }
    }
}

/// `law` with each name of `parameters` (`t`, `y`, `y'` as declared) replaced by the
/// argument of the same position in `arguments`, all at once (an argument that names
/// another parameter is not substituted again). Every node of the result that came from
/// `law` is placed at `at` (the call), so that a diagnostic about it points at the call in
/// the model's text, not into the law's own text.
pub(crate) fn substitute_arguments(
    law: &ExprNode,
    parameters: &[String],
    arguments: &[ExprNode],
    at: Span,
) -> ExprNode {
    let bound = |written: String| {
        parameters
            .iter()
            .position(|p| *p == written)
            .and_then(|j| arguments.get(j))
    };
    let node = match law.node.as_ref() {
        Expr::Name(name) => match bound(name.clone()) {
            Some(argument) => return argument.clone(),
            None => Expr::Name(name.clone()),
        },
        Expr::Derivative { name, order } => {
            match bound(format!("{name}{}", "'".repeat(usize::from(*order)))) {
                Some(argument) => return argument.clone(),
                None => Expr::Derivative {
                    name: name.clone(),
                    order: *order,
                },
            }
        }
        Expr::Number(text) => Expr::Number(text.clone()),
        Expr::Neg(inner) => Expr::Neg(substitute_arguments(inner, parameters, arguments, at)),
        Expr::Binary { op, lhs, rhs } => Expr::Binary {
            op: *op,
            lhs: substitute_arguments(lhs, parameters, arguments, at),
            rhs: substitute_arguments(rhs, parameters, arguments, at),
        },
        Expr::Call { func, args } => Expr::Call {
            func: crate::parse::Spanned::new(func.node.clone(), at),
            args: args
                .iter()
                .map(|a| substitute_arguments(a, parameters, arguments, at))
                .collect(),
        },
    };
    crate::parse::Spanned::new(Box::new(node), at)
}
