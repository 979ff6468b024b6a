//! Reading a model file, selecting its tagged effects (`--with`) and deriving it, with
//! diagnostics rendered by the symbolic crate's own renderer (`error: …`,
//! `--> FILE:line:column`, the line and a caret, as the macro shows them too).

use std::path::Path;

use varmass::symbolic::mechanics::{derive, Derivation, Parameters};
use varmass::symbolic::parse::ast::StatementKind;
use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::Diagnostic;

use crate::args::ModelArgs;
use crate::error::CliError;

/// A model file's derivation.
pub struct LoadedModel {
    /// The derivation (parameters inferred: every free name is one).
    pub derivation: Derivation,
    /// The text of each selected `check` statement as written, in order (as
    /// `derivation.checks`).
    pub check_texts: Vec<String>,
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
    load_source(&source, path, &args.with)
}

/// Derives the model text `source` (diagnostics name it `path`, which need not exist) with
/// the statements `with` selects: [`load`] without reading a file, for callers that hold the
/// text (the Python package's `Model(text)`).
pub fn load_source(source: &str, path: &Path, with: &[String]) -> Result<LoadedModel, CliError> {
    let failed = |diagnostics: Vec<Diagnostic>| CliError::Model {
        rendered: render(&diagnostics, source, path),
        count: diagnostics.len(),
    };
    let ast = parse_system(source).map_err(failed)?;
    let ast = select_tags(&ast, with).map_err(|unknown| {
        let messages: Vec<String> = unknown.iter().map(|u| format!("--with: {u}")).collect();
        CliError::Input(messages.join("\n"))
    })?;
    let derivation = derive(&ast, Parameters::Inferred).map_err(failed)?;
    let check_texts = ast
        .statements
        .iter()
        .filter(|s| matches!(s.kind, StatementKind::Check { .. }))
        .map(|s| {
            source
                .get(s.span.start..s.span.end)
                .unwrap_or("")
                .trim()
                .to_string()
        })
        .collect();
    Ok(LoadedModel {
        derivation,
        check_texts,
    })
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
