//! The dimension check of a system with a `units` statement, on the resolved model: what
//! each name is (coordinate, mass, inertia, definition, parameter, table, the time) comes
//! from [`Model`] — this module resolves nothing itself — and each statement's rule is
//! applied to the statement's spanned expressions, because a diagnostic quotes the written
//! term and points at it (the model's arena has no positions). Every problem is reported
//! together.

use super::infer::Dim;
use super::text::text;
use super::unit::unit_dimension;
use crate::dimension::Dimension;
use crate::mechanics::{Binding, Model, UnitTable};
use crate::parse::ast::{
    Attitude, BinOp, Expr, ExprNode, Flow, FlowVelocity, InertiaValue, Load, LoadValue, MassDecl,
    MassLaw, RigidDecl, Statement, StatementKind, SystemAst, UnitDecl, VectorNode,
};
use crate::parse::keywords;
use crate::parse::{Diagnostic, Span};
use crate::quantity::is_reserved;
use rustc_hash::{FxHashMap, FxHashSet};

/// The state of one check.
pub(crate) struct Checker<'m> {
    /// The resolved model: what each name is.
    model: &'m Model,
    table: UnitTable,
    /// `let` definitions without a declared unit: their inferred dimension (`None` when it
    /// could not be inferred, so that their uses stay silent).
    lets: FxHashMap<String, Option<Dim>>,
    /// Names whose unit was given but could not be read (already reported).
    unreadable: FxHashSet<String>,
    /// Whether the expression being checked is in a `check` (derived quantities allowed).
    in_check: bool,
    /// Every name met in an expression.
    used: FxHashSet<String>,
    /// Names without a unit, with their first use.
    missing: Vec<(String, Span)>,
    diagnostics: Vec<Diagnostic>,
    /// Each table's name, with its argument's dimension and where it was first inferred
    /// (`calls.rs`).
    pub(crate) tables: FxHashMap<String, Option<(Dimension, Span)>>,
}

/// Checks the dimensions of every statement of `ast`, resolved into `model`, when it has a
/// `units` statement. Returns `Ok(None)` for a system without one (nothing is checked),
/// the table of units when every rule holds, and otherwise every problem found.
///
/// ```
/// use varmass_symbolic::mechanics::{build_model, Parameters};
/// use varmass_symbolic::parse::parse_system;
/// use varmass_symbolic::units::check_units;
/// let ast = parse_system("coordinates x\nunits x: m, k: N/m\npotential k*x'^2").unwrap();
/// let model = build_model(&ast, Parameters::Inferred).unwrap();
/// let errors = check_units(&ast, &model).unwrap_err();
/// assert_eq!(
///     errors[0].message,
///     "potential term k*x'^2 has kg·m²/s⁴, expected an energy, kg·m²/s²"
/// );
/// ```
pub fn check_units(ast: &SystemAst, model: &Model) -> Result<Option<UnitTable>, Vec<Diagnostic>> {
    let has_units = |s: &Statement| matches!(s.kind, StatementKind::Units(_));
    if !ast.statements.iter().any(has_units) {
        return Ok(None);
    }
    let mut checker = Checker::new(model);
    checker.declare(ast);
    for statement in &ast.statements {
        checker.statement(statement);
    }
    checker.bodies_with_units(ast);
    checker.missing_units();
    let Checker {
        table,
        lets,
        mut diagnostics,
        ..
    } = checker;
    if !diagnostics.is_empty() {
        diagnostics.sort_by_key(|d| d.span.start);
        return Err(diagnostics);
    }
    let mut table = table;
    for (name, dim) in lets {
        if let Some(Dim::Of(dimension)) = dim {
            table.dimensions.insert(name, dimension);
        }
    }
    Ok(Some(table))
}

/// `has kg·m` or `is dimensionless`, for messages.
pub(crate) fn has(dimension: Dimension) -> String {
    if dimension.is_dimensionless() {
        "is dimensionless".to_string()
    } else {
        format!("has {dimension}")
    }
}

/// The `units` entries of `ast`, in source order.
fn unit_entries(ast: &SystemAst) -> impl Iterator<Item = &UnitDecl> {
    ast.statements.iter().flat_map(|s| match &s.kind {
        StatementKind::Units(entries) => entries.as_slice(),
        _ => &[],
    })
}

impl<'m> Checker<'m> {
    fn new(model: &'m Model) -> Checker<'m> {
        Checker {
            model,
            table: UnitTable::default(),
            lets: FxHashMap::default(),
            unreadable: FxHashSet::default(),
            in_check: false,
            used: FxHashSet::default(),
            missing: Vec::new(),
            diagnostics: Vec::new(),
            tables: FxHashMap::default(),
        }
    }

    pub(crate) fn report(&mut self, diagnostic: Diagnostic) {
        self.diagnostics.push(diagnostic);
    }

    /// What `name` is in an expression: its dimension, or `None` (and, the first time, a
    /// note that it has no unit). The model says what the name is; a name it does not bind
    /// is, in a `check`, a derived quantity of the registry.
    pub(crate) fn name(&mut self, name: &str, span: Span) -> Option<Dim> {
        self.used.insert(name.to_string());
        let found = match self.model.names.get(name) {
            // A definition without a unit of its own: what its value was inferred to be
            // (`None`, silently, when that could not be inferred).
            Some(Binding::Let(_)) if self.lets.contains_key(name) => return self.lets[name],
            Some(_) => self.table.dimension(name),
            None if self.in_check => self.table.quantity(name),
            None => None,
        };
        if let Some(dimension) = found {
            return Some(Dim::Of(dimension));
        }
        if !self.unreadable.contains(name) && !self.missing.iter().any(|(n, _)| n == name) {
            self.missing.push((name.to_string(), span));
        }
        None
    }

    /// Reads the units, then the model's coordinates, masses, inertias and tables, which
    /// every statement may use.
    fn declare(&mut self, ast: &SystemAst) {
        for entry in unit_entries(ast) {
            self.declare_unit(entry);
        }
        let model = self.model;
        for coordinate in &model.coordinates {
            self.table.coordinates.push(coordinate.name.clone());
            if self.table.dimension(&coordinate.name).is_none() {
                self.name(&coordinate.name, coordinate.span);
            }
        }
        for mass in &model.masses {
            let span = model.declared_at.get(&mass.name).copied();
            match mass.inertia {
                false => self.declare_mass(&mass.name, span, Dimension::MASS, "a mass"),
                true => self.declare_mass(&mass.name, span, Dimension::INERTIA, "an inertia"),
            }
        }
        for table in &model.tables {
            self.tables.insert(table.name.clone(), None);
        }
        // An input's value has its declared unit; its arguments are the declared ones (the
        // first is checked for one unit at every call, as a table's).
        for input in &model.inputs {
            self.tables.insert(input.name.clone(), None);
        }
    }

    fn declare_unit(&mut self, entry: &UnitDecl) {
        let name = &entry.name;
        if is_reserved(&name.node) {
            let message = if name.node == keywords::TIME {
                format!("`{}` is the time, always in s", keywords::TIME)
            } else {
                format!(
                    "`{}` is a derived quantity: its unit follows from the others",
                    name.node
                )
            };
            return self.report(Diagnostic::new(name.span, message));
        }
        if self.table.written.contains_key(&name.node) || self.unreadable.contains(&name.node) {
            let message = format!("the unit of `{}` is given twice", name.node);
            return self.report(Diagnostic::new(name.span, message));
        }
        match unit_dimension(&entry.unit) {
            Ok(dimension) => {
                self.table.dimensions.insert(name.node.clone(), dimension);
                let written = text(&entry.unit);
                self.table.written.insert(name.node.clone(), written);
            }
            Err(diagnostic) => {
                self.unreadable.insert(name.node.clone());
                self.report(diagnostic);
            }
        }
    }

    /// A mass is in kg and an inertia in kg·m²: a unit given for one must say so.
    fn declare_mass(&mut self, name: &str, at: Option<Span>, dimension: Dimension, what: &str) {
        self.table.masses.push(name.to_string());
        // Whatever `units` says, the mass is checked as what it is.
        if let Some(given) = self.table.dimensions.insert(name.to_string(), dimension) {
            if given != dimension {
                let message =
                    format!("`{name}` is {what}, in {dimension}, but `units` gives it {given}");
                self.report(Diagnostic::new(at.unwrap_or_default(), message));
            }
        }
    }

    /// The rules of one statement.
    fn statement(&mut self, statement: &Statement) {
        match &statement.kind {
            StatementKind::Let { name, value } => self.definition(&name.node, value),
            StatementKind::Mass(decl) => self.mass_law(decl, "mass"),
            StatementKind::Inertia(decl) => self.mass_law(decl, "inertia"),
            StatementKind::Body(body) => {
                let label = |t: &str| format!("position of body `{}`: {t}", body.name.node);
                for component in &body.position.node {
                    self.expect(component, Dimension::LENGTH, None, &label);
                }
            }
            StatementKind::Kinetic(e) => self.energy(e, "kinetic"),
            StatementKind::Potential(e) => self.energy(e, "potential"),
            StatementKind::Lagrangian(e) => self.energy(e, "lagrangian"),
            StatementKind::Force(load) => self.load(load, "generalized force", "force"),
            StatementKind::Thrust(load) => self.load(load, "thrust", "thrust"),
            StatementKind::Impact(load) => self.load(load, "impact force", "impact force"),
            StatementKind::Outflow(flow) => self.flow(flow, "outflow from"),
            StatementKind::Inflow(flow) => self.flow(flow, "inflow into"),
            StatementKind::Check { lhs, rhs, .. } => self.check(lhs, rhs),
            StatementKind::Rigid(rigid) => self.rigid(rigid),
            StatementKind::Torque(load) => self.torque(load),
            StatementKind::Coordinates(_)
            | StatementKind::Units(_)
            | StatementKind::Table(_)
            | StatementKind::Input(_)
            | StatementKind::Use(_)
            | StatementKind::Parameter(_) => {}
        }
    }

    /// Every term of `node` (split at top-level `+` and `-`) has dimension `expected`:
    /// otherwise "<label(term)> has <found>, expected <expected>".
    fn expect(
        &mut self,
        node: &ExprNode,
        expected: Dimension,
        explained: Option<&str>,
        label: &dyn Fn(&str) -> String,
    ) {
        match &*node.node {
            Expr::Binary {
                op: BinOp::Add | BinOp::Sub,
                lhs,
                rhs,
            } => {
                self.expect(lhs, expected, explained, label);
                self.expect(rhs, expected, explained, label);
            }
            _ => {
                if let Some(Dim::Of(found)) = self.infer(node) {
                    if found != expected {
                        let expected = match explained {
                            Some(why) => format!("{} ({why})", expected.described()),
                            None => expected.described(),
                        };
                        let term = label(&text(node));
                        let message = format!("{term} {}, expected {expected}", has(found));
                        self.report(Diagnostic::new(node.span, message));
                    }
                }
            }
        }
    }

    fn energy(&mut self, node: &ExprNode, kind: &str) {
        self.expect(node, Dimension::ENERGY, None, &|t| {
            format!("{kind} term {t}")
        });
    }

    /// A `let` is inferred, or checked against the unit `units` gives it.
    fn definition(&mut self, name: &str, value: &ExprNode) {
        match self.table.dimension(name) {
            Some(given) => {
                let label = |t: &str| format!("definition of `{name}`: {t}");
                self.expect(
                    value,
                    given,
                    Some(&format!("the unit `units` gives `{name}`")),
                    &label,
                );
            }
            None if !self.unreadable.contains(name) => {
                let dim = self.infer(value);
                self.lets.insert(name.to_string(), dim);
            }
            None => {}
        }
    }

    fn mass_law(&mut self, decl: &MassDecl, kind: &str) {
        let name = &decl.name.node;
        let Some(dimension) = self.table.dimension(name) else {
            return;
        };
        match &decl.law {
            MassLaw::Law(law) => {
                let label = |t: &str| format!("{kind} law of `{name}`: {t}");
                self.expect(law, dimension, None, &label);
            }
            MassLaw::State { rate } => {
                let Some(per_second) = dimension.checked_div(Dimension::TIME) else {
                    return;
                };
                let label = |t: &str| format!("rate of `{name}`: {t}");
                self.expect(rate, per_second, None, &label);
            }
        }
    }

    /// A load on a coordinate q has dimension energy / dim(q); on a body, a force.
    fn load(&mut self, load: &Load, generalized: &str, on_body: &str) {
        let target = &load.target.node;
        self.point(load.at.as_ref(), target);
        match &load.value {
            LoadValue::Scalar(value) => {
                if !self.table.coordinates.contains(target) {
                    return;
                }
                let Some(q) = self.table.dimension(target) else {
                    return;
                };
                let Some(expected) = Dimension::ENERGY.checked_div(q) else {
                    return;
                };
                let unit = self.table.written(target).unwrap_or("1").to_string();
                let why = format!("energy per unit of `{target}`, J/{unit}");
                let label = |t: &str| format!("{generalized} on `{target}`: {t}");
                self.expect(value, expected, Some(&why), &label);
            }
            LoadValue::Vector(vector) => {
                let label = |t: &str| format!("{on_body} on body `{target}`: {t}");
                for component in &vector.node {
                    self.expect(component, Dimension::FORCE, None, &label);
                }
            }
        }
    }

    /// A rigid body's position and centre are lengths, its inertia kg·m², its angles
    /// dimensionless (docs/dsl.md#rigid).
    fn rigid(&mut self, rigid: &RigidDecl) {
        let body = &rigid.name.node;
        let lengths = rigid
            .position
            .node
            .iter()
            .chain(rigid.centre.iter().flat_map(|c| &c.node));
        for component in lengths {
            self.expect(component, Dimension::LENGTH, None, &|t| {
                format!("position or centre of rigid body `{body}`: {t}")
            });
        }
        let inertia: Vec<&ExprNode> = match &rigid.inertia {
            InertiaValue::Scalar(e) => vec![e],
            InertiaValue::Principal(v) => v.node.iter().collect(),
            InertiaValue::Tensor(rows) => rows.node.iter().flat_map(|r| &r.node).collect(),
        };
        for component in inertia {
            self.expect(component, Dimension::INERTIA, None, &|t| {
                format!("inertia of rigid body `{body}`: {t}")
            });
        }
        let angles: Vec<&ExprNode> = match &rigid.attitude {
            Attitude::Angle(e) => vec![e],
            Attitude::Orientation { angles, .. } => angles.iter().collect(),
        };
        for angle in angles {
            self.expect(angle, Dimension::NONE, None, &|t| {
                format!("angle of rigid body `{body}`: {t}")
            });
        }
    }

    /// A torque on a rigid body is N·m, a scalar in the plane or a vector in space.
    fn torque(&mut self, load: &Load) {
        let target = &load.target.node;
        let components: Vec<&ExprNode> = match &load.value {
            LoadValue::Scalar(e) => vec![e],
            LoadValue::Vector(v) => v.node.iter().collect(),
        };
        for component in components {
            self.expect(component, Dimension::ENERGY, Some("a torque, N·m"), &|t| {
                format!("torque on `{target}`: {t}")
            });
        }
    }

    /// The point `at [..]` of a load or a flow on a rigid body is a length.
    fn point(&mut self, at: Option<&VectorNode>, target: &str) {
        for component in at.iter().flat_map(|v| &v.node) {
            self.expect(component, Dimension::LENGTH, None, &|t| {
                format!("point `at` on `{target}`: {t}")
            });
        }
    }

    fn flow(&mut self, flow: &Flow, direction: &str) {
        let body = &flow.body.node;
        self.point(flow.at.as_ref(), body);
        if let Some(rate) = &flow.rate {
            let label = |t: &str| format!("rate of {direction} `{body}`: {t}");
            self.expect(rate, Dimension::MASS_FLOW, None, &label);
        }
        let (vector, what) = match &flow.velocity {
            Some(FlowVelocity::Absolute(v)) => (v, "velocity"),
            Some(FlowVelocity::Relative(v)) => (v, "relative velocity"),
            None => return,
        };
        let label = |t: &str| format!("{what} of {direction} `{body}`: {t}");
        for component in &vector.node {
            self.expect(component, Dimension::VELOCITY, None, &label);
        }
    }

    /// Both sides of a `check` have the same dimension.
    fn check(&mut self, lhs: &ExprNode, rhs: &ExprNode) {
        self.in_check = true;
        let (left, right) = (self.infer(lhs), self.infer(rhs));
        self.in_check = false;
        if let (Some(left), Some(right)) = (left, right) {
            let what = "the two sides of this check disagree";
            self.agree(what, lhs, left, rhs, right, lhs.span.join(rhs.span));
        }
    }

    /// A body has no unit. A unit for a name the system does not use is allowed (one
    /// `units` line serves every tag selection); [`Checker::missing_units`] points out a
    /// likely typo among them.
    fn bodies_with_units(&mut self, ast: &SystemAst) {
        let model = self.model;
        for body in &model.bodies {
            for entry in unit_entries(ast).filter(|e| e.name.node == body.name) {
                let name = &entry.name.node;
                let message =
                    format!("`{name}` is a body: it has no unit; its mass and position do");
                self.report(Diagnostic::new(entry.name.span, message));
            }
        }
    }

    /// Whether `name` is given a unit by `units` but is no coordinate or mass and is never
    /// written in an expression: the likely typo when a used name lacks a unit.
    fn is_unused_entry(&self, name: &str) -> bool {
        let declared = self.table.coordinates.iter().chain(&self.table.masses);
        self.table.written.contains_key(name)
            && !self.used.contains(name)
            && !declared.into_iter().any(|d| d == name)
    }

    /// One diagnostic per name used without a unit, its caret on the name where it is
    /// first written (a coordinate at its declaration), with the nearest name the system
    /// declares or uses as "did you mean", and the `units` statement as the other place to
    /// fix it. (A diagnostic has one span: the statement is named in the help, not shown.)
    fn missing_units(&mut self) {
        let missing = std::mem::take(&mut self.missing);
        let missing_names: FxHashSet<&str> = missing.iter().map(|(n, _)| n.as_str()).collect();
        // Every name with a unit or an inferred dimension, and every name written.
        let known = self.table.dimensions.keys().chain(self.lets.keys());
        let known: Vec<&str> = known
            .chain(&self.used)
            .map(String::as_str)
            .filter(|n| !missing_names.contains(n))
            .collect();
        let mut diagnostics = Vec::new();
        for (name, span) in &missing {
            let message = format!(
                "no unit for `{name}`: with `units`, every coordinate and parameter needs one"
            );
            let add = format!("add `{name}: …` to the `units` statement");
            let help = match keywords::nearest(name, known.iter().copied()) {
                Some(close) if self.is_unused_entry(close) => format!(
                    "`{close}` has a unit in the `units` statement but is used nowhere: did you mean `{name}` there? Otherwise {add}"
                ),
                Some(close) => format!("did you mean `{close}`? Otherwise {add}"),
                None => add,
            };
            diagnostics.push(Diagnostic::new(*span, message).with_help(help));
        }
        for diagnostic in diagnostics {
            self.report(diagnostic);
        }
    }
}
