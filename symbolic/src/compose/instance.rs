//! One instance of a component (docs/components.md#expansion): what the component's
//! statements declare and read, the use site's bindings checked against them, and the
//! statements renamed under the instance's prefix with a `let` for each bound value.

use super::walk::{self, Role, Visit};
use crate::parse::ast::{Expr, Statement, StatementKind, UseBinding, UseDecl};
use crate::parse::keywords::{closest, LET};
use crate::parse::{Diagnostic, Span, Spanned};
use crate::quantity::is_reserved;
use rustc_hash::{FxHashMap, FxHashSet};

/// A name the component reads but does not declare: bound at the use site.
struct Free {
    /// Where it is first read (a span in the component's region; line and column the
    /// component file's).
    span: Span,
    /// Read where a name must stay a name (a load's target, a flow's body, a body's mass)
    /// or with primes: bound to a name of the using model, not to an expression.
    port: bool,
}

/// What a component's statements declare and read.
#[derive(Default)]
struct Names {
    declared: FxHashSet<String>,
    free: Vec<(String, Free)>,
}

impl Visit for Names {
    fn name(&mut self, name: &mut String, span: Span, role: Role) {
        match role {
            Role::Declared => {
                self.declared.insert(name.clone());
            }
            Role::Called | Role::Unit => {}
            Role::Read | Role::Primed | Role::Target => {
                let port = role != Role::Read;
                match self.free.iter_mut().find(|(n, _)| n == name) {
                    Some((_, free)) => free.port |= port,
                    None => self.free.push((name.clone(), Free { span, port })),
                }
            }
        }
    }
}

/// Renames names by a map; a reserved name (`p_x`, `mdot_m`) is renamed after its prefix,
/// and a unit given to a name the component never reads is the instance's (`left_k`).
struct Rename<'m> {
    map: &'m FxHashMap<String, String>,
    instance: &'m str,
}

impl Visit for Rename<'_> {
    fn name(&mut self, name: &mut String, _span: Span, role: Role) {
        if let Some(new) = self.map.get(name.as_str()) {
            *name = new.clone();
        } else if role == Role::Unit {
            *name = format!("{}_{name}", self.instance);
        } else if let Some((prefix, rest)) = name.split_once('_') {
            if let Some(new) = self.map.get(rest).filter(|_| is_reserved(name)) {
                *name = format!("{prefix}_{new}");
            }
        }
    }
}

/// The use site's bindings applied: the renaming of every name of the component, the
/// `let`s of bound values, the ports and the names bound.
#[derive(Default)]
struct Bindings {
    map: FxHashMap<String, String>,
    definitions: Vec<Statement>,
    ports: FxHashSet<String>,
    bound: FxHashSet<String>,
}

/// The statements of one use of a component, whose own uses are already expanded
/// (`statements`, spans in its region): bound, renamed under the instance's name and
/// tagged with the `use` statement's `tags`; or every problem of the use site.
pub(super) fn instantiate(
    decl: &UseDecl,
    tags: &[Spanned<String>],
    mut statements: Vec<Statement>,
    shown: &str,
) -> Result<Vec<Statement>, Vec<Diagnostic>> {
    let mut names = Names::default();
    for statement in &mut statements {
        walk::statement(statement, &mut names);
    }
    names
        .free
        .retain(|(name, _)| !names.declared.contains(name) && !is_reserved(name));
    let parameters: FxHashSet<String> = statements
        .iter()
        .filter_map(|s| match &s.kind {
            StatementKind::Parameter(p) => Some(p.name.node.clone()),
            _ => None,
        })
        .collect();
    let mut errors = check_instance_name(decl);
    let bindings = bind(decl, (&names, &parameters), tags, shown, &mut errors);
    if !errors.is_empty() {
        return Err(errors);
    }
    statements.retain_mut(|s| keep(s, &bindings.bound, &bindings.ports));
    let instance = &decl.instance.node;
    for statement in &mut statements {
        let mut rename = Rename {
            map: &bindings.map,
            instance,
        };
        walk::statement(statement, &mut rename);
        let mut all = tags.to_vec();
        all.extend(
            statement
                .tags
                .drain(..)
                .filter(|t| !tags.iter().any(|u| u.node == t.node)),
        );
        statement.tags = all;
    }
    let mut spliced = bindings.definitions;
    spliced.extend(statements);
    Ok(spliced)
}

/// Every binding of `decl` checked against what the component reads (`names`) and its
/// `parameters`, each problem in `errors`, and every read name left unbound an error too.
fn bind(
    decl: &UseDecl,
    (names, parameters): (&Names, &FxHashSet<String>),
    tags: &[Spanned<String>],
    shown: &str,
    errors: &mut Vec<Diagnostic>,
) -> Bindings {
    let instance = &decl.instance.node;
    // Called names that are not declared are built-in functions (or unknown, which the
    // derivation reports inside the component): left as they are.
    let map = names
        .declared
        .iter()
        .map(|n| (n.clone(), format!("{instance}_{n}")));
    let mut out = Bindings {
        map: map.collect(),
        ..Bindings::default()
    };
    for binding in &decl.bindings {
        let name = &binding.name.node;
        if !out.bound.insert(name.clone()) {
            let message = format!("`{name}` is bound twice for `{instance}`");
            errors.push(Diagnostic::new(binding.name.span, message));
            continue;
        }
        let free = names.free.iter().find(|(n, _)| n == name).map(|(_, f)| f);
        match (free, parameters.contains(name)) {
            (Some(free), _) if free.port => match binding.value.node.as_ref() {
                Expr::Name(target) => {
                    out.map.insert(name.clone(), target.clone());
                    out.ports.insert(name.clone());
                }
                _ => errors.push(port_not_a_name(binding, free, shown)),
            },
            (Some(_), _) | (None, true) => {
                let qualified = format!("{instance}_{name}");
                out.map.insert(name.clone(), qualified.clone());
                out.definitions.push(definition(binding, qualified, tags));
            }
            (None, false) => errors.push(unknown_binding(binding, names, parameters, shown)),
        }
    }
    for (name, free) in &names.free {
        if !out.bound.contains(name) {
            errors.push(missing_binding(decl, name, free, shown));
        }
    }
    out
}

/// Whether a statement of the component stays: a bound `parameter` gives way to its
/// binding, and a port's unit to the unit of the name it is bound to (dropped from
/// `units`).
fn keep(statement: &mut Statement, bound: &FxHashSet<String>, ports: &FxHashSet<String>) -> bool {
    match &mut statement.kind {
        StatementKind::Parameter(p) => !bound.contains(&p.name.node),
        StatementKind::Units(entries) => {
            entries.retain(|e| !ports.contains(&e.name.node));
            !entries.is_empty()
        }
        _ => true,
    }
}

/// `let left_F = <the bound value>`, where the binding is written.
fn definition(binding: &UseBinding, qualified: String, tags: &[Spanned<String>]) -> Statement {
    let span = binding.name.span.join(binding.value.span);
    Statement {
        kind: StatementKind::Let {
            name: Spanned::new(qualified, binding.name.span),
            value: binding.value.clone(),
        },
        span,
        tags: tags.to_vec(),
    }
}

/// An instance name whose qualified names would be reserved (`p` gives `p_x`).
fn check_instance_name(decl: &UseDecl) -> Vec<Diagnostic> {
    let instance = &decl.instance.node;
    if !is_reserved(&format!("{instance}_x")) && !is_reserved(instance) {
        return Vec::new();
    }
    vec![Diagnostic::new(
        decl.instance.span,
        format!("`{instance}` cannot name an instance: the names `{instance}_…` are reserved"),
    )
    .with_help("choose another instance name")]
}

/// A port (what the component acts on) bound to an expression.
fn port_not_a_name(binding: &UseBinding, free: &Free, shown: &str) -> Diagnostic {
    let name = &binding.name.node;
    Diagnostic::new(
        binding.value.span,
        format!(
            "`{name}` is what the component acts on or differentiates ({shown}:{}:{}): bind it \
             to a name of this model (a body, a mass or a coordinate), not an expression",
            free.span.line, free.span.column
        ),
    )
}

/// A binding of a name the component does not read.
fn unknown_binding(
    binding: &UseBinding,
    names: &Names,
    parameters: &FxHashSet<String>,
    shown: &str,
) -> Diagnostic {
    let name = &binding.name.node;
    let mut candidates: Vec<&str> = names.free.iter().map(|(n, _)| n.as_str()).collect();
    candidates.extend(parameters.iter().map(String::as_str));
    candidates.sort_unstable();
    let mut diagnostic = Diagnostic::new(
        binding.name.span,
        format!("the component `{shown}` has no parameter or port `{name}` to bind"),
    );
    diagnostic = match closest(name, &candidates) {
        Some(near) => diagnostic.with_help(format!("did you mean `{near}`?")),
        None if candidates.is_empty() => diagnostic.with_help("it reads no name of its user"),
        None => diagnostic.with_help(format!("it reads `{}`", candidates.join("`, `"))),
    };
    diagnostic
}

/// A name the component reads that the use site leaves unbound.
fn missing_binding(decl: &UseDecl, name: &str, free: &Free, shown: &str) -> Diagnostic {
    let instance = &decl.instance.node;
    Diagnostic::new(
        decl.instance.span,
        format!(
            "`{instance}` does not bind `{name}`, which the component `{shown}` reads at {}:{}",
            free.span.line, free.span.column
        ),
    )
    .with_help(format!(
        "bind it at the use (`{instance}: {name} = …`), or give it a default in the component \
         (`parameter {name} = …`; an expression of its own names is a `{LET}`)"
    ))
}
