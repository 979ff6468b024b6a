//! `varmass derive FILE [--latex]`: the whole derivation as text or LaTeX.

use crate::args::ModelArgs;
use crate::error::CliError;
use crate::model::load;

/// The derivation of the model as text, or LaTeX with `latex`.
pub fn derive(args: &ModelArgs, latex: bool) -> Result<String, CliError> {
    let mut model = load(args)?;
    // The only holder of it: made mutable in place, not copied.
    let derivation = std::sync::Arc::make_mut(&mut model.derivation);
    Ok(if latex {
        derivation.to_latex()
    } else {
        derivation.to_text()
    })
}
