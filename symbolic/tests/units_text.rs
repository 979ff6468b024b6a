//! The derivation text of a system with units states the unit of every coordinate and
//! parameter and of each derived quantity; without units it is unchanged.

use varmass_symbolic::{derive_source, mechanics::Parameters};

/// The leaking polar pendulum: r in m, th in rad.
const PENDULUM: &str = "coordinates r, th
units r: m, th: rad, mu: kg/s, u_e: m/s, k: N/m, l0: m, g: m/s^2
mass m: state, rate -mu
body bob: mass m, position [r*sin(th), -r*cos(th)]
potential 1/2*k*(r - l0)^2 - m*g*r*cos(th)
outflow bob: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]";

fn text(source: &str) -> String {
    let mut d = derive_source(source, Parameters::Inferred).unwrap();
    d.to_text()
}

/// The unit stated at the end of the text's line that starts with `label`.
fn unit_of(text: &str, label: &str) -> String {
    let line = text
        .lines()
        .map(str::trim_start)
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("no line {label:?} in\n{text}"));
    let (_, unit) = line
        .rsplit_once("   [")
        .unwrap_or_else(|| panic!("no unit in {line:?}"));
    unit.trim_end_matches(']').to_string()
}

#[test]
fn the_text_states_the_units_of_parameters_and_quantities() {
    let text = text(PENDULUM);
    assert!(
        text.starts_with(
            "Units (rad is dimensionless)\n    r in m, th in rad, mu in kg/s, k in N/m, l0 in m, \
             g in m/s^2, u_e in m/s\n"
        ),
        "{text}"
    );
    // Derived by hand: p_r = m ṙ, p_th = m r² θ̇; Q, R on r are forces, on th torques.
    for (label, unit) in [
        ("dm/dt", "kg/s"),
        ("T =", "J"),
        ("L =", "J"),
        ("p_r =", "kg·m/s"),
        ("p_th =", "kg·m²/s"),
        ("H = p·q̇ − L", "J"),
        ("H(q, p, t)", "J"),
        ("Q*_r", "N"),
        ("R1_th", "N·m"),
        ("r' = ∂*H", "m/s"),
        ("th' = ∂*H", "1/s"),
        ("d*p_r/dt", "N"),
        ("d*p_th/dt", "N·m"),
        ("dp_th/dt", "N·m"),
        ("r'' =", "m/s²"),
        ("th'' =", "1/s²"),
        ("dH/dt", "W"),
    ] {
        assert_eq!(unit_of(&text, label), unit, "{label}");
    }
}

#[test]
fn without_units_the_text_has_none() {
    let plain = PENDULUM.replace(
        "units r: m, th: rad, mu: kg/s, u_e: m/s, k: N/m, l0: m, g: m/s^2\n",
        "",
    );
    let text = text(&plain);
    assert!(!text.contains("Units") && !text.contains("   ["), "{text}");
}

#[test]
fn the_generated_doc_comments_state_units() {
    let mut d = derive_source(PENDULUM, Parameters::Inferred).unwrap();
    let target = varmass_symbolic::emit::Target {
        name: quote::format_ident!("Pendulum"),
        runtime: quote::quote!(::varmass::core),
    };
    let code = varmass_symbolic::emit::emit_system(&mut d, PENDULUM, &target).to_string();
    let docs: Vec<&str> = code
        .split("# [doc = \"")
        .skip(1)
        .filter_map(|rest| rest.split("\"]").next())
        .collect();
    let has = |text: &str| docs.iter().any(|d| d.contains(text));
    assert!(has("Units: r in m, th in rad, mu in kg/s"), "{docs:#?}");
    for line in ["H = ", "d*p_th/dt = ", "dp_r/dt = ", "th' = ", "dH/dt = "] {
        let doc = docs
            .iter()
            .find(|d| d.starts_with(line))
            .unwrap_or_else(|| panic!("{line}"));
        let unit = doc
            .rsplit_once("   [")
            .map(|(_, u)| u.trim_end_matches(']'));
        let expected = match line {
            "H = " => "J",
            "d*p_th/dt = " => "N·m",
            "dp_r/dt = " => "N",
            "th' = " => "1/s",
            _ => "W",
        };
        assert_eq!(unit, Some(expected), "{doc}");
    }
}
