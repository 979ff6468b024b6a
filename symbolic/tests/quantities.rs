//! The registry of quantities (`varmass_symbolic::quantity`): every entry is complete and
//! reachable from each place that lists quantities — a `check`, the units check and table,
//! the derivation text and the generated docs (the command line tool's `--record` is held
//! to it in `cli/tests/run.rs`). A quantity added by one registry entry plus its
//! derivation (ARCHITECTURE.md, "Add a generated quantity") is covered here without a new
//! test: each test walks `Quantity::ALL`.

use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;
use varmass_symbolic::emit::{emit_system, Method, Target};
use varmass_symbolic::expr::Identity;
use varmass_symbolic::quantity::{Named, Quantity};
use varmass_symbolic::{
    derive_source,
    mechanics::{is_reserved, Derivation, Parameters},
};

/// A planar rocket: two coordinates (so q̈ is in closed form), a state mass with an outflow,
/// units. By hand, with v = (x', y') and the exhaust at −u along y relative to the body:
/// p = m v; R1 = μ (0, −u)·∂r/∂q = (0, −μu); d*p_y/dt = −m g − R1_y = −m g + μu;
/// ṗ_y = d*p_y/dt + ṁ y' = −m g + μu − μ y'; ṁ = −μ; ÿ = μu/m − g, ẍ = 0;
/// H = T + V = m (x'² + y'²)/2 + m g y.
const ROCKET: &str = "coordinates x, y
units x: m, y: m, mu: kg/s, u: m/s, g: m/s^2
mass m: state, rate -mu
body rocket: mass m, position [x, y]
potential m*g*y
outflow rocket: rate mu, relative_velocity [0, -u]
check p_x = m*x'
check R1_y = -mu*u
check dp_y = -m*g + mu*u
check pdot_y = -m*g + mu*u - mu*y'
check mdot_m = -mu
check y'' = mu*u/m - g
check x'' = 0
check H = m*(x'^2 + y'^2)/2 + m*g*y
check T = m*(x'^2 + y'^2)/2
check V = m*g*y
";

fn rocket(extra: &str) -> Derivation {
    let source = format!("{ROCKET}{extra}");
    match derive_source(&source, Parameters::Inferred) {
        Ok(d) => d,
        Err(e) => panic!("{source}\n{e:#?}"),
    }
}

/// Every DSL name of the registry for the rocket, with its quantity.
fn names(d: &Derivation) -> Vec<(String, Quantity, usize)> {
    let coordinates: Vec<&str> = d.coordinates.iter().map(|c| c.name.as_str()).collect();
    let masses: Vec<&str> = d.masses.iter().map(|m| m.name.as_str()).collect();
    Quantity::names(&coordinates, &masses)
}

#[test]
fn every_quantity_has_one_entry_and_its_names_parse_back() {
    for (i, q) in Quantity::ALL.iter().enumerate() {
        assert_eq!(q.index(), i, "{q:?} is in ALL once, at its index");
    }
    let d = rocket("");
    let all = names(&d);
    // 5 scalars, 6 per-coordinate names on 2 coordinates, x'' and y'', mdot_m.
    assert_eq!(all.len(), 5 + 6 * 2 + 2 + 1);
    for (name, q, i) in &all {
        assert_eq!(Quantity::parse(name, &["x", "y"], &["m"]), Some((*q, *i)));
        let prefixed = !matches!(q.spec().name, Named::PerCoordinate { prefix: "", .. });
        assert_eq!(is_reserved(name), prefixed, "`{name}` reserved");
    }
}

#[test]
fn every_named_quantity_is_reachable_from_a_check_with_its_value() {
    // The hand-derived checks above decide the values; `NAME = NAME` reaches every name.
    let identities: String = names(&rocket(""))
        .iter()
        .map(|(name, _, _)| format!("check {name} = {name}\n"))
        .collect();
    let d = rocket(&identities);
    assert_eq!(d.checks.len(), 10 + 20);
    for c in &d.checks {
        assert!(
            matches!(c.verdict, Identity::Proven | Identity::Numerical { .. }),
            "{}: {:?}",
            c.source,
            c.verdict
        );
    }
    // A wrong value is refuted: the name is bound to its own quantity, not another.
    let wrong = derive_source(
        &format!("{ROCKET}check pdot_y = -m*g + mu*u"),
        Parameters::Inferred,
    );
    assert!(wrong.is_err(), "pdot_y is the true ṗ, not d*p/dt");
}

#[test]
fn every_named_quantity_has_a_dimension_and_a_unit() {
    let d = rocket("");
    let units = d.units.as_ref().expect("the rocket declares units");
    for (name, q, i) in names(&d) {
        let dimension = units.quantity(&name);
        assert!(dimension.is_some(), "`{name}` has a dimension");
        let of = match q.spec().name {
            Named::PerMass(_) => Some(d.masses[i].name.as_str()),
            Named::PerCoordinate { .. } => Some(d.coordinates[i].name.as_str()),
            _ => None,
        };
        let unit = units.quantity_unit(q, of);
        assert_eq!(unit, dimension.map(|d| d.unit(false)), "`{name}`");
    }
    assert_eq!(
        units.quantity("p_x").map(|d| d.to_string()).as_deref(),
        Some("kg·m/s")
    );
    assert_eq!(
        units.quantity("mdot_m").map(|d| d.to_string()).as_deref(),
        Some("kg/s")
    );
    assert_eq!(
        units.quantity("y''").map(|d| d.to_string()).as_deref(),
        Some("m/s²")
    );
}

#[test]
fn every_named_quantity_is_in_the_derivation_text_and_its_method_in_the_docs() {
    let mut d = rocket("");
    let text = d.to_text();
    let latex = d.to_latex();
    let target = Target {
        name: Ident::new("Rocket", Span::call_site()),
        runtime: quote!(::varmass::core),
    };
    let code: TokenStream = emit_system(&mut d, ROCKET, &target);
    let code = code.to_string();
    for (name, q, i) in names(&d) {
        let on = match q.spec().name {
            Named::PerMass(_) => d.masses[i].name.clone(),
            Named::Scalar(_) => String::new(),
            _ => d.coordinates[i].name.clone(),
        };
        let label = q.text_label(&on);
        assert!(
            text.contains(&format!("{label} ")),
            "`{name}`: `{label}` in\n{text}"
        );
        assert!(latex.contains(&q.latex_label(&on)), "`{name}` in the LaTeX");
        if let Some((method, _)) = Method::carrying(q) {
            let method = method.name();
            assert!(
                code.contains(&format!("fn {method}")),
                "`{name}`: fn {method}"
            );
            assert!(code.contains(&label), "`{name}`: `{label}` in the docs");
        }
    }
    // The units follow the quantity, not the label's spelling.
    assert!(text.contains("dm/dt (state mass) = -mu   [kg/s]"), "{text}");
    assert!(text.contains("R1_y = -mu*u   [N]"), "{text}");
}
