//! Reading a model file, selecting its tagged effects (`--with`) and deriving it, with
//! diagnostics rendered by the symbolic crate's own renderer (`error: …`,
//! `--> FILE:line:column`, the line and a caret, as the macro shows them too).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use varmass::symbolic::compose::{compose, Composition};
use varmass::symbolic::parse::ast::{ExprNode, StatementKind, SystemAst};
use varmass::symbolic::parse::{parse_system, select_tags};
use varmass::symbolic::Diagnostic;
use varmass::symbolic::{
    derive_in, derive_with_laws,
    mechanics::{Derivation, Outputs, Parameters},
};

use crate::args::ModelArgs;
use crate::error::CliError;

/// A model file's derivation.
#[derive(Clone)]
pub struct LoadedModel {
    /// The directory the model's table files are read from (the model file's).
    pub base: PathBuf,
    /// The derivation (parameters inferred: every free name is one), shared by the copies
    /// of the model (a scene's phases, an ensemble's members): each program that runs it
    /// takes its own copy of it.
    pub derivation: Arc<Derivation>,
    /// The whole model, every tag included: where a parameter of a tag not asked for is
    /// found.
    pub ast: SystemAst,
    /// The tags asked for.
    pub with: Vec<String>,
    /// The statements selected by the tags (what was derived).
    pub selected: SystemAst,
    /// Warnings to print before the command's output (see [`crate::lint`]).
    pub warnings: Vec<String>,
    /// The model's text and the name diagnostics give it, to render those of a
    /// re-derivation ([`LoadedModel::with_laws`]).
    source: (String, PathBuf),
    /// Where the statements of its components came from (docs/components.md), to locate
    /// their diagnostics at the use sites.
    composition: Composition,
    /// What was derived: [`Outputs::FULL`], with the parameter Jacobian for a run with
    /// sensitivities ([`LoadedModel::with_sensitivities`]).
    outputs: Outputs,
}

/// The tag, among those not asked for (`with`), whose statements make `name` a parameter
/// of `ast`: for "`g` is a parameter of `[gravity]`; add `--with gravity`". Each tag is
/// tried alone with the ones asked for; only called on the error path, so the extra
/// derivations cost nothing in a good run.
pub fn tag_with_parameter(
    ast: &SystemAst,
    with: &[String],
    name: &str,
    base: &Path,
) -> Option<String> {
    {
        varmass::symbolic::parse::known_tags(ast)
            .into_iter()
            .filter(|tag| !with.contains(tag))
            .find(|tag| {
                let mut with = with.to_vec();
                with.push(tag.clone());
                select_tags(ast, &with)
                    .ok()
                    .and_then(|ast| derive_in(&ast, Parameters::Inferred, Outputs::FULL, base).ok())
                    .is_some_and(|d| d.parameters.iter().any(|(n, _)| n == name))
            })
    }
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
    let parsed = parse_system(source).map_err(failed)?;
    let composition = compose(source, parsed, path).map_err(failed)?;
    let full = composition.ast.clone();
    let ast = select_tags(&full, with).map_err(|unknown| {
        let messages: Vec<String> = unknown.iter().map(|u| format!("--with: {u}")).collect();
        CliError::Input(messages.join("\n"))
    })?;
    // Table files are read relative to the model file.
    let base = path.parent().map(PathBuf::from).unwrap_or_default();
    let derivation = derive_in(&ast, Parameters::Inferred, Outputs::FULL, &base)
        .map_err(|diagnostics| failed(composition.locate(diagnostics)))?;
    let warnings = crate::lint::typo_warnings(&derivation, &ast);
    Ok(LoadedModel {
        base,
        derivation: Arc::new(derivation),
        ast: full,
        with: with.to_vec(),
        selected: ast,
        warnings,
        source: (source.to_string(), path.to_path_buf()),
        composition,
        outputs: Outputs::FULL,
    })
}

impl LoadedModel {
    /// The model derived again with a law in place of each of its inputs (`--input`,
    /// [`derive_with_laws`]); a problem the laws bring is a [`CliError::Model`] at the
    /// calls they replace.
    pub fn with_laws(mut self, laws: &[(String, ExprNode)]) -> Result<LoadedModel, CliError> {
        let derived = derive_with_laws(
            &self.selected,
            Parameters::Inferred,
            self.outputs,
            &self.base,
            laws,
        );
        self.derivation = Arc::new(derived.map_err(|diagnostics| self.failed(diagnostics))?);
        Ok(self)
    }
}

impl LoadedModel {
    /// The model derived again with each table of `files` (name, path) read from its path
    /// (`--table`, docs/tables.md#runtime-tables): a `= runtime` table gets its data, a file
    /// table other data, both with the statement's options. Every name must be a table of
    /// the model and every path readable (`run::tables::apply` checks both first).
    pub fn with_tables(mut self, files: &[(String, PathBuf)]) -> Result<LoadedModel, CliError> {
        for ast in [&mut self.ast, &mut self.selected] {
            for statement in &mut ast.statements {
                let StatementKind::Table(decl) = &mut statement.kind else {
                    continue;
                };
                if let Some((_, path)) = files.iter().find(|(name, _)| *name == decl.name.node) {
                    // An absolute path: the derivation joins it to the model's directory.
                    decl.file.node = path.to_string_lossy().into_owned();
                    decl.runtime = false;
                }
            }
        }
        let derived = derive_in(
            &self.selected,
            Parameters::Inferred,
            self.outputs,
            &self.base,
        );
        self.derivation = Arc::new(derived.map_err(|diagnostics| self.failed(diagnostics))?);
        Ok(self)
    }

    /// Whether the model was derived with its parameter Jacobian (forward sensitivities,
    /// docs/sensitivities.md).
    pub fn has_sensitivities(&self) -> bool {
        self.outputs.sensitivities
    }

    /// The model derived again with (`true`) or without its parameter Jacobian: a run with
    /// `--sensitivity` needs it, and a run without is derived as it always was (its
    /// implicit steppers' Jacobian by differences), whatever ran before.
    pub fn with_sensitivities(mut self, sensitivities: bool) -> Result<LoadedModel, CliError> {
        if self.outputs.sensitivities == sensitivities {
            return Ok(self);
        }
        self.outputs.sensitivities = sensitivities;
        let derived = derive_in(
            &self.selected,
            Parameters::Inferred,
            self.outputs,
            &self.base,
        );
        self.derivation = Arc::new(derived.map_err(|diagnostics| self.failed(diagnostics))?);
        Ok(self)
    }
}

impl LoadedModel {
    /// The values of the parameters `values` (`--set`) leaves out that have a default in
    /// the model (`parameter g = 9.81`, docs/components.md#defaults), after `values`.
    pub fn with_defaults(&self, values: &[(String, f64)]) -> Vec<(String, f64)> {
        let mut all = values.to_vec();
        let parameters = &self.derivation.parameters;
        for (name, value) in self.composition.defaults() {
            let known = parameters.iter().any(|(n, _)| *n == name);
            if known && !values.iter().any(|(n, _)| *n == name) {
                all.push((name, value));
            }
        }
        all
    }

    /// A re-derivation's diagnostics as a [`CliError::Model`], those inside components at
    /// their use sites.
    fn failed(&self, diagnostics: Vec<Diagnostic>) -> CliError {
        let diagnostics = self.composition.locate(diagnostics);
        CliError::Model {
            rendered: render(&diagnostics, &self.source.0, &self.source.1),
            count: diagnostics.len(),
        }
    }
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
