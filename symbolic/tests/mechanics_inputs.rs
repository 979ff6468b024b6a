//! `input` statements in the symbolic engine (docs/inputs.md): parsing, every misuse a
//! diagnostic at its text, calls lowered to the opaque input, its partials only in the
//! Jacobian, and the equations never differentiating it.

use varmass_symbolic::parse::ast::StatementKind;
use varmass_symbolic::parse::parse_system;
use varmass_symbolic::Diagnostic;
use varmass_symbolic::{
    derive_for,
    mechanics::{Derivation, Outputs, Parameters},
};

fn derive(source: &str) -> Result<Derivation, Vec<Diagnostic>> {
    let ast = parse_system(source)?;
    derive_for(&ast, Parameters::Inferred, Outputs::FULL)
}

#[track_caller]
fn error(source: &str, message: &str, line: u32, column: u32) {
    let errors = match derive(source) {
        Ok(_) => panic!("expected a diagnostic for:\n{source}"),
        Err(e) => e,
    };
    let found = errors.iter().find(|e| e.message.contains(message));
    let Some(found) = found else {
        let all: Vec<String> = errors.iter().map(|e| e.render(source)).collect();
        panic!(
            "no diagnostic containing {message:?}; got:\n{}",
            all.join("\n")
        );
    };
    assert_eq!(
        (found.span.line, found.span.column),
        (line, column),
        "{}",
        found.render(source)
    );
}

/// The hovering rocket of tests/inputs_hover.rs: thrust m·u, u the commanded acceleration.
const HOVER: &str = "coordinates y
input u(t, y, y')
mass m: state, rate -m*u(t, y, y')/u_e
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate m*u(t, y, y')/u_e, relative_velocity [-u_e]";

#[test]
fn the_statement_parses_with_and_without_a_period() {
    let ast = parse_system("coordinates y\ninput u(t, y, y') every 0.01\ninput w(y)").unwrap();
    let inputs: Vec<_> = ast
        .statements
        .iter()
        .filter_map(|s| match &s.kind {
            StatementKind::Input(i) => Some(i),
            _ => None,
        })
        .collect();
    assert_eq!(inputs.len(), 2);
    let arguments: Vec<(&str, u8)> = inputs[0]
        .arguments
        .iter()
        .map(|(n, p)| (n.node.as_str(), *p))
        .collect();
    assert_eq!(arguments, [("t", 0), ("y", 0), ("y", 1)]);
    assert_eq!(
        inputs[0].every.as_ref().map(|e| e.node.as_str()),
        Some("0.01")
    );
    assert_eq!(inputs[1].every, None);
}

#[test]
fn misuses_are_diagnostics_at_their_text() {
    error(
        "coordinates y\ninput u(t, y'')",
        "`y''`: an input's argument",
        2,
        12,
    );
    error(
        "coordinates y\ninput u(t, z)\nforce y: u(t, y)",
        "`z` cannot be an argument",
        2,
        12,
    );
    error("coordinates y\ninput u(t, y'')", "`y''`", 2, 12);
    error(
        "coordinates y\ninput u(t, y)\nforce y: u(t)",
        "`u` takes 2 arguments, found 1",
        3,
        10,
    );
    error(
        "coordinates y\ninput u(t)\nforce y: u",
        "`u` is an input",
        3,
        10,
    );
    error(
        "coordinates y\ninput u(t) every 0\nforce y: u(t)",
        "not a positive number",
        2,
        18,
    );
    error(
        "coordinates y\ninput u(t) every 1e-320\nforce y: u(t)",
        "below the smallest normal f64",
        2,
        18,
    );
    error(
        "coordinates y\ninput u(t) every -1\nforce y: u(t)",
        "the sample period in seconds",
        2,
        18,
    );
    error(
        "coordinates y\ninput u(t) every x\nforce y: u(t)",
        "the sample period in seconds",
        2,
        18,
    );
    // A sampled input's value is held from the sample, taken at its declared arguments.
    error(
        "coordinates y\ninput u(t, y) every 0.01\nforce y: u(t, 2*y)",
        "sampled input `u` is called with its declared arguments only: `u(t, y)`",
        3,
        10,
    );
    error(
        "coordinates y\ninput u(t) every 0.01\nmass m = 1\nbody b: mass m, position [y]\npotential u(t)*y",
        "sampled input `u` is inside a position, a mass law or an energy",
        2,
        7,
    );
    error(
        "coordinates y\ninput u(t, t)\nforce y: u(t, t)",
        "names `t` twice",
        2,
        12,
    );
    error("coordinates y\ninput y(t)", "`y` is declared twice", 2, 7);
    error("coordinates y\ninput u(t\n", "expected `,` or `)`", 2, 10);
}

#[test]
fn an_input_the_equations_would_differentiate_is_refused() {
    // In a position: the velocity of the body needs ∂u/∂t.
    let moved = "coordinates x\ninput u(t)\nmass m = m0\nbody b: mass m, position [x + u(t)]";
    error(moved, "would differentiate input `u`", 2, 7);
    // In the potential: the generalized force −∂V/∂x needs ∂u/∂x.
    let energy = "coordinates x\ninput u(x)\nkinetic 1/2*m0*x'^2\npotential u(x)";
    error(energy, "would differentiate input `u`", 2, 7);
}

#[test]
fn the_equations_call_the_input_and_the_jacobian_its_partials() {
    let d = derive(HOVER).unwrap();
    assert_eq!(d.inputs.len(), 1);
    assert_eq!(d.inputs[0].rust_argument(2), "y_dot");
    // ṁ = −m u/u_e, with the call as written.
    let rate = d.pool.display(d.mass_rates[0]).to_string();
    assert!(rate.contains("u(t, y, y')"), "{rate}");
    // ∂ṁ/∂ẏ = −m ∂_y'u / u_e: the partial with respect to the third argument.
    let j = d.jacobian.as_ref().unwrap();
    let entry = d.pool.display(j.rate_wrt_velocity[1][0]).to_string();
    assert!(entry.contains("∂_y' u(t, y, y')"), "{entry}");
    let entry = d.pool.display(j.rate_wrt_q[1][0]).to_string();
    assert!(entry.contains("∂_y u(t, y, y')"), "{entry}");
}

#[test]
fn units_of_an_input_are_declared() {
    // u is an acceleration: m u is a thrust and m u/u_e a mass rate.
    let with_units = format!("{HOVER}\nunits y: m, u: m/s^2, u_e: m/s, g: m/s^2");
    derive(&with_units).unwrap();
    let wrong = format!("{HOVER}\nunits y: m, u: m/s, u_e: m/s, g: m/s^2");
    let errors = derive(&wrong).unwrap_err();
    assert!(!errors.is_empty());
}

/// The derivation of `source` with `law` in place of input `u` ([`derive_with_laws`]).
fn derive_with_law(source: &str, law: &str) -> Result<Derivation, Vec<Diagnostic>> {
    let ast = parse_system(source)?;
    let law = varmass_symbolic::parse::parse_expression(law).map_err(|d| vec![d])?;
    varmass_symbolic::derive_with_laws(
        &ast,
        Parameters::Inferred,
        Outputs::FULL,
        std::path::Path::new("."),
        &[("u".to_string(), law)],
    )
}

/// Each acceleration of `d`, printed.
fn accelerations(d: &Derivation) -> Vec<String> {
    let rows = d.accelerations.as_ref().expect("solved accelerations");
    d.pool.display_all(rows)
}

#[test]
fn a_law_replaces_each_call_with_the_arguments_bound_at_once() {
    // `u(y, x')` is declared with y first; the call `u(x, 3*y)` passes x for y and 3y for
    // x'. The law y - 2·x' read at (y := x, x' := 3y) is x − 6y: bound at once, not in turn
    // (in turn, x' := 3y and then y := x, it would be x − 6x). (A declared name at another
    // position, `u(x', y)`, is refused: an_input_called_with_its_arguments_swapped_is_refused.)
    let with_input =
        "coordinates x, y\ninput u(y, x')\nmass m = m0\nbody a: mass m, position [x, y]\n\
                      force x: u(x, 3*y)\nforce y: k*u(2*t, x')";
    let written = "coordinates x, y\nmass m = m0\nbody a: mass m, position [x, y]\n\
                   force x: x - 6*y\nforce y: k*(2*t - 2*x')";
    let given = derive_with_law(with_input, "y - 2*x'").expect("derives");
    let expected = derive(written).expect("derives");
    assert!(given.inputs.is_empty(), "a law leaves no input");
    assert_eq!(accelerations(&given), accelerations(&expected));
    // The Jacobian is the written model's too (no finite difference of an input).
    let jacobian = |d: &Derivation| {
        let parts = d.jacobian.as_ref().expect("derived");
        let entries: Vec<_> = [&parts.rate_wrt_q, &parts.rate_wrt_velocity]
            .into_iter()
            .flatten()
            .flatten()
            .copied()
            .collect();
        d.pool.display_all(&entries)
    };
    assert_eq!(jacobian(&given), jacobian(&expected));
}

#[test]
fn a_law_that_calls_the_input_is_a_diagnostic_at_its_declaration() {
    let errors = derive_with_law(HOVER, "2*u(t, y, y')").expect_err("refused");
    assert!(
        errors.iter().any(
            |e| e.message == "the law given for input `u` calls input `u`" && e.span.line == 2
        ),
        "{errors:?}"
    );
}

/// A call that passes a declared argument at another position (`u(y, t)` for
/// `input u(t, y)`) is refused at that argument: the Rust function takes its arguments by
/// position, so t and y would arrive swapped. Any other expression is passed as written.
#[test]
fn an_input_called_with_its_arguments_swapped_is_refused() {
    let swapped = "coordinates y\ninput u(t, y)\nmass m = m0\nbody b: mass m, position [y]\nforce b: [u(y, t)]";
    error(
        swapped,
        "its argument 1 is `y`, which the declaration puts at argument 2",
        5,
        13,
    );
    let velocity = "coordinates y\ninput u(y, y')\nmass m = m0\nbody b: mass m, position [y]\nforce b: [u(y', y)]";
    error(velocity, "its argument 1 is `y'`", 5, 13);
    let shifted = "coordinates y\ninput u(t, y)\nmass m = m0\nbody b: mass m, position [y]\nforce b: [u(t, 2*y)]";
    assert!(derive(shifted).is_ok());
}

/// A period given twice is named as such (before: "unexpected `every`; expected `every`,
/// `;` or a newline"), and a reserved name says "an input".
#[test]
fn a_second_period_and_a_reserved_name_are_worded_for_an_input() {
    error(
        "coordinates y\ninput u(t) every 0.01 every 0.02\nforce y: u(t)",
        "`every` is given twice",
        2,
        23,
    );
    let errors = parse_system("coordinates y\ninput u(t) every 0.01 x").unwrap_err();
    assert!(
        errors[0].message.contains("expected `;` or a newline"),
        "{}",
        errors[0].message
    );
    error(
        "coordinates y\ninput H(t)\nforce y: H(t)",
        "cannot name an input",
        2,
        7,
    );
}
