//! Non-smooth points of a derivation: a mass law that can jump is refused at the jump
//! (docs/mechanics.md#jumps-and-phases); a kink is allowed.

use varmass_symbolic::{derive_source, mechanics::Parameters};

/// The 23 % example: the dry stage m_d "drops" at t_b inside the law. Refused at
/// `sign` (line 2, column 25), with help pointing to phases.
#[test]
fn a_mass_law_with_sign_is_refused_at_sign() {
    let source = "coordinates y
mass m = m_p + m_d*(1 + sign(t_b - t))/2 - mu*t
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: velocity [-u_e]";
    let errors = derive_source(source, Parameters::Inferred).expect_err("the jump is refused");
    assert_eq!(errors.len(), 1, "{errors:?}");
    let error = &errors[0];
    assert!(
        error.message.contains("the law of `m` can jump"),
        "{}",
        error.message
    );
    assert!(error.message.contains("`sign`"), "{}", error.message);
    assert_eq!((error.span.line, error.span.column), (2, 25));
    assert_eq!(&source[error.span.start..error.span.end], "sign");
    let help = error.help.as_deref().expect("help");
    assert!(help.contains("phases"), "{help}");
}

/// An inertia law is a mass law too; a jump reached through a `let` is reported at the law.
#[test]
fn a_jump_through_a_definition_is_reported_at_the_law() {
    let source = "coordinates theta
let on = (1 + sign(t_b - t))/2
inertia J = J0 + J1*on
lagrangian J*theta'^2/2";
    let errors = derive_source(source, Parameters::Inferred).expect_err("the jump is refused");
    let error = errors
        .iter()
        .find(|e| e.message.contains("the law of `J` can jump"))
        .expect("the inertia's jump is reported");
    assert_eq!(error.span.line, 3);
    assert_eq!(error.span.column, 1);
}

/// Kinks are allowed: `abs`, `min` and `max` in a law derive (ṁ then contains `sign`, a jump
/// in the rate, not in the mass).
#[test]
fn a_kink_in_a_mass_law_is_allowed() {
    let source = "coordinates y
mass m = m0 - mu*min(t, t_b) + c*abs(t - t_c) - k*max(0, t - t_d)
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: velocity [-u_e]";
    derive_source(source, Parameters::Inferred).expect("a kink derives");
}
