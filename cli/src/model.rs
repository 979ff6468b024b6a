//! Reading a model file, selecting its tagged effects (`--with`) and deriving it, with
//! diagnostics rendered by the symbolic crate's own renderer (`error: …`,
//! `--> FILE:line:column`, the line and a caret, as the macro shows them too).

use std::path::Path;

use varmass::symbolic::mechanics::{derive, Derivation, Parameters};
use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::Diagnostic;

use crate::args::ModelArgs;
use crate::error::CliError;

/// A model file's derivation.
pub struct LoadedModel {
    /// The derivation (parameters inferred: every free name is one).
    pub derivation: Derivation,
}

/// Reads `args.file`, keeps the statements `args.with` selects and derives them; a problem
/// in the model is a [`CliError::Model`] with its diagnostics, an unknown tag a
/// [`CliError::Input`] naming the model's tags.
pub fn load(args: &ModelArgs) -> Result<LoadedModel, CliError> {
    let path = &args.file;
    let source = std::fs::read_to_string(path).map_err(|source| CliError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let failed = |diagnostics: Vec<Diagnostic>| CliError::Model {
        rendered: render(&diagnostics, &source, path),
        count: diagnostics.len(),
    };
    let ast = parse_system(&source).map_err(failed)?;
    let ast = select_tags(&ast, &args.with).map_err(|unknown| {
        let messages: Vec<String> = unknown.iter().map(|u| format!("--with: {u}")).collect();
        CliError::Input(messages.join("\n"))
    })?;
    let derivation = derive(&ast, Parameters::Inferred).map_err(failed)?;
    Ok(LoadedModel { derivation })
}

/// Every diagnostic, rustc-style, one after another.
fn render(diagnostics: &[Diagnostic], source: &str, path: &Path) -> String {
    let file = path.display().to_string();
    diagnostics
        .iter()
        .map(|d| d.render_in_file(source, &file))
        .collect::<Vec<_>>()
        .join("\n\n")
}
