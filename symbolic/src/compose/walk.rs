//! One walk over every name and every span of a statement, for the expansion: the spans
//! of a component's text are moved into its region ([`Shift`]), its names read
//! (`instance::Names`) and renamed (`instance::Rename`). A name is visited with its
//! [`Role`], which decides what a binding of it may be.

use crate::parse::ast::{
    Attitude, Expr, ExprNode, Flow, FlowVelocity, InertiaValue, InputDecl, Load, LoadValue,
    MassLaw, RigidDecl, Statement, StatementKind, VectorNode,
};
use crate::parse::{Span, Spanned};

/// What a name is where it is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Role {
    /// It is declared here (`coordinates x`, `mass m`, `let w`, `body b`, `table F`,
    /// `input u`, `parameter g`).
    Declared,
    /// Read in an expression.
    Read,
    /// Read with primes (`x'`) or as an input's argument: a coordinate.
    Primed,
    /// What a statement acts on or is made of: the target of a load, the body of a flow,
    /// the mass of a body. It must stay a name.
    Target,
    /// Called as a function (`F(t)`): a table, an input or a built-in function.
    Called,
    /// The name before `:` in `units`.
    Unit,
}

/// What the walk does at each name and span.
pub(super) trait Visit {
    /// At every span, after the names it holds.
    fn span(&mut self, _span: &mut Span) {}
    /// At every name, with the span it is written at.
    fn name(&mut self, _name: &mut String, _span: Span, _role: Role) {}
}

/// Moves every span by `by` bytes: a component's text placed in its region.
pub(super) struct Shift(pub usize);

impl Visit for Shift {
    fn span(&mut self, span: &mut Span) {
        span.start += self.0;
        span.end += self.0;
    }
}

/// Every name and span of `statement`, in source order within each part.
pub(super) fn statement(statement: &mut Statement, v: &mut impl Visit) {
    for tag in &mut statement.tags {
        v.span(&mut tag.span);
    }
    v.span(&mut statement.span);
    match &mut statement.kind {
        StatementKind::Coordinates(names) => {
            names.iter_mut().for_each(|n| named(n, Role::Declared, v))
        }
        StatementKind::Mass(decl) | StatementKind::Inertia(decl) => {
            named(&mut decl.name, Role::Declared, v);
            match &mut decl.law {
                MassLaw::Law(e) | MassLaw::State { rate: e } => expr(e, v),
            }
        }
        StatementKind::Let { name, value } => {
            named(name, Role::Declared, v);
            expr(value, v);
        }
        StatementKind::Body(body) => {
            named(&mut body.name, Role::Declared, v);
            named(&mut body.mass, Role::Target, v);
            vector(&mut body.position, v);
        }
        StatementKind::Kinetic(e) | StatementKind::Potential(e) | StatementKind::Lagrangian(e) => {
            expr(e, v)
        }
        StatementKind::Force(load)
        | StatementKind::Thrust(load)
        | StatementKind::Impact(load)
        | StatementKind::Torque(load) => load_parts(load, v),
        StatementKind::Outflow(flow) | StatementKind::Inflow(flow) => flow_parts(flow, v),
        StatementKind::Check { lhs, rhs, .. } => {
            expr(lhs, v);
            expr(rhs, v);
        }
        StatementKind::Units(entries) => {
            for entry in entries {
                named(&mut entry.name, Role::Unit, v);
                // Unit symbols (`m`, `kg`) are no names of the system: spans only.
                spans_only(&mut entry.unit, v);
            }
        }
        StatementKind::Rigid(rigid) => rigid_body(rigid, v),
        StatementKind::Table(table) => {
            named(&mut table.name, Role::Declared, v);
            v.span(&mut table.parameter.span);
            v.span(&mut table.file.span);
        }
        StatementKind::Input(input) => input_parts(input, v),
        StatementKind::Use(decl) => {
            v.span(&mut decl.file.span);
            v.span(&mut decl.instance.span);
            for binding in &mut decl.bindings {
                v.span(&mut binding.name.span);
                expr(&mut binding.value, v);
            }
        }
        StatementKind::Parameter(decl) => {
            named(&mut decl.name, Role::Declared, v);
            expr(&mut decl.default, v);
        }
    }
}

/// The parts of a load: its target, value and point.
fn load_parts(load: &mut Load, v: &mut impl Visit) {
    named(&mut load.target, Role::Target, v);
    match &mut load.value {
        LoadValue::Scalar(e) => expr(e, v),
        LoadValue::Vector(vn) => vector(vn, v),
    }
    load.at.iter_mut().for_each(|at| vector(at, v));
}

/// The parts of a flow: its body, rate, velocity and point.
fn flow_parts(flow: &mut Flow, v: &mut impl Visit) {
    named(&mut flow.body, Role::Target, v);
    flow.rate.iter_mut().for_each(|e| expr(e, v));
    match &mut flow.velocity {
        Some(FlowVelocity::Absolute(vn) | FlowVelocity::Relative(vn)) => vector(vn, v),
        None => {}
    }
    flow.at.iter_mut().for_each(|at| vector(at, v));
}

/// The parts of an `input` statement: its name, arguments and period.
fn input_parts(input: &mut InputDecl, v: &mut impl Visit) {
    named(&mut input.name, Role::Declared, v);
    for (argument, primes) in &mut input.arguments {
        let role = if *primes > 0 {
            Role::Primed
        } else {
            Role::Read
        };
        named(argument, role, v);
    }
    input.every.iter_mut().for_each(|e| v.span(&mut e.span));
}

/// The parts of a `rigid` statement.
fn rigid_body(rigid: &mut RigidDecl, v: &mut impl Visit) {
    named(&mut rigid.name, Role::Declared, v);
    named(&mut rigid.mass, Role::Target, v);
    match &mut rigid.inertia {
        InertiaValue::Scalar(e) => expr(e, v),
        InertiaValue::Principal(vn) => vector(vn, v),
        InertiaValue::Tensor(rows) => {
            rows.node.iter_mut().for_each(|row| vector(row, v));
            v.span(&mut rows.span);
        }
    }
    vector(&mut rigid.position, v);
    match &mut rigid.attitude {
        Attitude::Angle(e) => expr(e, v),
        Attitude::Orientation { sequence, angles } => {
            v.span(&mut sequence.span);
            angles.iter_mut().for_each(|e| expr(e, v));
        }
    }
    rigid.centre.iter_mut().for_each(|c| vector(c, v));
}

/// A name with its span.
fn named(name: &mut Spanned<String>, role: Role, v: &mut impl Visit) {
    v.name(&mut name.node, name.span, role);
    v.span(&mut name.span);
}

/// A bracketed vector.
fn vector(vn: &mut VectorNode, v: &mut impl Visit) {
    vn.node.iter_mut().for_each(|e| expr(e, v));
    v.span(&mut vn.span);
}

/// An expression: its names, then its spans. Recursive: the parser bounds the depth
/// (`MAX_DEPTH`), so that this walk cannot overflow the stack.
fn expr(node: &mut ExprNode, v: &mut impl Visit) {
    let span = node.span;
    match node.node.as_mut() {
        Expr::Number(_) => {}
        Expr::Name(name) => v.name(name, span, Role::Read),
        Expr::Derivative { name, .. } => v.name(name, span, Role::Primed),
        Expr::Neg(inner) => expr(inner, v),
        Expr::Binary { lhs, rhs, .. } => {
            expr(lhs, v);
            expr(rhs, v);
        }
        Expr::Call { func, args } => {
            named(func, Role::Called, v);
            args.iter_mut().for_each(|a| expr(a, v));
        }
    }
    v.span(&mut node.span);
}

/// The spans of an expression whose names are not the system's (a unit).
fn spans_only(node: &mut ExprNode, v: &mut impl Visit) {
    struct Spans<'v, V>(&'v mut V);
    impl<V: Visit> Visit for Spans<'_, V> {
        fn span(&mut self, span: &mut Span) {
            self.0.span(span);
        }
    }
    expr(node, &mut Spans(v));
}
