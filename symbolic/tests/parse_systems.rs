//! Whole systems parse to the expected statements: the paper's sled in both forms, a
//! rocket, every statement form, separators and comments, and exact spans.

mod parse_support;

use parse_support::*;
use varmass_symbolic::parse::ast::{
    Attitude, FlowVelocity, Frame, InertiaValue, Load, LoadValue, MassLaw, StatementKind,
    SystemAst, VectorNode,
};
use varmass_symbolic::parse::{parse_system, Span};

fn parse(source: &str) -> SystemAst {
    match parse_system(source) {
        Ok(system) => system,
        Err(errors) => panic!(
            "{}",
            errors
                .iter()
                .map(|e| e.render(source))
                .collect::<Vec<_>>()
                .join("\n")
        ),
    }
}

fn vector(v: &VectorNode) -> String {
    let parts: Vec<String> = v.node.iter().map(show).collect();
    format!("[{}]", parts.join(", "))
}

/// A load's value with its frame and point: `body [0, F] at [0, -l]`.
fn load_value(l: &Load) -> String {
    let value = match &l.value {
        LoadValue::Scalar(e) => show(e),
        LoadValue::Vector(v) if l.frame == Frame::Body => format!("body {}", vector(v)),
        LoadValue::Vector(v) => vector(v),
    };
    match &l.at {
        Some(at) => format!("{value} at {}", vector(at)),
        None => value,
    }
}

/// A span-free summary of a statement, one line, for comparing whole systems.
fn summary(kind: &StatementKind) -> String {
    match kind {
        StatementKind::Coordinates(names) => {
            let names: Vec<&str> = names.iter().map(|n| n.node.as_str()).collect();
            format!("coordinates {}", names.join(", "))
        }
        StatementKind::Mass(decl) | StatementKind::Inertia(decl) => {
            let head = if matches!(kind, StatementKind::Mass(_)) {
                "mass"
            } else {
                "inertia"
            };
            match &decl.law {
                MassLaw::Law(law) => format!("{head} {} = {}", decl.name.node, show(law)),
                MassLaw::State { rate } => {
                    format!("{head} {}: state, rate {}", decl.name.node, show(rate))
                }
            }
        }
        StatementKind::Let { name, value } => format!("let {} = {}", name.node, show(value)),
        StatementKind::Body(b) => format!(
            "body {}: mass {}, position {}",
            b.name.node,
            b.mass.node,
            vector(&b.position)
        ),
        StatementKind::Kinetic(e) => format!("kinetic {}", show(e)),
        StatementKind::Potential(e) => format!("potential {}", show(e)),
        StatementKind::Lagrangian(e) => format!("lagrangian {}", show(e)),
        StatementKind::Force(l) | StatementKind::Thrust(l) | StatementKind::Impact(l) => {
            let head = match kind {
                StatementKind::Force(_) => "force",
                StatementKind::Thrust(_) => "thrust",
                _ => "impact",
            };
            format!("{head} {}: {}", l.target.node, load_value(l))
        }
        StatementKind::Torque(l) => format!("torque {}: {}", l.target.node, load_value(l)),
        StatementKind::Rigid(r) => {
            let inertia = match &r.inertia {
                InertiaValue::Scalar(e) => show(e),
                InertiaValue::Principal(v) => vector(v),
                InertiaValue::Tensor(rows) => {
                    let rows: Vec<String> = rows.node.iter().map(vector).collect();
                    format!("[{}]", rows.join(", "))
                }
            };
            let attitude = match &r.attitude {
                Attitude::Angle(e) => format!("angle {}", show(e)),
                Attitude::Orientation { sequence, angles } => {
                    let angles: Vec<String> = angles.iter().map(show).collect();
                    format!("orientation {}({})", sequence.node, angles.join(", "))
                }
            };
            let centre = r
                .centre
                .as_ref()
                .map_or(String::new(), |c| format!(", centre {}", vector(c)));
            format!(
                "rigid {}: mass {}, inertia {inertia}, position {}, {attitude}{centre}",
                r.name.node,
                r.mass.node,
                vector(&r.position)
            )
        }
        StatementKind::Outflow(f) | StatementKind::Inflow(f) => {
            let head = if matches!(kind, StatementKind::Outflow(_)) {
                "outflow"
            } else {
                "inflow"
            };
            let mut options = Vec::new();
            if let Some(rate) = &f.rate {
                options.push(format!("rate {}", show(rate)));
            }
            let frame = if f.frame == Frame::Body { "body " } else { "" };
            match &f.velocity {
                Some(FlowVelocity::Absolute(v)) => {
                    options.push(format!("velocity {frame}{}", vector(v)))
                }
                Some(FlowVelocity::Relative(v)) => {
                    options.push(format!("relative_velocity {frame}{}", vector(v)))
                }
                None => {}
            }
            if let Some(at) = &f.at {
                options.push(format!("at {}", vector(at)));
            }
            format!("{head} {}: {}", f.body.node, options.join(", "))
        }
        StatementKind::Check { lhs, rhs, .. } => format!("check {} = {}", show(lhs), show(rhs)),
        StatementKind::Units(entries) => {
            let entries: Vec<String> = entries
                .iter()
                .map(|e| format!("{}: {}", e.name.node, show(&e.unit)))
                .collect();
            format!("units {}", entries.join(", "))
        }
        StatementKind::Table(t) => format!(
            "table {}({}) = {:?}, {:?}, outside {:?}",
            t.name.node, t.parameter.node, t.file.node, t.interpolation, t.outside
        ),
        StatementKind::Input(i) => {
            let arguments: Vec<String> = i
                .arguments
                .iter()
                .map(|(n, p)| format!("{}{}", n.node, "'".repeat(usize::from(*p))))
                .collect();
            let every = i.every.as_ref().map(|e| format!(" every {}", e.node));
            format!(
                "input {}({}){}",
                i.name.node,
                arguments.join(", "),
                every.unwrap_or_default()
            )
        }
        StatementKind::Use(u) => {
            let bindings: Vec<String> = u
                .bindings
                .iter()
                .map(|b| format!("{} = {}", b.name.node, show(&b.value)))
                .collect();
            format!(
                "use {:?} as {}: {}",
                u.file.node,
                u.instance.node,
                bindings.join(", ")
            )
        }
        StatementKind::Parameter(p) => format!("parameter {} = {:?}", p.name.node, p.value),
    }
}

fn summaries(source: &str) -> Vec<String> {
    parse(source)
        .statements
        .iter()
        .map(|s| summary(&s.kind))
        .collect()
}

#[test]
fn paper_sled_parses_to_the_expected_statements() {
    assert_eq!(
        summaries(SLED_PAPER),
        [
            "coordinates x",
            "mass m = (m0 + (c * x))",
            "lagrangian ((((1 / 2) * m) * (x' ^ 2)) + (((m * g) * x) * sin(theta)))",
            "force x: ((((-f_d) * m) * g) * cos(theta))",
            "impact x: ((-c) * (x' ^ 2))",
        ]
    );
}

#[test]
fn body_sled_parses_to_the_expected_statements() {
    assert_eq!(
        summaries(SLED_BODY),
        [
            "coordinates x",
            "mass m = (m0 + (c * x))",
            "body sled: mass m, position [x]",
            "potential ((((-m) * g) * x) * sin(theta))",
            "force sled: [((((-f_d) * m) * g) * cos(theta))]",
            "inflow sled: velocity [0]",
        ]
    );
}

#[test]
fn rocket_parses_to_the_expected_statements() {
    assert_eq!(
        summaries(ROCKET),
        [
            "coordinates y",
            "mass m: state, rate (-mu)",
            "body rocket: mass m, position [y]",
            "potential ((m * g) * y)",
            "outflow rocket: rate mu, relative_velocity [(-u_e)]",
        ]
    );
}

#[test]
fn every_statement_form_parses() {
    assert_eq!(
        summaries(EVERY_STATEMENT),
        [
            "coordinates x, y, phi",
            "mass m = (m0 + (c * x))",
            "mass q: state, rate (-mu)",
            "inertia J = ((m * (r ^ 2)) / 2)",
            "inertia K: state, rate k",
            "let w = sqrt((g / l))",
            "body b: mass m, position [x, y, 0]",
            "kinetic (((1 / 2) * J) * (phi' ^ 2))",
            "potential ((m * g) * y)",
            "lagrangian ((((-1) / 2) * k) * (phi ^ 2))",
            "force x: ((-f) * x')",
            "force b: [0, ((-m) * g)]",
            "thrust y: (mu * u)",
            "impact phi: ((-c) * phi')",
            "outflow b: rate mu, relative_velocity [(-u), 0]",
            "inflow b: velocity [0, 0]",
            "inflow b: ",
            "check x'' = ((-(w ^ 2)) * x)",
        ]
    );
}

#[test]
fn scalar_and_vector_loads_are_told_apart() {
    let system = parse("force x: 1\nthrust b: [1, 2]\nimpact x: (1)");
    let values: Vec<bool> = system
        .statements
        .iter()
        .map(|s| match &s.kind {
            StatementKind::Force(l) | StatementKind::Thrust(l) | StatementKind::Impact(l) => {
                matches!(l.value, LoadValue::Vector(_))
            }
            other => panic!("unexpected {other:?}"),
        })
        .collect();
    assert_eq!(values, [false, true, false]);
}

#[test]
fn flow_options_come_in_any_order_and_may_be_absent() {
    assert_eq!(
        summaries("outflow r: relative_velocity [1], rate 2\ninflow s: rate 3\ninflow s: velocity [0]\noutflow r"),
        [
            "outflow r: rate 2, relative_velocity [1]",
            "inflow s: rate 3",
            "inflow s: velocity [0]",
            "outflow r: ",
        ]
    );
}

#[test]
fn semicolons_newlines_comments_and_blank_lines_separate_statements_alike() {
    let lines = "coordinates x\nmass m = 2\nkinetic m*x'^2/2\n";
    let semicolons = "coordinates x; mass m = 2; kinetic m*x'^2/2";
    let messy = "\n\n   # a comment line\n\t coordinates x # trailing comment\r\n;;\nmass m = 2 ;\n\n  kinetic m*x'^2/2   # end\n   \n";
    let expected = summaries(lines);
    assert_eq!(expected.len(), 3);
    assert_eq!(summaries(semicolons), expected);
    assert_eq!(summaries(messy), expected);
    assert!(parse("").statements.is_empty());
    assert!(parse("  # nothing but a comment\n\n;\n")
        .statements
        .is_empty());
}

#[test]
fn newlines_continue_a_statement_inside_parentheses_and_brackets() {
    let source = "kinetic (1/2*m*x'^2 +   # translation\n   1/2*J*phi'^2)\nforce b: [\n  1,\n  2\n]\nlet v = max(a,\n b)";
    assert_eq!(
        summaries(source),
        [
            "kinetic ((((1 / 2) * m) * (x' ^ 2)) + (((1 / 2) * J) * (phi' ^ 2)))",
            "force b: [1, 2]",
            "let v = max(a, b)",
        ]
    );
    let system = parse(source);
    assert_eq!(system.statements[1].span.line, 3);
    assert_eq!(
        text(source, system.statements[1].span),
        "force b: [\n  1,\n  2\n]"
    );
}

#[test]
fn keywords_are_names_inside_expressions() {
    assert_eq!(
        summaries("kinetic mass*body + check\nlet force = t"),
        ["kinetic ((mass * body) + check)", "let force = t"]
    );
}

#[test]
fn statement_spans_cover_keyword_to_end_of_text() {
    let source = "coordinates x   # c\n  mass m = m0 + c*x ; let w = 2\n";
    let system = parse(source);
    let spans: Vec<(&str, u32, u32)> = system
        .statements
        .iter()
        .map(|s| (text(source, s.span), s.span.line, s.span.column))
        .collect();
    assert_eq!(
        spans,
        [
            ("coordinates x", 1, 1),
            ("mass m = m0 + c*x", 2, 3),
            ("let w = 2", 2, 23),
        ]
    );
}

#[test]
fn sled_spans_are_exact() {
    let system = parse(SLED_PAPER);
    let StatementKind::Lagrangian(l) = &system.statements[2].kind else {
        panic!("not a lagrangian: {:?}", system.statements[2].kind)
    };
    assert_eq!(text(SLED_PAPER, l.span), "1/2*m*x'^2 + m*g*x*sin(theta)");
    assert_eq!((l.span.line, l.span.column), (4, 12));
    // The node for `sin(theta)` and its name.
    let call = nodes(l)
        .into_iter()
        .find(|n| show(n) == "sin(theta)")
        .expect("a call node");
    assert_eq!(text(SLED_PAPER, call.span), "sin(theta)");
    assert_eq!((call.span.line, call.span.column), (4, 31));

    let system = parse(SLED_BODY);
    let StatementKind::Body(body) = &system.statements[2].kind else {
        panic!("not a body")
    };
    assert_eq!(text(SLED_BODY, body.name.span), "sled");
    assert_eq!(text(SLED_BODY, body.mass.span), "m");
    assert_eq!(text(SLED_BODY, body.position.span), "[x]");
    assert_eq!(
        body.position.span,
        Span {
            start: body.position.span.start,
            end: body.position.span.end,
            line: 4,
            column: 29
        }
    );
    let StatementKind::Inflow(flow) = &system.statements[5].kind else {
        panic!("not an inflow")
    };
    let Some(FlowVelocity::Absolute(v)) = &flow.velocity else {
        panic!("no velocity")
    };
    assert_eq!(text(SLED_BODY, v.span), "[0]");
    assert_eq!(
        text(SLED_BODY, system.statements[5].span),
        "inflow sled: velocity [0]"
    );
}

#[test]
fn every_span_of_every_example_is_exact_text_that_reparses_to_its_node() {
    for source in [SLED_PAPER, SLED_BODY, ROCKET, EVERY_STATEMENT] {
        for statement in parse(source).statements {
            assert_span_valid(source, statement.span);
            // The statement's own text is a system of that one statement.
            let alone = parse(text(source, statement.span));
            assert_eq!(alone.statements.len(), 1);
            assert_eq!(summary(&alone.statements[0].kind), summary(&statement.kind));
            for root in statement_expressions(&statement) {
                for node in nodes(root) {
                    assert_span_valid(source, node.span);
                    let reparsed =
                        varmass_symbolic::parse::parse_expression(text(source, node.span))
                            .unwrap_or_else(|e| panic!("{:?}: {e}", text(source, node.span)));
                    assert_eq!(show(&reparsed), show(node));
                }
            }
        }
    }
}

#[test]
fn body_options_come_in_any_order() {
    assert_eq!(
        summaries("body b: position [x, y], mass m"),
        ["body b: mass m, position [x, y]"]
    );
}

/// The rigid-body forms of docs/dsl.md#rigid, each exactly as the design brief writes them,
/// parse to what they say; `body` stays a name where no `[` follows it.
#[test]
fn rigid_forms_parse() {
    let source = "coordinates x, y, th
rigid rocket: mass m, inertia J, position [x, y], angle th
rigid craft: mass m, inertia [A, B, C], position [x, y, z], orientation zyx(psi, th, phi)
rigid rocket: mass m, inertia J, position [x, y], angle th, centre [0, c]
force rocket: body [0, F] at [0, -l]
torque rocket: tau
outflow rocket: rate mu, at [0, -l], relative_velocity body [0, -u_e]
rigid top: orientation zxz(a, b, g), inertia [[P, Q, 0], [Q, R, 0], [0, 0, S]], position [0, 0, 0], mass m
force x: body*2
torque craft: body [1, 0, 0]
";
    let expected = [
        "coordinates x, y, th",
        "rigid rocket: mass m, inertia J, position [x, y], angle th",
        "rigid craft: mass m, inertia [A, B, C], position [x, y, z], orientation zyx(psi, th, phi)",
        "rigid rocket: mass m, inertia J, position [x, y], angle th, centre [0, c]",
        "force rocket: body [0, F] at [0, (-l)]",
        "torque rocket: tau",
        "outflow rocket: rate mu, relative_velocity body [0, (-u_e)], at [0, (-l)]",
        "rigid top: mass m, inertia [[P, Q, 0], [Q, R, 0], [0, 0, S]], position [0, 0, 0], orientation zxz(a, b, g)",
        "force x: (body * 2)",
        "torque craft: body [1, 0, 0]",
    ];
    let system = parse(source);
    let found: Vec<String> = system.statements.iter().map(|s| summary(&s.kind)).collect();
    assert_eq!(found, expected);
}

/// Each malformed rigid form is one diagnostic naming what is wrong.
#[test]
fn rigid_form_errors() {
    let cases = [
        (
            "rigid r: mass m, position [x, y], angle th",
            "missing `inertia` for rigid body `r`",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y]",
            "missing `angle` or `orientation`",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y], angle th, orientation zyx(a, b, c)",
            "`orientation` and `angle` cannot both be given",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y, z], orientation zyy(a, b, c)",
            "unknown Euler sequence `zyy`",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y, z], orientation zyx(a, b)",
            "takes 3 angles, found 2",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y, z], orientation a",
            "an orientation is an Euler sequence",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y, z], orientation quaternion(a, b, c)",
            "`quaternion` takes 4 components, found 3",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y, z], orientation quaternoin(a, b, c, d)",
            "unknown Euler sequence `quaternoin`",
        ),
        (
            "rigid r: mass m, inertai J, position [x, y], angle th",
            "unknown option `inertai` for rigid",
        ),
        ("force r: body [1, 0] at", "expected a vector"),
    ];
    for (source, message) in cases {
        let errors = parse_system(source).expect_err(source);
        assert_eq!(errors.len(), 1, "{source}: {errors:?}");
        assert!(
            errors[0].message.contains(message),
            "{source}: {}",
            errors[0].message
        );
    }
}
