//! `--input NAME=EXPRESSION`: a law for each `input` of the model, parsed with the DSL's
//! expression parser; the derivation replaces each call of the input by it, with the
//! input's declared arguments bound to the call's (docs/inputs.md#the-command-line-tool).
//! Every mistake is a [`CliError::Input`] (exit 2): a malformed option, a name that is no
//! input, an expression that does not parse (with its column), a declared input without
//! a law.

use varmass::symbolic::mechanics::ModelInput;
use varmass::symbolic::parse::ast::{Expr, ExprNode};
use varmass::symbolic::parse::parse_expression;

use super::names::resolve;
use crate::args::Words;
use crate::error::CliError;
use crate::model::LoadedModel;

/// `model` with the laws `options` (the `--input` values) in the calls of its inputs,
/// derived again; a model without inputs and no `--input` is returned as it is. The one
/// place the tool's runs ([`super::Compiled`]: `varmass run`, scenes, Python) apply laws;
/// `words` says how the run's user gives a law.
pub fn apply(
    model: LoadedModel,
    options: &[String],
    words: Words,
) -> Result<LoadedModel, CliError> {
    if model.derivation.inputs.is_empty() && options.is_empty() {
        return Ok(model);
    }
    // `--input u=FILE.csv`: a table of u's first argument, and its law (docs/tables.md).
    let (model, options) = super::input_tables::apply(model, options)?;
    let options = options.as_slice();
    let laws = laws(options, &model.derivation.inputs, words)?;
    model.with_laws(&laws)
}

/// The laws `options` (the `--input` values) give, one for each of `declared`, in the
/// order given.
pub fn laws(
    options: &[String],
    declared: &[ModelInput],
    words: Words,
) -> Result<Vec<(String, ExprNode)>, CliError> {
    let known: Vec<(String, usize)> = declared
        .iter()
        .enumerate()
        .map(|(k, input)| (input.name.clone(), k))
        .collect();
    let mut laws: Vec<(String, ExprNode)> = Vec::new();
    for option in options {
        let (name, law) = law(option)?;
        if known.is_empty() {
            return Err(CliError::Input(format!(
                "--input {name}: the model declares no input"
            )));
        }
        resolve(&name, &known, "an input")?;
        if let Some(called) = input_called(&law, &known) {
            return Err(CliError::Input(format!(
                "--input {name}: the law calls input `{called}`; a law is an expression of \
                 the input's arguments and the parameters"
            )));
        }
        if laws.iter().any(|(given, _)| *given == name) {
            return Err(CliError::Input(format!("--input {name} is given twice")));
        }
        laws.push((name, law));
    }
    if let Some(input) = declared
        .iter()
        .find(|input| !laws.iter().any(|(name, _)| *name == input.name))
    {
        let arguments = input.arguments.join(", ");
        return Err(CliError::Input(format!(
            "no law for input `{}`: the model declares `input {}({arguments})`; give \
             {}, an expression of {arguments} and the parameters",
            input.name,
            input.name,
            words.give_input(&input.name)
        )));
    }
    Ok(laws)
}

/// Splits `NAME=EXPRESSION` at its first `=` and parses the expression.
fn law(option: &str) -> Result<(String, ExprNode), CliError> {
    let Some((name, text)) = option.split_once('=') else {
        return Err(CliError::Input(format!(
            "--input `{option}`: expected NAME=EXPRESSION"
        )));
    };
    let name = name.trim().to_string();
    let law = parse_expression(text).map_err(|diagnostic| {
        CliError::Input(format!(
            "--input {name}: {} at column {} of `{text}`",
            diagnostic.message, diagnostic.span.column
        ))
    })?;
    Ok((name, law))
}

/// The first call in `law` of an input of `known` (a law may not call one: the
/// replacement would never end).
fn input_called<'a>(law: &ExprNode, known: &'a [(String, usize)]) -> Option<&'a str> {
    match law.node.as_ref() {
        Expr::Number(_) | Expr::Name(_) | Expr::Derivative { .. } => None,
        Expr::Neg(inner) => input_called(inner, known),
        Expr::Binary { lhs, rhs, .. } => {
            input_called(lhs, known).or_else(|| input_called(rhs, known))
        }
        Expr::Call { func, args } => known
            .iter()
            .find(|(name, _)| *name == func.node)
            .map(|(name, _)| name.as_str())
            .or_else(|| args.iter().find_map(|a| input_called(a, known))),
    }
}
