//! `varmass derive FILE [--latex]`: the whole derivation as text or LaTeX.

use crate::args::ModelArgs;
use crate::error::CliError;
use crate::model::load;

/// The derivation of the model as text, or LaTeX with `latex`.
pub fn derive(args: &ModelArgs, latex: bool) -> Result<String, CliError> {
    let mut model = load(args)?;
    Ok(if latex {
        model.derivation.to_latex()
    } else {
        model.derivation.to_text()
    })
}
