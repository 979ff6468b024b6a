//! Reading a model file and deriving it, with diagnostics rendered rustc-style by
//! `annotate-snippets` (`error: …`, `--> FILE:line:column`, the line and a caret).

use std::path::Path;

use annotate_snippets::{Level, Renderer, Snippet};
use varmass::symbolic::mechanics::{derive, Derivation, Parameters};
use varmass::symbolic::parse::ast::StatementKind;
use varmass::symbolic::parse::parse_system;
use varmass::symbolic::Diagnostic;

use crate::error::CliError;

/// A model file's text and its derivation.
pub struct LoadedModel {
    /// The derivation (parameters inferred: every free name is one).
    pub derivation: Derivation,
    /// The text of each `check` statement as written, in order (as `derivation.checks`).
    pub check_texts: Vec<String>,
}

/// Reads and derives `path`; every problem is a [`CliError::Model`] with its diagnostics.
pub fn load(path: &Path) -> Result<LoadedModel, CliError> {
    let source = std::fs::read_to_string(path).map_err(|source| CliError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let failed = |diagnostics: Vec<Diagnostic>| CliError::Model {
        rendered: render(&diagnostics, &source, &path.display().to_string()),
        count: diagnostics.len(),
    };
    let ast = parse_system(&source).map_err(failed)?;
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
pub fn render(diagnostics: &[Diagnostic], source: &str, file: &str) -> String {
    let renderer = if std::io::IsTerminal::is_terminal(&std::io::stderr()) {
        Renderer::styled()
    } else {
        Renderer::plain()
    };
    diagnostics
        .iter()
        .map(|d| render_one(&renderer, d, source, file))
        .collect::<Vec<_>>()
        .join("\n\n")
}

fn render_one(renderer: &Renderer, d: &Diagnostic, source: &str, file: &str) -> String {
    // A span is clamped to the text (and to character boundaries) before it is shown.
    let span = varmass::symbolic::Span::from_range(source, d.span.start, d.span.end);
    let mut message = Level::Error.title(&d.message).snippet(
        Snippet::source(source)
            .line_start(1)
            .origin(file)
            .fold(true)
            .annotation(Level::Error.span(span.start..span.end)),
    );
    if let Some(help) = &d.help {
        message = message.footer(Level::Help.title(help));
    }
    renderer.render(message).to_string()
}
