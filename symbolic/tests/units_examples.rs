//! The example systems with a `units` statement derive exactly as without one: the unit
//! check only reads the system, it never changes a derived quantity or the generated code
//! (doc comments aside, which may state units).

use proc_macro2::{TokenStream, TokenTree};
use quote::format_ident;
use varmass_symbolic::emit::{emit_system, Target};
use varmass_symbolic::{
    derive_source,
    mechanics::{Derivation, Parameters},
};

/// The sled in body form (eqs. 20–24), with the paper's results as checks.
const SLED: &str = "coordinates x
mass m = m0 + c*x
body sled: mass m, position [x]
potential -m*g*x*sin(theta)
force sled: [-f_d*m*g*cos(theta)]
inflow sled: velocity [0]
check L = 1/2*m*x'^2 + m*g*x*sin(theta)
check p_x = m*x'
check H = p_x^2/(2*m) - m*g*x*sin(theta)
check Q_x = -f_d*m*g*cos(theta)
check R2_x = -c*x'^2
check x'' = g*sin(theta) - f_d*g*cos(theta) - c*x'^2/m";
const SLED_UNITS: &str = "units x: m, m0: kg, c: kg/m, g: m/s^2, theta: rad, f_d: 1";

/// The sled in the paper's form: L, Q* and R2 given directly.
const SLED_PAPER: &str = "coordinates x
mass m = m0 + c*x
lagrangian 1/2*m*x'^2 + m*g*x*sin(theta)
force x: -f_d*m*g*cos(theta)
impact x: -c*x'^2";

const ROCKET: &str = "coordinates y
mass m: state, rate -mu
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate mu, relative_velocity [-u_e]
check R1_y = -mu*u_e
check y'' = mu*u_e/m - g";
const ROCKET_UNITS: &str = "units y: m, mu: kg/s, u_e: m/s, g: m/s^2";

const PENDULUM: &str = "coordinates r, th
mass m: state, rate -mu
body bob: mass m, position [r*sin(th), -r*cos(th)]
potential 1/2*k*(r - l0)^2 - m*g*r*cos(th)
outflow bob: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]
check p_th = m*r^2*th'
check R1_th = -mu*u_e*r
check pdot_th = -m*g*r*sin(th) + mu*u_e*r - mu*r^2*th'";
const PENDULUM_UNITS: &str = "units r: m, th: rad, mu: kg/s, u_e: m/s, k: N/m, l0: m, g: m/s^2";

fn derive(source: &str) -> Derivation {
    derive_source(source, Parameters::Inferred).unwrap_or_else(|errors| {
        let shown: Vec<String> = errors.iter().map(|e| e.render(source)).collect();
        panic!("{}", shown.join("\n"))
    })
}

/// Every derived quantity of `d`, printed.
fn quantities(d: &Derivation) -> Vec<String> {
    let mut ids = vec![d.kinetic, d.potential, d.lagrangian, d.energy, d.power];
    for list in [
        &d.mass_rates,
        &d.momenta,
        &d.lagrangian_gradient,
        &d.active_force,
        &d.reactive_thrust,
        &d.impact_force,
        &d.flow_rates,
        &d.frozen_momentum_rate,
        &d.mass_flux_force,
        &d.momentum_rate,
        &d.acceleration_rhs,
    ] {
        ids.extend(list.iter().copied());
    }
    ids.extend(d.hamiltonian);
    ids.extend(d.accelerations.iter().flatten().copied());
    ids.iter()
        .map(|&id| d.pool.display(id).to_string())
        .collect()
}

/// `tokens` without `#[doc = …]` attributes, at any depth.
fn without_docs(tokens: TokenStream) -> Vec<String> {
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut out = Vec::new();
    let mut k = 0;
    while k < trees.len() {
        let is_doc = matches!(&trees[k], TokenTree::Punct(p) if p.as_char() == '#')
            && matches!(trees.get(k + 1), Some(TokenTree::Group(g))
                if g.stream().into_iter().next().is_some_and(|t| t.to_string() == "doc"));
        if is_doc {
            k += 2;
            continue;
        }
        match &trees[k] {
            TokenTree::Group(g) => {
                out.push(format!("{:?}(", g.delimiter()));
                out.extend(without_docs(g.stream()));
                out.push(")".to_string());
            }
            other => out.push(other.to_string()),
        }
        k += 1;
    }
    out
}

/// `plain` and `plain` with `units` (inserted after its first line) derive the same
/// quantities, pass the same checks and generate the same code.
fn assert_same_with_units(plain: &str, units: &str) {
    let (first, rest) = plain.split_once('\n').unwrap();
    let with_units = format!("{first}\n{units}\n{rest}");
    let mut a = derive(plain);
    let mut b = derive(&with_units);
    assert_eq!(quantities(&a), quantities(&b));
    assert_eq!(a.checks.len(), b.checks.len());
    let target = Target {
        name: format_ident!("System"),
        runtime: quote::quote!(::varmass::core),
    };
    let code_a = without_text(without_docs(emit_system(&mut a, plain, &target)));
    let code_b = without_text(without_docs(emit_system(&mut b, plain, &target)));
    assert!(
        code_a.len() > 1000,
        "the generated code is {} tokens",
        code_a.len()
    );
    let differs = (0..code_a.len().max(code_b.len())).find(|&k| code_a.get(k) != code_b.get(k));
    if let Some(k) = differs {
        let window = |code: &[String]| {
            let end = (k + 10).min(code.len());
            code[k.saturating_sub(10).min(end)..end].join(" ")
        };
        panic!(
            "the code differs at token {k}:\n{}\n{}",
            window(&code_a),
            window(&code_b)
        );
    }
    // The derivation text differs only by the units it states.
    assert!(b.to_text().contains("Units (rad is dimensionless)"));
    assert!(!a.to_text().contains("Units"));
}

/// `code` without the value of the `DERIVATION` constant, which states the units.
fn without_text(mut code: Vec<String>) -> Vec<String> {
    if let Some(k) = code.iter().position(|t| t == "DERIVATION") {
        if let Some(end) = code[k..].iter().position(|t| t == ";") {
            code.drain(k..k + end);
        }
    }
    code
}

#[test]
fn the_sled_with_units_derives_exactly_as_before() {
    assert_same_with_units(SLED, SLED_UNITS);
    assert_same_with_units(SLED_PAPER, SLED_UNITS);
}

#[test]
fn the_rocket_with_units_derives_exactly_as_before() {
    assert_same_with_units(ROCKET, ROCKET_UNITS);
}

#[test]
fn the_leaking_pendulum_with_units_derives_exactly_as_before() {
    assert_same_with_units(PENDULUM, PENDULUM_UNITS);
}

#[test]
fn the_comparison_sees_a_changed_derivation() {
    // The comparison itself can fail: a different law changes the quantities.
    let changed = SLED
        .replace("m0 + c*x", "m0 + 2*c*x")
        .replace("check", "# check");
    let plain = SLED.replace("check", "# check");
    assert_ne!(quantities(&derive(&plain)), quantities(&derive(&changed)));
}

#[test]
fn the_sled_table_has_the_units_of_its_quantities() {
    let source = format!("{SLED_UNITS}\n{SLED}");
    let derivation = varmass_symbolic::derive_source(&source, Parameters::Inferred);
    let table = derivation.unwrap().units.unwrap();
    let shown = |name: &str| table.quantity(name).unwrap().to_string();
    assert_eq!(shown("H"), "kg·m²/s²");
    assert_eq!(shown("p_x"), "kg·m/s");
    assert_eq!(shown("R2_x"), "kg·m/s²");
    assert_eq!(shown("mdot_m"), "kg/s");
    assert_eq!(table.dimension("c").unwrap().to_string(), "kg/m");
    assert_eq!(table.written("theta"), Some("rad"));
}

#[test]
fn every_model_file_states_its_units_and_passes_the_check() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../models");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).expect("models/ exists") {
        let path = entry.expect("a directory entry").path();
        if path.extension().is_none_or(|e| e != "vms") {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("readable");
        let parsed = varmass_symbolic::parse::parse_system(&text).expect("parses");
        // Its components (models/lib/) expanded first, as every caller does.
        let composed = varmass_symbolic::compose::compose(&text, parsed, &path);
        let ast = composed.expect("its components compose").ast;
        let every_tag = varmass_symbolic::parse::known_tags(&ast);
        let all = varmass_symbolic::parse::select_tags(&ast, &every_tag).expect("known tags");
        let (inferred, minimal) = (
            Parameters::Inferred,
            varmass_symbolic::mechanics::Outputs::MINIMAL,
        );
        match varmass_symbolic::derive_in(&all, inferred, minimal, &dir) {
            Ok(d) if d.units.is_some() => count += 1,
            Ok(_) => panic!("{} has no `units` statement", path.display()),
            Err(errors) => panic!("{}: {}", path.display(), errors[0].render(&text)),
        }
    }
    assert!(count >= 8, "{count} model files");
}
