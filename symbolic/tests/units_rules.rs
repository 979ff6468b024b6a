//! One test per rule of the dimension check (`units`): the exact message, the offending
//! text under the caret, and that every problem is reported together. Each expected
//! dimension was derived by hand in the comment beside it.

use varmass_symbolic::Diagnostic;
use varmass_symbolic::{derive_source, mechanics::Parameters};

/// Every diagnostic of `source` (which must fail), rendered for failure messages.
fn errors(source: &str) -> Vec<Diagnostic> {
    match derive_source(source, Parameters::Inferred) {
        Ok(_) => panic!("expected a diagnostic for:\n{source}"),
        Err(errors) => errors,
    }
}

/// `source` fails with exactly one diagnostic, `message`, under the text `under`.
#[track_caller]
fn single(source: &str, message: &str, under: &str) -> Diagnostic {
    let errors = errors(source);
    let rendered: Vec<String> = errors.iter().map(|e| e.render(source)).collect();
    assert_eq!(errors.len(), 1, "{}", rendered.join("\n"));
    let error = errors.into_iter().next().unwrap();
    assert_eq!(error.message, message, "{}", rendered.join("\n"));
    assert_eq!(&source[error.span.start..error.span.end], under);
    error
}

#[test]
fn a_potential_term_that_is_not_an_energy_is_named_with_both_dimensions() {
    // m g x' sin θ: kg · m/s² · m/s · 1 = kg·m²/s³
    single(
        "coordinates x\nunits x: m, m: kg, g: m/s^2, theta: rad\n\
         potential m*g*x*sin(theta) + m*g*x'*sin(theta)",
        "potential term m*g*x'*sin(theta) has kg·m²/s³, expected an energy, kg·m²/s²",
        "m*g*x'*sin(theta)",
    );
}

#[test]
fn kinetic_and_lagrangian_terms_are_energies() {
    // ½ m ẋ: kg·m/s, a momentum
    single(
        "coordinates x\nunits x: m, m: kg\nkinetic 1/2*m*x'",
        "kinetic term 1/2*m*x' has kg·m/s, expected an energy, kg·m²/s²",
        "1/2*m*x'",
    );
    // k x: (N/m)·m = N
    single(
        "coordinates x\nunits x: m, m: kg, k: N/m\nlagrangian 1/2*m*x'^2 - k*x",
        "lagrangian term k*x has kg·m/s², expected an energy, kg·m²/s²",
        "k*x",
    );
}

#[test]
fn a_body_position_is_a_length() {
    // x t: m·s
    single(
        "coordinates x\nunits x: m\nmass m = M\nunits M: kg\nbody b: mass m, position [x, x*t]",
        "position of body `b`: x*t has m·s, expected a length, m",
        "x*t",
    );
}

#[test]
fn a_mass_law_is_a_mass_and_an_inertia_is_kg_m2() {
    // c x with c in kg·s/m and x in m: kg·s
    single(
        "coordinates x\nunits x: m, m0: kg, c: kg*s/m\nmass m = m0 + c*x\n\
         body b: mass m, position [x]",
        "mass law of `m`: c*x has kg·s, expected a mass, kg",
        "c*x",
    );
    single(
        "coordinates th\nunits th: rad, J0: kg\ninertia J = J0\nkinetic 1/2*J*th'^2",
        "inertia law of `J`: J0 has kg, expected a moment of inertia, kg·m²",
        "J0",
    );
}

#[test]
fn a_state_mass_rate_and_a_flow_rate_are_mass_flows() {
    single(
        "coordinates y\nunits y: m, mu: kg/s, g: m/s^2\nmass m: state, rate -mu*g\n\
         body r: mass m, position [y]\noutflow r: rate mu",
        "rate of `m`: -mu*g has kg·m/s³, expected a mass flow, kg/s",
        "-mu*g",
    );
    let messages: Vec<String> = errors(
        "coordinates y\nunits y: m, mu: kg\nmass m: state, rate -mu\n\
         body r: mass m, position [y]\noutflow r: rate mu",
    )
    .into_iter()
    .map(|e| e.message)
    .collect();
    assert_eq!(
        messages,
        [
            "rate of `m`: -mu has kg, expected a mass flow, kg/s",
            "rate of outflow from `r`: mu has kg, expected a mass flow, kg/s",
        ]
    );
}

#[test]
fn flow_velocities_are_velocities() {
    // u_e given in m: the relative velocity is a length
    single(
        "coordinates y\nunits y: m, mu: kg/s, u_e: m\nmass m: state, rate -mu\n\
         body r: mass m, position [y]\noutflow r: rate mu, relative_velocity [-u_e]",
        "relative velocity of outflow from `r`: -u_e has m, expected a velocity, m/s",
        "-u_e",
    );
    single(
        "coordinates x\nunits x: m, m0: kg, c: kg/m\nmass m = m0 + c*x\n\
         body b: mass m, position [x]\ninflow b: velocity [x]",
        "velocity of inflow into `b`: x has m, expected a velocity, m/s",
        "x",
    );
}

#[test]
fn a_body_force_is_a_force() {
    // f_d m g with f_d given in m: kg·m²/s²
    single(
        "coordinates x\nunits x: m, m: kg, g: m/s^2, f_d: m\nkinetic 1/2*m*x'^2\n\
         mass mb = m\nbody b: mass mb, position [x]\nforce b: [-f_d*m*g]",
        "force on body `b`: -f_d*m*g has kg·m²/s², expected a force, kg·m/s²",
        "-f_d*m*g",
    );
}

#[test]
fn a_generalized_force_is_an_energy_per_unit_of_its_coordinate() {
    // On an angle, a force (N) is not a torque (N·m = J/rad).
    single(
        "coordinates th\nunits th: rad, I0: kg*m^2, F: N\nkinetic 1/2*I0*th'^2\nforce th: F",
        "generalized force on `th`: F has kg·m/s², expected an energy, kg·m²/s² \
         (energy per unit of `th`, J/rad)",
        "F",
    );
    // The impact force on x (m) is −c ẋ² with c in kg/m: kg·m/s² = J/m. With c in kg it
    // is kg·m²/s².
    single(
        "coordinates x\nunits x: m, m0: kg, c: kg\nmass m = m0\nkinetic 1/2*m*x'^2\n\
         impact x: -c*x'^2",
        "impact force on `x`: -c*x'^2 has kg·m²/s², expected a force, kg·m/s² \
         (energy per unit of `x`, J/m)",
        "-c*x'^2",
    );
    single(
        "coordinates x\nunits x: m, m: kg, mu: kg/s\nkinetic 1/2*m*x'^2\nthrust x: mu",
        "thrust on `x`: mu has kg/s, expected a force, kg·m/s² (energy per unit of `x`, J/m)",
        "mu",
    );
}

#[test]
fn both_sides_of_a_check_agree() {
    // p_x = ∂L/∂ẋ: J·s/m = kg·m/s; m ẋ² is an energy
    single(
        "coordinates x\nunits x: m, m: kg\nkinetic 1/2*m*x'^2\ncheck p_x = m*x'^2",
        "the two sides of this check disagree: p_x has kg·m/s, m*x'^2 has kg·m²/s²",
        "p_x = m*x'^2",
    );
}

#[test]
fn derived_quantities_in_checks_have_their_dimensions() {
    // p_th on an angle is an angular momentum; R1 on th is a torque; mdot_m a mass flow;
    // x'' an acceleration; H and power an energy and a power.
    let source = "coordinates r, th
units r: m, th: rad, mu: kg/s, u_e: m/s, k: N/m, l0: m, g: m/s^2
mass m: state, rate -mu
body bob: mass m, position [r*sin(th), -r*cos(th)]
potential 1/2*k*(r - l0)^2 - m*g*r*cos(th)
outflow bob: rate mu, relative_velocity [-u_e*cos(th), -u_e*sin(th)]
check p_th = m*r^2*th'
check R1_th = -mu*u_e*r
check mdot_m = -mu
check power*t + H = H + t*power
check dp_r + Q_r = Q_r + dp_r";
    derive_source(source, Parameters::Inferred)
        .unwrap_or_else(|e| panic!("{}", e[0].render(source)));
}

#[test]
fn operands_of_sums_and_min_max_agree() {
    single(
        "coordinates x\nunits x: m, m: kg, l: m\nkinetic 1/2*m*(x' + l)^2",
        "the operands of `+` disagree: x' has m/s, l has m",
        "(x' + l)",
    );
    single(
        "coordinates x\nunits x: m, m: kg\nkinetic 1/2*m*min(x', x)^2",
        "the arguments of `min` disagree: x' has m/s, x has m",
        "min(x', x)",
    );
    // max of two lengths is a length: m g max(x, l) is an energy, no error
    derive_source(
        "coordinates x\nunits x: m, m: kg, g: m/s^2, l: m\nkinetic 1/2*m*x'^2\n\
         potential m*g*max(x, l)",
        Parameters::Inferred,
    )
    .unwrap();
}

#[test]
fn transcendental_arguments_are_dimensionless() {
    let error = single(
        "coordinates x\nunits x: m, m: kg, g: m/s^2\nkinetic 1/2*m*x'^2\npotential m*g*x*cos(x)",
        "the argument of `cos`, x, has m, expected dimensionless",
        "x",
    );
    assert_eq!(error.span.column, 21);
    single(
        "coordinates x, y\nunits x: m, y: m/s, m: kg\nkinetic 1/2*m*(x'^2 + y^2)*atan2(y, x)",
        "the arguments of `atan2` disagree: y has m/s, x has m",
        "atan2(y, x)",
    );
    // exp(x/l) and ln(x/l) are fine, atan2 of two lengths is dimensionless
    derive_source(
        "coordinates x, y\nunits x: m, y: m, m: kg, l: m\n\
         kinetic 1/2*m*(x'^2 + y'^2)*exp(x/l)*atan2(y, x)/ln(2 + x^2/l^2)",
        Parameters::Inferred,
    )
    .unwrap();
}

#[test]
fn sqrt_and_constant_powers_scale_dimensions() {
    // sqrt(k/m): 1/s; (m ẋ)^(3/2) / sqrt(m ẋ): kg·m/s
    derive_source(
        "coordinates x\nunits x: m, m: kg, k: N/m\n\
         kinetic 1/2*m*(sqrt(k/m)*x)^2 + 1/2*(m*x')^(3/2)/sqrt(m*x')*x'",
        Parameters::Inferred,
    )
    .unwrap();
    single(
        "coordinates x\nunits x: m, m: kg, k: N/m\nkinetic 1/2*m*x'^2*sqrt(k)",
        "kinetic term 1/2*m*x'^2*sqrt(k) has kg^(3/2)·m²/s³, expected an energy, kg·m²/s²",
        "1/2*m*x'^2*sqrt(k)",
    );
}

#[test]
fn a_dimensioned_base_needs_a_constant_exponent() {
    let error = single(
        "coordinates x\nunits x: m, m: kg, n: 1\nkinetic 1/2*m*x'^2\npotential m*x^n",
        "x has m, so its exponent must be a constant number, and n is not",
        "n",
    );
    assert!(error.help.unwrap().contains("fixed power"));
    // A dimensionless base may have any dimensionless exponent.
    derive_source(
        "coordinates x\nunits x: m, m: kg, n: 1, l: m, E: J\nkinetic 1/2*m*x'^2\npotential E*(x/l)^n",
        Parameters::Inferred,
    )
    .unwrap();
    single(
        "coordinates x\nunits x: m, m: kg, E: J\nkinetic 1/2*m*x'^2\npotential E*2^x",
        "exponent x has m, expected dimensionless",
        "x",
    );
}

#[test]
fn each_symbol_without_a_unit_is_reported_where_it_is_written() {
    // Coordinates at their declaration, a parameter at its first use; the `units` line is
    // named in the help as the other place to fix it.
    let source = "coordinates x, y\nunits m: kg\nkinetic 1/2*m*(x'^2 + y'^2)\npotential m*g*y";
    let errors = errors(source);
    let found: Vec<(&str, usize, &str)> = errors
        .iter()
        .map(|e| {
            (
                e.message.as_str(),
                e.span.line as usize,
                &source[e.span.start..e.span.end],
            )
        })
        .collect();
    let message = |n: &str| {
        format!("no unit for `{n}`: with `units`, every coordinate and parameter needs one")
    };
    let expected = [
        (message("x"), 1, "x"),
        (message("y"), 1, "y"),
        (message("g"), 4, "g"),
    ];
    let expected: Vec<(&str, usize, &str)> = expected
        .iter()
        .map(|(m, l, t)| (m.as_str(), *l, *t))
        .collect();
    assert_eq!(found, expected);
    assert_eq!(
        errors[2].help.as_deref(),
        Some("add `g: …` to the `units` statement")
    );
}

#[test]
fn a_typo_in_an_expression_suggests_the_name_used_elsewhere() {
    // Issue 23: `rate muu` with `mu` used in the relative velocity's statement too.
    let source = "coordinates y\nunits y: m, mu: kg/s, u_e: m/s\nmass m: state, rate -mu\n\
                  body b: mass m, position [y]\noutflow b: rate muu, relative_velocity [-u_e]";
    let error = single(
        source,
        "no unit for `muu`: with `units`, every coordinate and parameter needs one",
        "muu",
    );
    assert_eq!(
        error.help.as_deref(),
        Some("did you mean `mu`? Otherwise add `muu: …` to the `units` statement")
    );
}

#[test]
fn definitions_are_inferred_unless_given() {
    // r = sqrt(x² + y²) is inferred a length, so k (r − l0)² is an energy.
    derive_source(
        "coordinates x, y\nunits x: m, y: m, m: kg, k: N/m, l0: m\nlet r = sqrt(x^2 + y^2)\n\
         kinetic 1/2*m*(x'^2 + y'^2)\npotential 1/2*k*(r - l0)^2",
        Parameters::Inferred,
    )
    .unwrap();
    single(
        "coordinates x\nunits x: m, m: kg, w: 1/s\nlet w = x'/x^2\nkinetic 1/2*m*x^2*w^2",
        "definition of `w`: x'/x^2 has 1/(m·s), expected a rate, 1/s (the unit `units` gives `w`)",
        "x'/x^2",
    );
}

#[test]
fn unit_declarations_are_checked_themselves() {
    let source = "coordinates x\nunits x: m, m: kg, q: m, x: s, t: s, H: J, v: m/sec\n\
                  kinetic 1/2*m*x'^2";
    let messages: Vec<String> = errors(source).into_iter().map(|e| e.message).collect();
    assert_eq!(
        messages,
        [
            "the unit of `x` is given twice",
            "`t` is the time, always in s",
            "`H` is a derived quantity: its unit follows from the others",
            "unknown unit `sec`; the units are kg, m, s, rad, N, J, W, Pa, K, mol and 1",
        ]
    );
    single(
        "coordinates x\nunits x: m, b: kg, M0: kg\nmass m = M0\nbody b: mass m, position [x]",
        "`b` is a body: it has no unit; its mass and position do",
        "b",
    );
    single(
        "coordinates x\nunits x: m, M0: kg, m: m\nmass m = M0\nbody b: mass m, position [x]",
        "`m` is a mass, in kg, but `units` gives it m",
        "m",
    );
    // A rigid body is a body too (the check reads the resolved model's bodies).
    single(
        "coordinates x, th\nunits x: m, th: rad, M0: kg, J0: kg*m^2, b: kg\n\
         mass m = M0\ninertia J = J0\nrigid b: mass m, inertia J, position [x, 0], angle th",
        "`b` is a body: it has no unit; its mass and position do",
        "b",
    );
}

#[test]
fn every_problem_is_reported_together_in_source_order() {
    let source = "coordinates x\nunits x: m, m: kg, g: m/s^2, c: kg\n\
                  kinetic 1/2*m*x'\npotential m*g*x + sin(x)\nimpact x: -c*x'^2\ncheck p_x = m";
    let errors = errors(source);
    let lines: Vec<u32> = errors.iter().map(|e| e.span.line).collect();
    assert_eq!(lines, [3, 4, 4, 5, 6], "{errors:#?}");
}

#[test]
fn a_literal_zero_fits_any_dimension() {
    derive_source(
        "coordinates x\nunits x: m, m0: kg, c: kg/m\nmass m = m0 + c*x\n\
         body b: mass m, position [x]\ninflow b: velocity [0]\nforce x: 0*x",
        Parameters::Inferred,
    )
    .unwrap();
}

#[test]
fn a_system_without_units_is_not_checked() {
    // The same mistake as above (an energy plus a length) derives without `units`.
    let wrong = "coordinates x\nkinetic 1/2*m*x'^2\npotential 1/2*k*x^2 + x";
    derive_source(wrong, Parameters::Inferred).unwrap();
    single(
        &format!("{wrong}\nunits x: m, m: kg, k: N/m"),
        "potential term x has m, expected an energy, kg·m²/s²",
        "x",
    );
}

#[test]
fn a_sum_at_the_depth_limit_is_checked_on_a_default_thread() {
    // 995 terms, near the deepest tree the parser accepts (1000); each k*x^2 is an energy but the
    // last one, k*x.
    let terms = vec!["k*x^2"; 994].join(" + ");
    let source = format!(
        "coordinates x\nunits x: m, m: kg, k: N/m\nkinetic 1/2*m*x'^2\npotential {terms} + k*x"
    );
    let errors = std::thread::spawn(move || errors(&source))
        .join()
        .expect("no stack overflow on a 2 MB thread");
    assert_eq!(errors.len(), 1);
    assert_eq!(
        errors[0].message,
        "potential term k*x has kg·m/s², expected an energy, kg·m²/s²"
    );
}

#[test]
fn a_unit_for_an_unused_name_is_allowed_and_a_likely_typo_is_pointed_out() {
    // One `units` line serves every tag selection: k_d is used only with `[drag]`.
    derive_source(
        "coordinates y\nunits y: m, m0: kg, g: m/s^2, k_d: kg/m\nmass m = m0\n\
         body b: mass m, position [y]\npotential m*g*y",
        Parameters::Inferred,
    )
    .unwrap();
    let error = single(
        "coordinates x\nunits x: m, m: kg, E: J, thetta: rad\nkinetic 1/2*m*x'^2\n\
         potential E*cos(theta)",
        "no unit for `theta`: with `units`, every coordinate and parameter needs one",
        "theta",
    );
    assert_eq!(
        error.help.as_deref(),
        Some(
            "`thetta` has a unit in the `units` statement but is used nowhere: did you mean \
             `theta` there? Otherwise add `theta: …` to the `units` statement"
        )
    );
}
