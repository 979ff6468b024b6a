//! Building the checked [`Model`] from the AST: declarations first (so any statement may
//! name any coordinate or mass), then every expression lowered in its scope, each rule a
//! diagnostic at the statement it is about.

use rustc_hash::{FxHashMap, FxHashSet};
use std::path::{Path, PathBuf};

use super::model::{
    Body, Check, Coordinate, Flow, FlowVelocityValue, Load, LoadKind, LoadTarget, Mass, MassKind,
    Model, Term, TermKind,
};
use super::resolve::{is_reserved, lower_with, Binding, Context, Parameters};
use super::switches::jump_in_law;
use crate::expr::{ExprPool, Id, Symbol, SymbolKind};
use crate::parse::ast::{
    BodyDecl, ExprNode, FlowVelocity, LoadValue, MassDecl, MassLaw, ParameterDecl, StatementKind,
    SystemAst, VectorNode,
};
use crate::parse::{keywords, Diagnostic, Span, Spanned};

/// Builds the model, collecting every diagnostic; table files are read relative to `base`.
pub fn build_model(
    ast: &SystemAst,
    parameters: Parameters,
    base: &Path,
    laws: &[(String, ExprNode)],
) -> Result<Model, Vec<Diagnostic>> {
    let mut builder = Builder::new(parameters, base);
    builder.laws = laws.to_vec();
    builder.declare(ast);
    builder.lower_statements(ast);
    builder.lower_sampled_laws();
    builder.check_quaternion_potentials();
    builder.finish()
}

pub(super) struct Builder {
    pub(super) model: Model,
    pub(super) errors: Vec<Diagnostic>,
    /// Bodies whose `body` or `rigid` statement failed (and was reported): loads, torques
    /// and flows on them are skipped silently rather than reported as naming no body.
    pub(super) failed_bodies: FxHashSet<String>,
    /// The directory table files are read from.
    pub(super) base: PathBuf,
    /// Laws given for inputs by name (`inputs.rs`, [`super::derive_with_laws`]).
    pub(super) laws: Vec<(String, ExprNode)>,
}

impl Builder {
    fn new(parameters: Parameters, base: &Path) -> Builder {
        let mut pool = ExprPool::new();
        let time = pool.symbols_mut().add(keywords::TIME, SymbolKind::Time);
        let mut names = FxHashMap::default();
        names.insert(keywords::TIME.to_string(), Binding::Time(time));
        let mut declared = Vec::new();
        if let Parameters::Declared(list) = &parameters {
            // A field may not take over `t` (the macro reports such a field at its span).
            for name in list {
                if names.contains_key(name.as_str()) {
                    continue;
                }
                let symbol = pool.symbols_mut().add(name, SymbolKind::Parameter);
                names.insert(name.clone(), Binding::Parameter(symbol));
                declared.push((name.clone(), symbol));
            }
        }
        Builder {
            model: Model {
                pool,
                time,
                coordinates: Vec::new(),
                masses: Vec::new(),
                parameters: declared,
                bodies: Vec::new(),
                loads: Vec::new(),
                flows: Vec::new(),
                terms: Vec::new(),
                checks: Vec::new(),
                tables: Vec::new(),
                inputs: Vec::new(),
                names,
                declared_at: FxHashMap::default(),
                parameter_mode: parameters,
            },
            errors: Vec::new(),
            failed_bodies: FxHashSet::default(),
            base: base.to_path_buf(),
            laws: Vec::new(),
        }
    }

    /// Checks a new name against everything declared so far (why: one name, one meaning —
    /// a mass named like a coordinate would make every equation ambiguous).
    pub(super) fn check_new_name(&mut self, name: &str, span: Span, what: &str) -> bool {
        if is_reserved(name) {
            self.errors.push(Diagnostic::new(
                span,
                format!("`{name}` is reserved for a derived quantity or the time, and cannot name {} {what}", article(what)),
            ));
            return false;
        }
        if let Some(previous) = self.model.declared_at.get(name) {
            self.errors.push(
                Diagnostic::new(span, format!("`{name}` is declared twice")).with_help(format!(
                    "first declared at {}:{}",
                    previous.line, previous.column
                )),
            );
            return false;
        }
        if let Some(Binding::Parameter(_)) = self.model.names.get(name) {
            self.errors.push(Diagnostic::new(
                span,
                format!("`{name}` is already a parameter (a field of the struct); a {what} needs its own name"),
            ));
            return false;
        }
        self.model.declared_at.insert(name.to_string(), span);
        true
    }

    /// First pass: coordinates and masses, so that any statement may use them.
    fn declare(&mut self, ast: &SystemAst) {
        for statement in &ast.statements {
            match &statement.kind {
                StatementKind::Coordinates(names) => {
                    for name in names {
                        self.declare_coordinate(name);
                    }
                }
                StatementKind::Mass(decl) | StatementKind::Inertia(decl) => {
                    let inertia = matches!(statement.kind, StatementKind::Inertia(_));
                    self.declare_mass(decl, inertia, statement.span);
                }
                StatementKind::Let { name, .. } => {
                    self.check_new_name(&name.node, name.span, "definition");
                }
                StatementKind::Body(body) => {
                    self.check_new_name(&body.name.node, body.name.span, "body");
                }
                StatementKind::Rigid(rigid) => {
                    self.check_new_name(&rigid.name.node, rigid.name.span, "body");
                }
                StatementKind::Table(table) => self.declare_table(table),
                StatementKind::Input(input) => self.declare_input(input),
                StatementKind::Parameter(decl) => self.declare_default(decl),
                StatementKind::Use(decl) => self.errors.push(
                    Diagnostic::new(decl.file.span, "a `use` is not expanded")
                        .with_help("expand the model's components first (`compose::compose`)"),
                ),
                _ => {}
            }
        }
        for statement in &ast.statements {
            if let StatementKind::Input(input) = &statement.kind {
                self.check_input_arguments(input);
            }
        }
        if self.model.coordinates.is_empty() && self.errors.is_empty() {
            let span = ast.statements.first().map_or(Span::default(), |s| s.span);
            self.errors.push(
                Diagnostic::new(span, "the system declares no coordinates")
                    .with_help("start with `coordinates x` (one name per degree of freedom)"),
            );
        }
        // State masses first: the runtime keeps them in the state in this order.
        self.model
            .masses
            .sort_by_key(|m| !matches!(m.kind, MassKind::State { .. }));
    }

    /// A coordinate with its velocity, acceleration and momentum symbols.
    fn declare_coordinate(&mut self, name: &Spanned<String>) {
        if !self.check_new_name(&name.node, name.span, "coordinate") {
            return;
        }
        let symbols = self.model.pool.symbols_mut();
        let q = symbols.add_coordinate(&name.node);
        let (velocity, acceleration, momentum) = match (
            symbols.velocity_of(q),
            symbols.acceleration_of(q),
            symbols.momentum_of(q),
        ) {
            (Some(v), Some(a), Some(p)) => (v, a, p),
            _ => return,
        };
        self.model.names.insert(
            name.node.clone(),
            Binding::Coordinate {
                q,
                velocity,
                acceleration,
            },
        );
        self.model.coordinates.push(Coordinate {
            name: name.node.clone(),
            q,
            velocity,
            acceleration,
            momentum,
            span: name.span,
        });
    }

    /// A mass or inertia, its law or rate a placeholder until the second pass.
    fn declare_mass(&mut self, decl: &MassDecl, inertia: bool, span: Span) {
        let what = if inertia { "inertia" } else { "mass" };
        if !self.check_new_name(&decl.name.node, decl.name.span, what) {
            return;
        }
        let symbol = self
            .model
            .pool
            .symbols_mut()
            .add(&decl.name.node, SymbolKind::Frozen);
        self.model
            .names
            .insert(decl.name.node.clone(), Binding::Mass(symbol));
        // The kind's expression is a placeholder until the second pass lowers it.
        let placeholder = self.model.pool.int(0);
        let kind = match decl.law {
            MassLaw::Law(_) => MassKind::Law(placeholder),
            MassLaw::State { .. } => MassKind::State { rate: placeholder },
        };
        self.model.masses.push(Mass {
            name: decl.name.node.clone(),
            symbol,
            kind,
            inertia,
            span,
        });
    }
}

/// Lowers `node` in `model`'s scope.
pub(crate) fn lower_in(
    model: &mut Model,
    node: &ExprNode,
    context: Context,
    quantities: Option<&FxHashMap<String, Id>>,
) -> Result<Id, Vec<Diagnostic>> {
    let Model {
        pool,
        names,
        parameter_mode,
        parameters,
        ..
    } = model;
    lower_with(
        pool,
        names,
        parameter_mode,
        parameters,
        node,
        context,
        quantities,
    )
}

/// The first velocity symbol `e` depends on, if any.
pub(crate) fn first_velocity(pool: &ExprPool, e: Id) -> Option<Symbol> {
    pool.free_symbols(e)
        .into_iter()
        .find(|s| matches!(pool.symbols().kind(*s), SymbolKind::Velocity { .. }))
}

impl Builder {
    pub(super) fn lower(&mut self, node: &ExprNode) -> Option<Id> {
        match lower_in(&mut self.model, node, Context::Ordinary, None) {
            Ok(id) => Some(id),
            Err(mut errors) => {
                self.errors.append(&mut errors);
                None
            }
        }
    }

    pub(super) fn lower_vector(&mut self, vector: &VectorNode) -> Option<Vec<Id>> {
        let lowered: Vec<Option<Id>> = vector.node.iter().map(|e| self.lower(e)).collect();
        lowered.into_iter().collect()
    }

    /// A quantity of configuration (a mass law, a position) may not depend on velocities:
    /// the frozen-mass calculus needs m(q, t) and r(q, t).
    pub(super) fn require_configuration(&mut self, value: Id, span: Span, what: &str) -> bool {
        match first_velocity(&self.model.pool, value) {
            Some(v) => {
                let name = self.model.pool.symbols().name(v).to_string();
                self.errors.push(Diagnostic::new(
                    span,
                    format!("{what} depends on the velocity `{name}`; it may depend only on coordinates, time and parameters"),
                ));
                false
            }
            None => true,
        }
    }

    pub(super) fn mass_index(&self, name: &str) -> Option<usize> {
        self.model.masses.iter().position(|m| m.name == name)
    }

    pub(super) fn body_index(&self, name: &str) -> Option<usize> {
        self.model.bodies.iter().position(|b| b.name == name)
    }

    /// `parameter g = 9.81` (docs/components.md#defaults): with inferred parameters the name
    /// is a parameter like any other (its value given by the caller, the default when it
    /// gives none); with declared ones (the macro's fields) a name that is no field is a
    /// definition of its default, everywhere in the model.
    fn declare_default(&mut self, decl: &ParameterDecl) {
        let name = &decl.name.node;
        if matches!(self.model.parameter_mode, Parameters::Inferred)
            || self.model.names.contains_key(name)
            || !self.check_new_name(name, decl.name.span, "parameter")
        {
            return;
        }
        if let Some(value) = self.lower(&decl.default) {
            self.model.names.insert(name.clone(), Binding::Let(value));
        }
    }

    /// `let name = value`. A name an earlier statement read (so that it became an inferred
    /// parameter there, a `let` being visible only after it) is an error at the `let`: it
    /// was dropped without a word, and the model ran with the parameter (review of session
    /// 33; a component's values placed after a statement that reads them met it too).
    fn lower_let(&mut self, name: &str, span: Span, value: &ExprNode) {
        let read_before = matches!(self.model.parameter_mode, Parameters::Inferred)
            && matches!(self.model.names.get(name), Some(Binding::Parameter(_)));
        if read_before {
            self.errors.push(
                Diagnostic::new(
                    span,
                    format!("`{name}` is read before this `let` defines it"),
                )
                .with_help(format!(
                    "a `let` is visible only after it, so the earlier read made `{name}` a \
                     parameter: move this `let` above the first statement that reads `{name}` \
                     (or above the `use` whose bindings read it)"
                )),
            );
            return;
        }
        if let Some(value) = self.lower(value) {
            self.model
                .names
                .entry(name.to_string())
                .or_insert(Binding::Let(value));
        }
    }

    /// After a `body` or `rigid` statement: when it added no body `name`, it failed with
    /// its own diagnostics, and the loads and flows on `name` would only repeat them.
    fn note_failed_body(&mut self, name: &str) {
        if self.body_index(name).is_none() {
            self.failed_bodies.insert(name.to_string());
        }
    }

    /// Second pass: lower every expression. Definitions, masses, bodies and terms go in
    /// source order (a `let` is visible after it); loads, flows and checks after them, so
    /// they may name any body.
    fn lower_statements(&mut self, ast: &SystemAst) {
        for statement in &ast.statements {
            let span = statement.span;
            match &statement.kind {
                StatementKind::Let { name, value } => self.lower_let(&name.node, name.span, value),
                StatementKind::Mass(decl) | StatementKind::Inertia(decl) => {
                    self.lower_mass(decl, span);
                }
                StatementKind::Body(body) => {
                    self.lower_body(body, span);
                    self.note_failed_body(&body.name.node);
                }
                StatementKind::Rigid(rigid) => {
                    self.lower_rigid(rigid, span);
                    self.note_failed_body(&rigid.name.node);
                }
                StatementKind::Kinetic(e) => self.lower_term(TermKind::Kinetic, e, span),
                StatementKind::Potential(e) => self.lower_term(TermKind::Potential, e, span),
                StatementKind::Lagrangian(e) => self.lower_term(TermKind::Lagrangian, e, span),
                _ => {}
            }
        }
        for statement in &ast.statements {
            let span = statement.span;
            match &statement.kind {
                StatementKind::Force(load) => self.lower_load(LoadKind::Active, load, span),
                StatementKind::Thrust(load) => self.lower_load(LoadKind::Thrust, load, span),
                StatementKind::Impact(load) => self.lower_load(LoadKind::Impact, load, span),
                StatementKind::Torque(load) => self.lower_torque(load, span),
                StatementKind::Outflow(flow) | StatementKind::Inflow(flow) => {
                    let inflow = matches!(statement.kind, StatementKind::Inflow(_));
                    self.lower_flow(inflow, flow, span);
                }
                StatementKind::Check { lhs, rhs, text } => self.model.checks.push(Check {
                    lhs: lhs.clone(),
                    rhs: rhs.clone(),
                    source: format!("{} {text}", keywords::CHECK),
                    span,
                }),
                _ => {}
            }
        }
    }

    /// A term of the Lagrangian L = T − V: a `kinetic`, `potential` or `lagrangian` statement.
    fn lower_term(&mut self, kind: TermKind, e: &ExprNode, span: Span) {
        if let Some(value) = self.lower(e) {
            self.model.terms.push(Term { kind, value, span });
        }
    }

    /// The law or the rate of a declared mass, replacing its placeholder.
    fn lower_mass(&mut self, decl: &MassDecl, span: Span) {
        let Some(index) = self.mass_index(&decl.name.node) else {
            return;
        };
        let kind = match &decl.law {
            MassLaw::Law(written) => {
                let Some(law) = self.lower(written) else {
                    return;
                };
                let what = format!("the law of `{}`", decl.name.node);
                if !self.require_configuration(law, span, &what) {
                    return;
                }
                let name = &decl.name.node;
                if let Some(jump) = jump_in_law(&self.model.pool, law, written, span, name) {
                    self.errors.push(jump);
                    return;
                }
                MassKind::Law(law)
            }
            MassLaw::State { rate } => match self.lower(rate) {
                Some(rate) => MassKind::State { rate },
                None => return,
            },
        };
        self.model.masses[index].kind = kind;
    }

    /// The index of a body's declared mass, or a diagnostic.
    pub(super) fn body_mass(&mut self, mass: &Spanned<String>) -> Option<usize> {
        let index = self.mass_index(&mass.node);
        if index.is_none() {
            let d = Diagnostic::new(mass.span, format!("`{}` is not a declared mass", mass.node))
                .with_help(format!(
                    "declare it first, e.g. `{} {} = m0` or `{} {}: state, rate -mu`",
                    keywords::MASS,
                    mass.node,
                    keywords::MASS,
                    mass.node
                ));
            self.errors.push(d);
        }
        index
    }

    /// A body on a declared mass, its position a function of configuration only.
    fn lower_body(&mut self, body: &BodyDecl, span: Span) {
        let Some(mass) = self.body_mass(&body.mass) else {
            return;
        };
        let Some(position) = self.lower_vector(&body.position) else {
            return;
        };
        let what = format!("the position of body `{}`", body.name.node);
        if position
            .iter()
            .all(|p| self.require_configuration(*p, body.position.span, &what))
        {
            self.model.bodies.push(Body {
                name: body.name.node.clone(),
                mass,
                position,
                rigid: None,
                span,
            });
        }
    }

    fn lower_load(&mut self, kind: LoadKind, load: &crate::parse::ast::Load, span: Span) {
        let target = &load.target;
        if let Some(index) = self
            .model
            .coordinates
            .iter()
            .position(|c| c.name == target.node)
        {
            match &load.value {
                LoadValue::Scalar(e) => {
                    if let Some(value) = self.lower(e) {
                        self.model.loads.push(Load {
                            kind,
                            target: LoadTarget::Coordinate(index, value),
                            span,
                        });
                    }
                }
                LoadValue::Vector(v) => self.errors.push(
                    Diagnostic::new(v.span, format!("`{}` is a coordinate, so its load is a generalized component, not a vector", target.node))
                        .with_help(format!("write `{}: <expression>`, or name a body to apply a vector", target.node)),
                ),
            }
        } else if let Some(index) = self.body_index(&target.node) {
            if self.model.bodies[index].rigid.is_some() {
                self.lower_rigid_load(kind, index, load, span);
                return;
            }
            if !self.particle_plain(index, load.frame, load.at.as_ref()) {
                return;
            }
            match &load.value {
                LoadValue::Vector(v) => {
                    let Some(value) = self.lower_vector(v) else {
                        return;
                    };
                    if self.check_dimension(index, value.len(), v.span) {
                        self.model.loads.push(Load {
                            kind,
                            target: LoadTarget::Body(index, value),
                            span,
                        });
                    }
                }
                LoadValue::Scalar(e) => self.errors.push(Diagnostic::new(
                    e.span,
                    format!(
                        "`{}` is a body, so its load is a vector `[...]` in the body's dimensions",
                        target.node
                    ),
                )),
            }
        } else if !self.failed_bodies.contains(&target.node) {
            let coordinates = self.model.coordinates.iter().map(|c| c.name.as_str());
            let bodies = self.model.bodies.iter().map(|b| b.name.as_str());
            let message = format!("`{}` is neither a coordinate nor a body", target.node);
            let diagnostic = Diagnostic::new(target.span, message);
            let close = keywords::nearest(&target.node, coordinates.chain(bodies));
            self.errors.push(did_you_mean(diagnostic, close));
        }
    }

    /// Vectors on a body live in the space of its position (why: F·∂r/∂q needs both).
    pub(super) fn check_dimension(&mut self, body: usize, found: usize, span: Span) -> bool {
        let expected = self.model.bodies[body].position.len();
        if expected == found {
            return true;
        }
        self.errors.push(Diagnostic::new(
            span,
            format!(
                "body `{}` moves in {expected} dimension{}, but this vector has {found} component{}",
                self.model.bodies[body].name,
                if expected == 1 { "" } else { "s" },
                if found == 1 { "" } else { "s" },
            ),
        ));
        false
    }

    fn lower_flow(&mut self, inflow: bool, flow: &crate::parse::ast::Flow, span: Span) {
        let Some(body) = self.body_index(&flow.body.node) else {
            if self.failed_bodies.contains(&flow.body.node) {
                return;
            }
            let message = format!(
                "`{}` is not a body; mass flows in and out of bodies",
                flow.body.node
            );
            let bodies = self.model.bodies.iter().map(|b| b.name.as_str());
            let close = keywords::nearest(&flow.body.node, bodies);
            let diagnostic = Diagnostic::new(flow.body.span, message);
            self.errors.push(did_you_mean(diagnostic, close));
            return;
        };
        let rate = match &flow.rate {
            Some(rate) => match self.lower(rate) {
                Some(rate) => Some(rate),
                None => return,
            },
            None => None,
        };
        let rigid = self.model.bodies[body].rigid.is_some();
        if !rigid && !self.particle_plain(body, flow.frame, flow.at.as_ref()) {
            return;
        }
        let velocity = match &flow.velocity {
            Some(FlowVelocity::Absolute(v)) | Some(FlowVelocity::Relative(v)) => {
                let Some(value) = self.lower_vector(v) else {
                    return;
                };
                if !self.check_dimension(body, value.len(), v.span) {
                    return;
                }
                let value = self.in_world_axes(body, flow.frame, value);
                if matches!(flow.velocity, Some(FlowVelocity::Absolute(_))) {
                    FlowVelocityValue::Absolute(value)
                } else {
                    FlowVelocityValue::Relative(value)
                }
            }
            None => FlowVelocityValue::WithBody,
        };
        let point = if rigid {
            match self.body_point(body, flow.at.as_ref()) {
                Some(point) => Some(point),
                None => return,
            }
        } else {
            None
        };
        self.model.flows.push(Flow {
            inflow,
            body,
            rate,
            velocity,
            point,
            span,
        });
    }

    fn finish(self) -> Result<Model, Vec<Diagnostic>> {
        if self.errors.is_empty() {
            Ok(self.model)
        } else {
            Err(self.errors)
        }
    }
}

/// `diagnostic` with "did you mean `close`?" when there is a near name.
fn did_you_mean(diagnostic: Diagnostic, close: Option<&str>) -> Diagnostic {
    match close {
        Some(close) => diagnostic.with_help(format!("did you mean `{close}`?")),
        None => diagnostic,
    }
}

/// "a" or "an" before `word` (by its first letter: the words named here are plain nouns,
/// "an input", "a mass").
fn article(word: &str) -> &'static str {
    match word.starts_with(['a', 'e', 'i', 'o', 'u']) {
        true => "an",
        false => "a",
    }
}
