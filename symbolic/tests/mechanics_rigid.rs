//! Rigid bodies in the derivation: each mistake in a `rigid` model is one diagnostic at the
//! text it is about, and the hand-derived terms of docs/mechanics.md#flows-at-points hold
//! as `check`s (thrust torque, jet damping, a torque's generalized force).

use varmass_symbolic::mechanics::{derive_source, Parameters};

/// The one diagnostic of `source`, with the text under its span.
fn error(source: &str) -> (String, String) {
    let errors = derive_source(source, Parameters::Inferred).expect_err("a mistake");
    assert_eq!(errors.len(), 1, "{errors:?}");
    let span = errors[0].span;
    let text = source[span.start..span.end].to_string();
    (errors[0].message.clone(), text)
}

const PLANAR: &str = "coordinates x, y, th\nmass m = m0\n";

#[test]
fn rigid_mistakes_are_diagnostics_at_their_text() {
    let cases = [
        (
            "rigid r: mass m, inertia J0 + a*t, position [x, y], angle th",
            "the inertia of rigid body `r` depends on `t`; it is frozen like a mass",
            "J0 + a*t",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y], angle th, centre [0, x]",
            "the centre of rigid body `r` depends on `x`",
            "x",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y, 0], angle th",
            "rigid body `r` is planar (`angle`), so its position has 2 components, found 3",
            "[x, y, 0]",
        ),
        (
            "rigid r: mass m, inertia [A, B, C], position [x, y], angle th",
            "a planar body has one moment",
            "[A, B, C]",
        ),
        (
            "body p: mass m, position [x, y]\ntorque p: tau",
            "`p` is not a rigid body; a torque turns a rigid body",
            "p",
        ),
        (
            "body p: mass m, position [x, y]\nforce p: [F, 0] at [0, 1]",
            "`p` is a particle: a point `at [..]` needs a rigid body",
            "[0, 1]",
        ),
        (
            "rigid r: mass m, inertia J, position [x, y], angle th\ntorque r: [1, 2]",
            "a planar body's torque is a scalar",
            "[1, 2]",
        ),
        (
            // A scalar torque with a point: refused by the derivation, not as a syntax error.
            "rigid r: mass m, inertia J, position [x, y], angle th\ntorque r: tau at [0, 1]",
            "a torque has no point of application: a couple acts on the whole body",
            "at [0, 1]",
        ),
    ];
    for (statements, message, under) in cases {
        let source = format!("{PLANAR}{statements}\n");
        let (found, text) = error(&source);
        assert!(found.contains(message), "{statements}: {found}");
        assert_eq!(text, under, "{statements}: {found}");
    }
}

/// A torque written with a point, planar (scalar) or spatial (vector): the message says a
/// couple has no point and suggests the force at a point, pointing at `at [..]`.
#[test]
fn a_torque_at_a_point_suggests_a_force_at_the_point() {
    let spatial = "coordinates x, y, z, a, b, c
        mass m = m0
        rigid r: mass m, inertia [A, A, C], position [x, y, z], orientation zyx(a, b, c)
        torque r: body [0, 0, tau] at [0, 0, 1]\n";
    let planar = format!(
        "{PLANAR}rigid r: mass m, inertia J, position [x, y], angle th\ntorque r: tau at [0, 1]\n"
    );
    for (source, under) in [(spatial.to_string(), "at [0, 0, 1]"), (planar, "at [0, 1]")] {
        let Err(errors) = derive_source(&source, Parameters::Inferred) else {
            panic!("a torque at a point derived: {source}");
        };
        let first = &errors[0];
        assert!(
            first
                .message
                .contains("a torque has no point of application"),
            "{first:?}"
        );
        let help = first.help.as_deref().unwrap_or_default();
        assert!(help.contains("force r: body [..] at [..]"), "{first:?}");
        assert_eq!(
            &source[first.span.start..first.span.end],
            under,
            "{first:?}"
        );
    }
}

#[test]
fn a_spatial_tensor_must_be_symmetric_and_a_sequence_known() {
    let source = "coordinates a, b, c
        mass m = m0
        rigid r: mass m, inertia [[P, Q, 0], [R, P, 0], [0, 0, S]], position [0, 0, 0], orientation zyx(a, b, c)";
    let (message, _) = error(source);
    assert!(
        message.contains("not symmetric: entry (2, 1) differs from (1, 2)"),
        "{message}"
    );
}

/// The derived generalized forces against hand derivations (docs/mechanics.md): a torque
/// enters the angle's equation as itself; a body-axis force at a point, (R F)·∂r_P/∂θ; a
/// gimballed nozzle gives the thrust torque −μ l u_e sin δ and jet damping.
#[test]
fn derived_terms_hold_as_checks() {
    let source = "coordinates x, y, th
        mass m: state, rate -mu
        inertia J = m*k^2
        rigid r: mass m, inertia J, position [x, y], angle th
        torque r: tau
        force r: body [F, 0] at [0, -l]
        outflow r: rate mu, at [0, -l], relative_velocity body [u_e*sin(delta), -u_e*cos(delta)]
        check Q_th = tau + F*l
        check Q_x = F*cos(th)
        check R1_th = mu*l*u_e*sin(delta) + mu*(l^2 - k^2)*th'
        check p_th = m*k^2*th'";
    let derivation = derive_source(source, Parameters::Inferred).unwrap_or_else(|e| {
        panic!(
            "{}",
            e.iter()
                .map(|d| d.render(source))
                .collect::<Vec<_>>()
                .join("\n")
        )
    });
    assert_eq!(derivation.checks.len(), 4);
}
