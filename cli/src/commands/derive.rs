//! `varmass derive FILE [--latex]`: the whole derivation as text or LaTeX.

use std::path::Path;

use crate::error::CliError;
use crate::model::load;

/// The derivation of `file` as text, or LaTeX with `latex`.
pub fn derive(file: &Path, latex: bool) -> Result<String, CliError> {
    let mut model = load(file)?;
    Ok(if latex {
        model.derivation.to_latex()
    } else {
        model.derivation.to_text()
    })
}
