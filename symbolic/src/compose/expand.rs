//! The expansion of `use` statements (docs/components.md#expansion): each component file
//! read relative to the file that uses it, parsed, its own uses expanded first, then made
//! an instance (`instance.rs`) and spliced where the `use` was. Each file read gets a
//! [`Region`] of byte offsets past the using text, where its spans are moved, so that a
//! diagnostic about it can be traced back ([`super::Composition::locate`]).

use super::instance::instantiate;
use super::walk::{self, Shift};
use super::Region;
use crate::parse::ast::{Statement, StatementKind, UseDecl};
use crate::parse::{parse_system, Diagnostic, Spanned};
use std::path::{Path, PathBuf};

/// Deepest chain of components using components.
pub const MAX_COMPONENT_DEPTH: usize = 16;

/// Most component files read for one model (a chain of components each using the next
/// twice would otherwise read 2^depth files).
pub const MAX_COMPONENTS: usize = 256;

/// The state of one expansion.
pub(super) struct Expander<'a> {
    /// The directory of the model being composed: every path is relative to it.
    base: &'a Path,
    /// The files read, in order.
    pub regions: Vec<Region>,
    /// The problems found, spans anywhere (located by the caller).
    pub errors: Vec<Diagnostic>,
    /// The files being expanded, outermost first (canonical paths): a file on it used
    /// again is a circular use.
    stack: Vec<PathBuf>,
    /// The first free virtual offset.
    next: usize,
}

impl<'a> Expander<'a> {
    /// An expansion of the model `file` (its text `length` bytes long).
    pub fn new(file: &'a Path, length: usize) -> Self {
        Expander {
            base: file.parent().unwrap_or(Path::new("")),
            regions: Vec::new(),
            errors: Vec::new(),
            stack: vec![canonical(file)],
            next: length + 1,
        }
    }

    /// `statements` with each `use` replaced by its instance's statements; `directory` is
    /// the using file's, relative to the base.
    pub fn statements(&mut self, statements: Vec<Statement>, directory: &Path) -> Vec<Statement> {
        let mut out = Vec::with_capacity(statements.len());
        let mut instances: Vec<Spanned<String>> = Vec::new();
        for statement in statements {
            let StatementKind::Use(decl) = &statement.kind else {
                out.push(statement);
                continue;
            };
            if let Some(first) = instances.iter().find(|i| i.node == decl.instance.node) {
                self.errors.push(two_instances(decl, first));
                continue;
            }
            instances.push(decl.instance.clone());
            if let Some(spliced) = self.component(decl, &statement, directory) {
                out.extend(spliced);
            }
        }
        out
    }

    /// The statements of one use, or `None` after recording why not.
    fn component(
        &mut self,
        decl: &UseDecl,
        statement: &Statement,
        directory: &Path,
    ) -> Option<Vec<Statement>> {
        let relative = directory.join(&decl.file.node);
        let shown = relative.display().to_string();
        let path = self.base.join(&relative);
        if let Some(error) = self.refused(decl, &path) {
            self.errors.push(error);
            return None;
        }
        let text = match std::fs::read_to_string(&path) {
            Ok(text) => text,
            Err(error) => {
                let message = format!("cannot read the component `{shown}`: {error}");
                let help = "a component's path is relative to the file that uses it";
                self.errors
                    .push(Diagnostic::new(decl.file.span, message).with_help(help));
                return None;
            }
        };
        let start = self.next;
        self.next = start.saturating_add(text.len() + 1);
        let parsed = parse_system(&text);
        self.regions.push(Region {
            start,
            text,
            shown: shown.clone(),
            path: path.clone(),
            use_span: statement.span,
            instance: decl.instance.node.clone(),
        });
        let mut statements = match parsed {
            Ok(ast) => ast.statements,
            Err(errors) => {
                self.errors.extend(errors.into_iter().map(|mut d| {
                    Shift(start).span_of(&mut d);
                    d
                }));
                return None;
            }
        };
        let inner = relative.parent().unwrap_or(Path::new("")).to_path_buf();
        for statement in &mut statements {
            walk::statement(statement, &mut Shift(start));
            relocate_table(statement, &inner);
        }
        self.stack.push(canonical(&path));
        let statements = self.statements(statements, &inner);
        self.stack.pop();
        instantiate(decl, &statement.tags, statements, &shown)
            .map_err(|errors| self.errors.extend(errors))
            .ok()
    }

    /// Why the component at `path` is not read: a circular use, or past the limits.
    fn refused(&self, decl: &UseDecl, path: &Path) -> Option<Diagnostic> {
        let file = &decl.file.node;
        let here = canonical(path);
        if let Some(at) = self.stack.iter().position(|p| *p == here) {
            let chain: Vec<String> = self.stack[at..]
                .iter()
                .chain([&here])
                .map(|p| format!("`{}`", p.display()))
                .collect();
            return Some(
                Diagnostic::new(decl.file.span, format!("circular use of `{file}`"))
                    .with_help(format!("the uses go round: {}", chain.join(" uses "))),
            );
        }
        if self.stack.len() > MAX_COMPONENT_DEPTH {
            let message =
                format!("components nested deeper than {MAX_COMPONENT_DEPTH} (at `{file}`)");
            return Some(Diagnostic::new(decl.file.span, message));
        }
        if self.regions.len() >= MAX_COMPONENTS {
            let message = format!("more than {MAX_COMPONENTS} component files read (at `{file}`)");
            return Some(Diagnostic::new(decl.file.span, message));
        }
        None
    }
}

impl Shift {
    /// A diagnostic's span moved.
    fn span_of(&mut self, diagnostic: &mut Diagnostic) {
        walk::Visit::span(self, &mut diagnostic.span);
    }
}

/// A table file named in a component is read relative to the component's file: its path
/// becomes relative to the model's directory.
fn relocate_table(statement: &mut Statement, directory: &Path) {
    if let StatementKind::Table(table) = &mut statement.kind {
        if !table.runtime {
            let path = directory.join(&table.file.node);
            table.file.node = path.to_string_lossy().into_owned();
        }
    }
}

/// Two uses with one instance name.
fn two_instances(decl: &UseDecl, first: &Spanned<String>) -> Diagnostic {
    let name = &decl.instance.node;
    Diagnostic::new(
        decl.instance.span,
        format!("two instances named `{name}`: each use of a component needs its own name"),
    )
    .with_help(format!(
        "the first `{name}` is at {}:{}",
        first.span.line, first.span.column
    ))
}

/// The path with links and `..` resolved when the file exists (so that one file reached by
/// two spellings is seen as one), else as given.
fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}
