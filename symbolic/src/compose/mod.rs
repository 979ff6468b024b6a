//! Components (docs/components.md): a model file that uses other model files.
//!
//! `use "lib/thruster.vms" as left: F = 2*F0, on = rocket` is expanded here, after parsing
//! and before the derivation, into the component's statements: every name the component
//! declares is qualified by the instance's name (`left_F`), every name it reads and does
//! not declare is bound at the use site (to a name of the using model where the component
//! acts on it, else by a `let left_F = …` whose unit the component's `units` checks), and
//! the statements are spliced where the `use` was. Everything downstream (the frozen-mass
//! derivation, units, tags, checks, `emit`, the derivation text) sees one composed model.
//!
//! A component's spans are moved past the using text, one region per file read, so that a
//! diagnostic about a component's statement is traced back by [`Composition::locate`] to
//! the use site that brought it in, naming the component's file, line and column.

mod expand;
mod instance;
mod walk;

pub use expand::{MAX_COMPONENTS, MAX_COMPONENT_DEPTH};

use crate::parse::ast::{StatementKind, SystemAst};
use crate::parse::{Diagnostic, Span, Spanned};
use std::path::{Path, PathBuf};

/// A composed model: its statements, every `use` expanded, and where the statements of
/// its components came from.
#[derive(Clone, Debug, Default)]
pub struct Composition {
    /// The composed statements (those of components with spans in their regions).
    pub ast: SystemAst,
    /// The component files read, in order.
    regions: Vec<Region>,
}

/// One component file read: its text sits at byte offsets `start..start + text.len()`.
#[derive(Clone, Debug)]
struct Region {
    start: usize,
    text: String,
    /// The path as diagnostics show it (relative to the model's directory).
    shown: String,
    /// The path read.
    path: PathBuf,
    /// The `use` statement that read it (a span of the using text, or of its region).
    use_span: Span,
    /// The instance's name at that use.
    instance: String,
}

/// Expands every `use` of `ast`, the parsed text `source` of the model file `file` (a
/// component's path is relative to the directory of the file that uses it; an inline
/// system gives a path in the crate's directory). A problem of a use is a diagnostic at
/// the use site; a problem inside a component names its file and line.
///
/// ```
/// use varmass_symbolic::{compose::compose, parse::parse_system};
/// let source = "coordinates x\nparameter k = 2\npotential k*x^2/2\nkinetic x'^2/2";
/// let composed = compose(source, parse_system(source).unwrap(), "m.vms".as_ref()).unwrap();
/// assert_eq!(composed.defaults(), vec![("k".to_string(), 2.0)]);
/// ```
pub fn compose(source: &str, ast: SystemAst, file: &Path) -> Result<Composition, Vec<Diagnostic>> {
    let mut expander = expand::Expander::new(file, source.len());
    let statements = expander.statements(ast.statements, Path::new(""));
    let composition = Composition {
        ast: SystemAst { statements },
        regions: expander.regions,
    };
    let mut errors = expander.errors;
    errors.extend(parameters_declared_twice(&composition.ast));
    if errors.is_empty() {
        Ok(composition)
    } else {
        Err(composition.locate(errors))
    }
}

impl Composition {
    /// Each diagnostic whose span lies in a component moved to the use site that brought
    /// the component in: "in component `left` (lib/thruster.vms:3:7): …", the component's
    /// line and caret in the help. Nested components give one such prefix per level.
    pub fn locate(&self, diagnostics: Vec<Diagnostic>) -> Vec<Diagnostic> {
        diagnostics
            .into_iter()
            .map(|d| self.locate_one(d))
            .collect()
    }

    fn locate_one(&self, mut diagnostic: Diagnostic) -> Diagnostic {
        // Each step moves to a use site at a smaller offset: at most one step a region.
        for _ in 0..=self.regions.len() {
            let at = diagnostic.span.start;
            let Some(region) = self.regions.iter().rev().find(|r| r.start <= at) else {
                return diagnostic;
            };
            let local = Span::from_range(
                &region.text,
                at - region.start,
                diagnostic.span.end.saturating_sub(region.start),
            );
            let message = diagnostic.message.clone();
            let inside = Diagnostic {
                span: local,
                ..diagnostic
            };
            let rendered = inside.render_in_file(&region.text, &region.shown);
            let body: Vec<&str> = rendered.lines().skip(1).collect();
            diagnostic = Diagnostic::new(
                region.use_span,
                format!(
                    "in component `{}` ({}:{}:{}): {message}",
                    region.instance, region.shown, local.line, local.column
                ),
            )
            .with_help(body.join("\n"));
        }
        diagnostic
    }

    /// The component files read (the paths opened), for a build to track.
    pub fn files(&self) -> impl Iterator<Item = &Path> {
        self.regions.iter().map(|r| r.path.as_path())
    }

    /// Each `parameter` with its default value, in statement order.
    pub fn defaults(&self) -> Vec<(String, f64)> {
        defaults(&self.ast)
    }
}

/// Each `parameter` of `ast` with its default value, in statement order.
pub fn defaults(ast: &SystemAst) -> Vec<(String, f64)> {
    ast.statements
        .iter()
        .filter_map(|s| match &s.kind {
            StatementKind::Parameter(p) => Some((p.name.node.clone(), p.value)),
            _ => None,
        })
        .collect()
}

/// A `parameter` whose name is declared again (by another `parameter` or any
/// declaration): the derivation knows no `parameter`, so it is checked here.
fn parameters_declared_twice(ast: &SystemAst) -> Vec<Diagnostic> {
    struct Declared(Vec<Spanned<String>>);
    impl walk::Visit for Declared {
        fn name(&mut self, name: &mut String, span: Span, role: walk::Role) {
            if role == walk::Role::Declared {
                self.0.push(Spanned::new(name.clone(), span));
            }
        }
    }
    let mut declared = Declared(Vec::new());
    let mut statements = ast.statements.clone();
    statements
        .iter_mut()
        .for_each(|s| walk::statement(s, &mut declared));
    let mut errors = Vec::new();
    for s in &ast.statements {
        let StatementKind::Parameter(p) = &s.kind else {
            continue;
        };
        let first = declared.0.iter().find(|d| d.node == p.name.node);
        if let Some(first) = first.filter(|d| d.span != p.name.span) {
            errors.push(
                Diagnostic::new(p.name.span, format!("`{}` is declared twice", p.name.node))
                    .with_help(format!(
                        "first declared at {}:{}",
                        first.span.line, first.span.column
                    )),
            );
        }
    }
    errors
}
