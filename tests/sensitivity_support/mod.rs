//! What the sensitivity tests share: the vertical rocket's closed-form sensitivities, and a
//! run-time model derived with its Jacobians.
#![allow(dead_code)] // each test file uses a part

use varmass::interpret::{Program, TapeSystem};
use varmass::symbolic::mechanics::{Outputs, Parameters};
use varmass::symbolic::{derive_for, parse::parse_system};

/// The run-time system of the DSL `source` derived with its Jacobians (what the
/// sensitivities need), with the parameter `values`.
pub fn tape<const N: usize, const S: usize>(
    source: &str,
    values: &[(&str, f64)],
) -> TapeSystem<N, S> {
    let ast = parse_system(source).expect("parses");
    let outputs = Outputs {
        sensitivities: true,
        ..Outputs::FULL
    };
    let d = derive_for(&ast, Parameters::Inferred, outputs).expect("derives");
    TapeSystem::new(Program::new(d, values).expect("the parameters fit")).expect("sizes")
}

/// ∂(y, v)/∂(u_e, μ, m0, p0) at t from rest at y = 0, by hand. With m = m0 − μ t and
/// L = ln(m0/m): v = u_e L − g t, y = u_e (t − (m/μ) L) − ½ g t² (dy/dt = u_e (1 + L − 1) − g t,
/// since d/dt[(m/μ) L] = −L + 1). Then, with ∂m/∂μ = −t, ∂L/∂μ = t/m, ∂(m/μ)/∂μ = −m0/μ²,
/// ∂m/∂m0 = 1 and ∂L/∂m0 = 1/m0 − 1/m:
///
/// ```text
/// ∂v/∂u_e = L                   ∂y/∂u_e = t − (m/μ) L
/// ∂v/∂μ   = u_e t/m             ∂y/∂μ   = u_e ((m0/μ²) L − t/μ)
/// ∂v/∂m0  = u_e (1/m0 − 1/m)    ∂y/∂m0  = −(u_e/μ) (L + m/m0 − 1)
/// ```
///
/// (each ∂y/∂w's t-derivative is the ∂v/∂w beside it, and both vanish at t = 0). A change δ
/// of p(0) = m0 v(0) moves v by δ/m0 for ever (v' does not depend on v): ∂v/∂p0 = 1/m0,
/// ∂y/∂p0 = t/m0.
///
/// `(m0, mu, u_e)` are the rocket's parameters.
pub fn rocket_by_hand((m0, mu, u_e): (f64, f64, f64), t: f64) -> [(f64, f64); 4] {
    let m = m0 - mu * t;
    let l = (m0 / m).ln();
    [
        (t - m / mu * l, l),
        (u_e * (m0 / mu.powi(2) * l - t / mu), u_e * t / m),
        (-(u_e / mu) * (l + m / m0 - 1.0), u_e * (1.0 / m0 - 1.0 / m)),
        (t / m0, 1.0 / m0),
    ]
}
