//! Components (docs/components.md): `use` and `parameter` parsed, expanded into one
//! composed model (qualified names, bindings, ports, defaults, tags, nested components),
//! the composed model deriving what the hand-written one does, and each bad use a
//! diagnostic at the use site.

use std::path::{Path, PathBuf};
use varmass_symbolic::compose::{compose, Composition};
use varmass_symbolic::mechanics::{Derivation, Outputs, Parameters};
use varmass_symbolic::parse::ast::StatementKind;
use varmass_symbolic::parse::{parse_system, Diagnostic};
use varmass_symbolic::{derive_in, derive_source};

/// A test's scratch directory, removed when the test is done with it (passed or failed).
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A fresh directory holding `files` (name, text), for one test.
fn directory(test: &str, files: &[(&str, &str)]) -> Scratch {
    let dir = std::env::temp_dir().join(format!("varmass-compose-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().expect("a directory")).expect("creates it");
        std::fs::write(path, text).expect("writes the file");
    }
    Scratch(dir)
}

/// The model `main.vms` of `dir` composed.
fn composed(dir: &Path) -> Result<Composition, Vec<Diagnostic>> {
    let path = dir.join("main.vms");
    let source = std::fs::read_to_string(&path).expect("reads main.vms");
    let ast = parse_system(&source).expect("main.vms parses");
    compose(&source, ast, &path)
}

/// `main.vms` composed and derived (parameters inferred), diagnostics located.
fn derived(dir: &Path) -> Result<Derivation, Vec<Diagnostic>> {
    let composition = composed(dir)?;
    derive_in(&composition.ast, Parameters::Inferred, Outputs::FULL, dir)
        .map_err(|errors| composition.locate(errors))
}

/// The one diagnostic of composing `main.vms`.
fn single_error(dir: &Path) -> Diagnostic {
    let errors = composed(dir).expect_err("a bad use");
    assert_eq!(errors.len(), 1, "{errors:#?}");
    errors.into_iter().next().expect("one")
}

/// The names `let`, `mass`, `outflow`… of the composed statements, for comparing shapes.
fn names(composition: &Composition) -> Vec<String> {
    composition
        .ast
        .statements
        .iter()
        .map(|s| match &s.kind {
            StatementKind::Let { name, .. } => format!("let {}", name.node),
            StatementKind::Parameter(p) => format!("parameter {} = {}", p.name.node, p.value),
            StatementKind::Force(l) => format!("force {}", l.target.node),
            StatementKind::Outflow(f) => format!("outflow {}", f.body.node),
            StatementKind::Units(u) => {
                let names: Vec<&str> = u.iter().map(|e| e.name.node.as_str()).collect();
                format!("units {}", names.join(" "))
            }
            StatementKind::Mass(m) => format!("mass {}", m.name.node),
            StatementKind::Coordinates(c) => format!("coordinates {}", c[0].node),
            StatementKind::Body(b) => format!("body {} {}", b.name.node, b.mass.node),
            other => format!("{other:?}").chars().take(12).collect(),
        })
        .collect()
}

const PUSH: &str = "\
# a constant push F along the axis, on the body `on`
parameter F = 100
let half = F/2
force on: [half + half]
";

/// A directory with the component `lib/push.vms` and a `main.vms` of a body `b` on `y`
/// followed by `rest` (its uses).
fn with_push(test: &str, rest: &str) -> Scratch {
    let main = format!("coordinates y\nmass m = m0\nbody b: mass m, position [y]\n{rest}");
    directory(test, &[("lib/push.vms", PUSH), ("main.vms", &main)])
}

#[test]
fn use_and_parameter_parse() {
    let source = "parameter g0 = -9.5e-1\nuse \"lib/a.vms\" as left: F = 2*F0, on = rocket";
    let ast = parse_system(source).expect("parses");
    let StatementKind::Parameter(p) = &ast.statements[0].kind else {
        panic!("{:?}", ast.statements[0]);
    };
    assert_eq!((p.name.node.as_str(), p.value), ("g0", -0.95));
    let StatementKind::Use(u) = &ast.statements[1].kind else {
        panic!("{:?}", ast.statements[1]);
    };
    assert_eq!(u.file.node, "lib/a.vms");
    assert_eq!(&source[u.file.span.start..u.file.span.end], "\"lib/a.vms\"");
    assert_eq!(u.instance.node, "left");
    let bound: Vec<&str> = u.bindings.iter().map(|b| b.name.node.as_str()).collect();
    assert_eq!(bound, ["F", "on"]);
    assert_eq!(
        &source[u.bindings[0].value.span.start..u.bindings[0].value.span.end],
        "2*F0"
    );
}

#[test]
fn a_default_must_be_a_number_and_a_use_needs_as() {
    let errors = parse_system("parameter g = 2*a").expect_err("not a number");
    assert_eq!(
        errors[0].message,
        "a parameter's default must be a finite number (in SI units)"
    );
    assert_eq!((errors[0].span.line, errors[0].span.column), (1, 15));
    let errors = parse_system("use \"a.vms\" left").expect_err("no `as`");
    assert_eq!(errors[0].message, "expected `as` after `\"a.vms\"`");
}

#[test]
fn two_instances_are_qualified_apart_and_act_on_the_users_body() {
    let dir = with_push(
        "two",
        "use \"lib/push.vms\" as left: on = b, F = 3*k\n\
         [wind] use \"lib/push.vms\" as right: on = b\n",
    );
    let composition = composed(&dir).expect("composes");
    assert_eq!(
        names(&composition),
        [
            "coordinates y",
            "mass m",
            "body b m",
            "let left_F",
            "let left_half",
            "force b",
            "parameter right_F = 100",
            "let right_half",
            "force b",
        ]
    );
    // The tags of a `use` are every spliced statement's.
    let tagged = composition
        .ast
        .statements
        .iter()
        .filter(|s| !s.tags.is_empty())
        .count();
    assert_eq!(tagged, 3);
    assert_eq!(composition.defaults(), vec![("right_F".to_string(), 100.0)]);
}

#[test]
fn two_pushes_derive_the_equation_of_one_push_of_the_sum() {
    // By hand: m0 y'' = F_left + F_right = 3k + 100 (the right push keeps its default when
    // it is made a definition, as under the macro without a field).
    let dir = with_push(
        "sum",
        "use \"lib/push.vms\" as left: on = b, F = 3*k\n\
         use \"lib/push.vms\" as right: on = b\n\
         check y'' = (3*k + 100)/m0\ncheck Q_y = 3*k + 100\n",
    );
    let composition = composed(&dir).expect("composes");
    // Under the macro (declared parameters) a default without a field is a definition.
    let fields = ["m0", "k"].map(String::from).to_vec();
    let declared = Parameters::Declared(fields);
    let derivation = derive_in(&composition.ast, declared, Outputs::FULL, &dir)
        .map_err(|e| composition.locate(e))
        .expect("the checks hold");
    let parameters: Vec<&str> = derivation
        .parameters
        .iter()
        .map(|(n, _)| n.as_str())
        .collect();
    assert_eq!(parameters, ["m0", "k"]);
    // Kept a parameter (parameters inferred, as by the command line tool), the default is
    // one more parameter of the derivation.
    let main = std::fs::read_to_string(dir.join("main.vms")).expect("reads");
    std::fs::write(dir.join("main.vms"), main.replace("100", "right_F")).expect("writes");
    let kept = derived(&dir).expect("derives");
    let parameters: Vec<&str> = kept.parameters.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(parameters, ["m0", "k", "right_F"]);
}

#[test]
fn the_twin_motor_rocket_derives_as_the_rocket_burning_twice_as_fast() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let path = root.join("tests/data/components/twin_motor_rocket.vms");
    let source = std::fs::read_to_string(&path).expect("reads the model");
    let composition = compose(&source, parse_system(&source).expect("parses"), &path);
    let composition = composition.expect("composes");
    let twin = derive_in(&composition.ast, Parameters::Inferred, Outputs::FULL, &root)
        .expect("its checks hold");
    // models/rocket.vms with mu → 2 mu, written here: the same momentum rate and mass rate.
    let one = derive_source(
        "coordinates y\nmass m: state, rate -2*mu\nbody rocket: mass m, position [y]\n\
         potential m*g*y\noutflow rocket: rate 2*mu, relative_velocity [-u_e]",
        Parameters::Inferred,
    )
    .expect("derives");
    // ṗ, ṁ and R1 of both at one point (p = m ẏ): the definitions `left_mu = mu` are
    // inlined, so both evaluate the same arithmetic up to the order of terms.
    let values = [
        ("y", 120.0),
        ("m", 800.0),
        ("mu", 10.0),
        ("u_e", 2500.0),
        ("g", 9.81),
    ];
    let rates = |d: &Derivation| {
        let mut env = vec![f64::NAN; 256];
        for (name, value) in values {
            let symbol = d.pool.symbols().lookup(name).expect("a symbol");
            env[symbol.index()] = value;
        }
        env[d.coordinates[0].velocity.index()] = 35.0;
        let roots = [d.momentum_rate[0], d.mass_rates[0], d.reactive_thrust[0]];
        roots.map(|root| d.pool.eval(root, &env))
    };
    let (twin, one) = (rates(&twin), rates(&one));
    // By hand: ṗ = 2 μ u_e − m g − 2 μ ẏ = 50000 − 7848 − 700, ṁ = −20, R1 = −50000.
    assert_eq!(one, [41452.0, -20.0, -50000.0]);
    for (a, b) in twin.iter().zip(one) {
        assert!((a - b).abs() <= 1e-15 * b.abs(), "{twin:?} against {one:?}");
    }
}

#[test]
fn an_unknown_file_is_a_diagnostic_at_its_name() {
    let dir = directory(
        "unknown",
        &[("main.vms", "coordinates y\nuse \"lib/nothing.vms\" as a\n")],
    );
    let d = single_error(&dir);
    assert!(
        d.message
            .starts_with("cannot read the component `lib/nothing.vms`"),
        "{d:?}"
    );
    assert_eq!((d.span.line, d.span.column), (2, 5));
}

#[test]
fn a_missing_binding_is_a_diagnostic_at_the_instance() {
    let dir = directory(
        "missing",
        &[
            ("lib/push.vms", PUSH),
            ("main.vms", "coordinates y\nuse \"lib/push.vms\" as left\n"),
        ],
    );
    let d = single_error(&dir);
    assert_eq!(
        d.message,
        "`left` does not bind `on`, which the component `lib/push.vms` reads at 4:7"
    );
    assert_eq!((d.span.line, d.span.column), (2, 23));
}

#[test]
fn a_binding_of_the_wrong_dimension_is_a_diagnostic_at_the_binding() {
    let push = format!("{PUSH}units F: N\n");
    let dir = directory(
        "dimension",
        &[
            ("lib/push.vms", &push),
            (
                "main.vms",
                "coordinates y\nunits y: m, m0: kg\nmass m = m0\nbody b: mass m, position [y]\n\
                 use \"lib/push.vms\" as left: on = b, F = m0\n",
            ),
        ],
    );
    let errors = derived(&dir).expect_err("a mass is no force");
    assert_eq!(errors.len(), 1, "{errors:#?}");
    let d = &errors[0];
    assert_eq!(
        d.message,
        "definition of `left_F`: m0 has kg, expected a force, kg·m/s² (the unit `units` gives \
         `left_F`)"
    );
    // The caret is under the bound value, in the using file.
    assert_eq!((d.span.line, d.span.column), (5, 41));
}

#[test]
fn two_instances_with_one_name_are_a_diagnostic_at_the_second() {
    let dir = with_push(
        "twice",
        "use \"lib/push.vms\" as left: on = b\nuse \"lib/push.vms\" as left: on = b\n",
    );
    let d = single_error(&dir);
    assert_eq!(
        d.message,
        "two instances named `left`: each use of a component needs its own name"
    );
    assert_eq!((d.span.line, d.span.column), (5, 23));
}

#[test]
fn a_circular_use_is_a_diagnostic_at_the_use_site() {
    let dir = directory(
        "circle",
        &[
            ("a.vms", "use \"b.vms\" as inner\n"),
            ("b.vms", "use \"a.vms\" as back\n"),
            ("main.vms", "coordinates y\nuse \"a.vms\" as outer\n"),
        ],
    );
    let d = single_error(&dir);
    // At main.vms's use, naming the chain a → b → a.
    assert_eq!((d.span.line, d.span.column), (2, 1));
    assert!(d.message.starts_with("in component `outer` (a.vms:1:1): in component `inner` (b.vms:1:5): circular use of `a.vms`"), "{}", d.message);
    let dir = directory(
        "itself",
        &[("main.vms", "coordinates y\nuse \"main.vms\" as me\n")],
    );
    assert_eq!(single_error(&dir).message, "circular use of `main.vms`");
}

#[test]
fn a_mistake_inside_a_component_names_its_file_and_line_at_the_use_site() {
    let dir = directory(
        "inside",
        &[
            ("lib/bad.vms", "# a typo on line 2\nforce on: [k*+]\n"),
            ("lib/unknown.vms", "force on: [F]\nforce on: [sinn(F)]\n"),
            (
                "main.vms",
                "coordinates y\nmass m = m0\nbody b: mass m, position [y]\n\
                 use \"lib/unknown.vms\" as u: on = b, F = 1\n",
            ),
            (
                "syntax.vms",
                "coordinates y\nuse \"lib/bad.vms\" as bad: on = y\n",
            ),
        ],
    );
    let errors = derived(&dir).expect_err("an unknown function");
    assert_eq!(errors.len(), 1, "{errors:#?}");
    assert!(
        errors[0]
            .message
            .starts_with("in component `u` (lib/unknown.vms:2:12): unknown function `sinn`"),
        "{}",
        errors[0].message
    );
    assert_eq!(errors[0].span.line, 4);
    let help = errors[0].help.as_deref().unwrap_or_default();
    assert!(help.contains("--> lib/unknown.vms:2:12"), "{help}");
    assert!(help.contains("force on: [sinn(F)]"), "{help}");
    // A syntax error of the component, the same way.
    let source = std::fs::read_to_string(dir.join("syntax.vms")).expect("reads");
    let errors = compose(
        &source,
        parse_system(&source).expect("parses"),
        &dir.join("syntax.vms"),
    )
    .expect_err("a syntax error");
    assert!(
        errors[0]
            .message
            .starts_with("in component `bad` (lib/bad.vms:2:14): expected an expression after `*`"),
        "{}",
        errors[0].message
    );
    assert_eq!(errors[0].span.line, 2);
}

#[test]
fn bindings_of_names_the_component_does_not_read_and_ports_bound_to_expressions_are_refused() {
    let dir = with_push("refused", "use \"lib/push.vms\" as left: on = 2*b, G = 1\n");
    let errors = composed(&dir).expect_err("two bad bindings");
    let messages: Vec<&str> = errors.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(messages.len(), 2, "{messages:?}");
    assert!(
        messages[0].starts_with("`on` is what the component acts on"),
        "{}",
        messages[0]
    );
    assert_eq!(
        messages[1],
        "the component `lib/push.vms` has no parameter or port `G` to bind"
    );
    assert_eq!(errors[1].help.as_deref(), Some("it reads `F`, `on`"));
}

#[test]
fn nested_components_are_qualified_by_both_instance_names() {
    let dir = directory(
        "nested",
        &[
            ("lib/push.vms", PUSH),
            ("lib/pair.vms", "use \"push.vms\" as one: on = on, F = f\nuse \"push.vms\" as two: on = on, F = f\n"),
            (
                "main.vms",
                "coordinates y\nmass m = m0\nbody b: mass m, position [y]\n\
                 use \"lib/pair.vms\" as pair: on = b, f = 2\ncheck Q_y = 4\n",
            ),
        ],
    );
    let composition = composed(&dir).expect("composes");
    let lets: Vec<String> = names(&composition)
        .into_iter()
        .filter(|n| n.starts_with("let"))
        .collect();
    assert_eq!(
        lets,
        [
            "let pair_f",
            "let pair_one_F",
            "let pair_one_half",
            "let pair_two_F",
            "let pair_two_half"
        ]
    );
    derived(&dir).expect("Q_y = 2 pushes of 2");
}

#[test]
fn a_parameter_declared_twice_is_a_diagnostic() {
    let dir = directory(
        "declared",
        &[("main.vms", "coordinates y\nlet g = 1\nparameter g = 2\n")],
    );
    let d = single_error(&dir);
    assert_eq!(d.message, "`g` is declared twice");
    assert_eq!((d.span.line, d.span.column), (3, 11));
}
