//! Test-only helpers shared by the `parse_*` tests: a fully parenthesized printer (so two
//! trees print the same exactly when they have the same structure, spans aside) and
//! walkers over the AST.
#![allow(dead_code)]

use varmass_symbolic::parse::ast::{
    Attitude, Expr, ExprNode, FlowVelocity, InertiaValue, LoadValue, MassLaw, Statement,
    StatementKind,
};
use varmass_symbolic::parse::{Diagnostic, Span};

/// Fully parenthesized text of an expression: `(a + b)`, `(-a)`, `f(a, b)`, `x'`.
/// Injective on trees: binary nodes have spaces around the operator, negation does not.
pub fn show(node: &ExprNode) -> String {
    match &*node.node {
        Expr::Number(text) => text.clone(),
        Expr::Name(name) => name.clone(),
        Expr::Derivative { name, order } => format!("{name}{}", "'".repeat(*order as usize)),
        Expr::Neg(inner) => format!("(-{})", show(inner)),
        Expr::Binary { op, lhs, rhs } => format!("({} {op} {})", show(lhs), show(rhs)),
        Expr::Call { func, args } => {
            let args: Vec<String> = args.iter().map(show).collect();
            format!("{}({})", func.node, args.join(", "))
        }
    }
}

/// Every expression node under `node`, itself included, parents before children.
pub fn nodes(node: &ExprNode) -> Vec<&ExprNode> {
    let mut all = vec![node];
    let mut index = 0;
    while let Some(&current) = all.get(index) {
        match &*current.node {
            Expr::Neg(inner) => all.push(inner),
            Expr::Binary { lhs, rhs, .. } => {
                all.push(lhs);
                all.push(rhs);
            }
            Expr::Call { args, .. } => all.extend(args.iter()),
            _ => {}
        }
        index += 1;
    }
    all
}

/// Every expression directly in a statement (not recursing into them).
pub fn statement_expressions(statement: &Statement) -> Vec<&ExprNode> {
    match &statement.kind {
        StatementKind::Coordinates(_) => vec![],
        StatementKind::Mass(decl) | StatementKind::Inertia(decl) => match &decl.law {
            MassLaw::Law(law) => vec![law],
            MassLaw::State { rate } => vec![rate],
        },
        StatementKind::Let { value, .. } => vec![value],
        StatementKind::Body(body) => body.position.node.iter().collect(),
        StatementKind::Kinetic(e) | StatementKind::Potential(e) | StatementKind::Lagrangian(e) => {
            vec![e]
        }
        StatementKind::Force(load)
        | StatementKind::Thrust(load)
        | StatementKind::Impact(load)
        | StatementKind::Torque(load) => {
            let mut all: Vec<&ExprNode> = match &load.value {
                LoadValue::Scalar(e) => vec![e],
                LoadValue::Vector(v) => v.node.iter().collect(),
            };
            all.extend(load.at.iter().flat_map(|v| v.node.iter()));
            all
        }
        StatementKind::Rigid(rigid) => {
            let mut all: Vec<&ExprNode> = match &rigid.inertia {
                InertiaValue::Scalar(e) => vec![e],
                InertiaValue::Principal(v) => v.node.iter().collect(),
                InertiaValue::Tensor(rows) => {
                    rows.node.iter().flat_map(|r| r.node.iter()).collect()
                }
            };
            all.extend(rigid.position.node.iter());
            match &rigid.attitude {
                Attitude::Angle(e) => all.push(e),
                Attitude::Orientation { angles, .. } => all.extend(angles.iter()),
            }
            all.extend(rigid.centre.iter().flat_map(|v| v.node.iter()));
            all
        }
        StatementKind::Outflow(flow) | StatementKind::Inflow(flow) => {
            let mut all: Vec<&ExprNode> = flow.rate.iter().collect();
            match &flow.velocity {
                Some(FlowVelocity::Absolute(v)) | Some(FlowVelocity::Relative(v)) => {
                    all.extend(v.node.iter())
                }
                None => {}
            }
            all.extend(flow.at.iter().flat_map(|v| v.node.iter()));
            all
        }
        StatementKind::Check { lhs, rhs, .. } => vec![lhs, rhs],
        StatementKind::Units(entries) => entries.iter().map(|e| &e.unit).collect(),
        StatementKind::Use(decl) => decl.bindings.iter().map(|b| &b.value).collect(),
        StatementKind::Table(_) | StatementKind::Input(_) | StatementKind::Parameter(_) => {
            vec![]
        }
    }
}

/// The source text a span covers.
pub fn text(source: &str, span: Span) -> &str {
    &source[span.start..span.end]
}

/// Asserts that `span` is well formed for `source`: inside it, on character boundaries,
/// with the line and column that [`Span::from_range`] computes independently.
pub fn assert_span_valid(source: &str, span: Span) {
    assert!(
        span.start <= span.end && span.end <= source.len(),
        "{span:?} out of range"
    );
    assert!(source.is_char_boundary(span.start) && source.is_char_boundary(span.end));
    assert_eq!(span, Span::from_range(source, span.start, span.end));
}

/// The single diagnostic of a system that must fail with exactly one error.
pub fn single_error(source: &str) -> Diagnostic {
    let errors = varmass_symbolic::parse::parse_system(source).expect_err(source);
    assert_eq!(errors.len(), 1, "{source:?} gave {errors:#?}");
    errors.into_iter().next().unwrap()
}

/// The value of `VARMASS_FUZZ_CASES` if set (for long fuzzing runs), else `default`.
pub fn fuzz_cases(default: u32) -> u32 {
    std::env::var("VARMASS_FUZZ_CASES")
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(default)
}

/// The paper's sled (docs/dsl.md#the-sled-both-ways), written with the impact force given directly.
pub const SLED_PAPER: &str = "\
# paper form
coordinates x
mass m = m0 + c*x
lagrangian 1/2*m*x'^2 + m*g*x*sin(theta)
force x: -f_d*m*g*cos(theta)
impact x: -c*x'^2
";

/// The same sled with a body and an inflow (docs/dsl.md#the-sled-both-ways).
pub const SLED_BODY: &str = "\
# body form: R2 derived from the inflow
coordinates x
mass m = m0 + c*x
body sled: mass m, position [x]
potential -m*g*x*sin(theta)
force sled: [-f_d*m*g*cos(theta)]
inflow sled: velocity [0]
";

/// A vertical rocket burning at a constant rate.
pub const ROCKET: &str =
    "coordinates y; mass m: state, rate -mu; body rocket: mass m, position [y]; \
potential m*g*y; outflow rocket: rate mu, relative_velocity [-u_e]";

/// A system using every statement form.
pub const EVERY_STATEMENT: &str = "\
coordinates x, y, phi    # three coordinates
mass m = m0 + c*x; mass q: state, rate -mu
inertia J = m*r^2/2
inertia K: state, rate k
let w = sqrt(g/l)
body b: position [x, y, 0], mass m
kinetic 1/2*J*phi'^2
potential m*g*y
lagrangian -1/2*k*phi^2
force x: -f*x'
force b: [0, -m*g]
thrust y: mu*u
impact phi: -c*phi'
outflow b: relative_velocity [-u, 0], rate mu
inflow b: velocity [0, 0]
inflow b
check x'' = -w^2*x
";
