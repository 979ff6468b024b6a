//! Planar rigid bodies (docs/mechanics.md#rigid-bodies, #flows-at-points) against
//! independent references: Thomson's jet damping in closed form, and a rigid dumbbell
//! against the same dumbbell written as the paper's two particles.

use varmass::interpret::{Program, Quantity, TapeSystem};
use varmass::prelude::*;
use varmass::symbolic::{derive_source, mechanics::Parameters};

/// The program of `source` with its parameters.
fn program(source: &str, parameters: &[(&str, f64)]) -> Program {
    let derivation = derive_source(source, Parameters::Inferred).unwrap_or_else(|errors| {
        let messages: Vec<String> = errors.iter().map(|e| e.render(source)).collect();
        panic!("{}", messages.join("\n"))
    });
    Program::new(derivation, parameters).expect("program")
}

/// A body spinning and translating freely in the plane, J = m k² (mass lost uniformly, so k
/// stays), nozzle on its axis at l from the centre of mass, exhaust along the axis at u_e.
const THOMSON: &str = "
coordinates x, y, th
mass m: state, rate -mu
inertia J = m*k^2
rigid body: mass m, inertia J, position [x, y], angle th
outflow body: rate mu, at [0, -l], relative_velocity body [0, -u_e]
check p_th = m*k^2*th'
check R1_th = mu*(l^2 - k^2)*th'          # jet damping (the exhaust is axial: no torque)
check R1_x = mu*(u_e*sin(th) + l*cos(th)*th')
";

/// Thomson's jet damping (W. T. Thomson, *Introduction to Space Dynamics*, §7.8, and
/// docs/mechanics.md#jet-damping). The angle equation is J θ̈ = −R1_θ = −μ(l² − k²) θ̇
/// (the `check` above), with J = m k² and ṁ = −μ:
///
/// ```text
/// m k² dω/dt = −μ (l² − k²) ω,   dt = −dm/μ   ⇒   dω/ω = n dm/m,   n = (l² − k²)/k²
/// ω(t) = ω0 (m/m0)^n,            m = m0 − μ t
/// θ(t) = θ0 + ∫ ω dt = θ0 + ω0 m0 / (μ (n + 1)) · (1 − (m/m0)^(n+1))
/// ```
///
/// independent of the translation: the frame of the centre of mass plays no part.
#[test]
fn jet_damping_is_thomsons() {
    let (mu, u_e, k, l) = (0.5, 200.0, 0.4, 0.8);
    let parameters = [("mu", mu), ("k", k), ("u_e", u_e), ("l", l)];
    let system = TapeSystem::<3, 7>::new(program(THOMSON, &parameters)).expect("sizes");
    let (m0, omega0, th0) = (10.0, 3.0, 0.2);
    let start = SVector::<f64, 7>::from_column_slice(&[
        0.0,
        0.0,
        th0,
        0.7 * m0,
        -0.3 * m0,
        m0 * k * k * omega0,
        m0,
    ]);
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-18,
        ..AdaptiveControl::default()
    });
    let mut stepper = Dop853::new(&system, 0.0, start, control).unwrap();
    // Burn three quarters of the mass: m0/m = 4, ω falls by 4^n = 4^3.
    let end = 0.75 * m0 / mu;
    let solution = run(&mut stepper, &RunConfig::until(end), &[]).unwrap();
    let n = (l * l - k * k) / (k * k);
    let (mut worst_omega, mut worst_theta) = (0.0_f64, 0.0_f64);
    for (&t, s) in solution.times.iter().zip(&solution.states) {
        let m = m0 - mu * t;
        let ratio = m / m0;
        let omega = omega0 * ratio.powf(n);
        let theta = th0 + omega0 * m0 / (mu * (n + 1.0)) * (1.0 - ratio.powf(n + 1.0));
        worst_omega = worst_omega.max((s[5] / (s[6] * k * k) - omega).abs() / omega);
        worst_theta = worst_theta.max((s[2] - theta).abs() / theta);
    }
    // Measured: 1.8e-13 (ω), 3.6e-14 (θ) with DOP853 at 1e-13; bound 1e-10 (the issue's).
    eprintln!("jet damping: ω {worst_omega:e}, θ {worst_theta:e}");
    assert!(worst_omega < 1e-10, "ω relative error {worst_omega:e}");
    assert!(worst_theta < 1e-10, "θ relative error {worst_theta:e}");
    assert!(solution.times.len() > 10);
}

/// End 1 (mass M1, fixed) at the reference point, end 2 (state mass m2) at body point
/// [0, −d], leaking at a velocity [w, −u] in body axes relative to its material point;
/// gravity, and a world force F at end 1.
const DUMBBELL_PARTICLES: &str = "
coordinates x, y, th
mass m2: state, rate -mu
mass m1 = M1
body a: mass m1, position [x, y]
body b: mass m2, position [x + d*sin(th), y - d*cos(th)]
outflow b: rate mu, relative_velocity [w*cos(th) + u*sin(th), w*sin(th) - u*cos(th)]
potential m1*g*y + m2*g*(y - d*cos(th))
force a: [F, 0]
";

/// The same dumbbell as one rigid body: m = M1 + m2, centre of mass at c = −d m2/m on the
/// axis, J = M1 m2 d²/m about it (M1 (d m2/m)² + m2 (d M1/m)²), all laws of m2.
const DUMBBELL_RIGID: &str = "
coordinates x, y, th
mass m2: state, rate -mu
mass m = M1 + m2
inertia J = M1*m2*d^2/m
rigid bell: mass m, inertia J, position [x, y], angle th, centre [0, -d*m2/m]
outflow bell: rate mu, at [0, -d], relative_velocity body [w, -u]
potential m*g*(y - d*m2/m*cos(th))
force bell: [F, 0]
";

/// A small deterministic generator (xorshift64*), so the states repeat.
struct Random(u64);

impl Random {
    fn next(&mut self, low: f64, high: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let unit = (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64;
        low + (high - low) * unit
    }
}

/// Largest |a − b| / max(|a|, |b|, 1).
fn gap(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(1.0))
        .fold(0.0, f64::max)
}

/// The rigid body and the paper's particles are one system: at 1 000 random states the
/// state rates [q̇, ṗ, ṁ] agree. The rigid side gets there through the centre offset and
/// inertia rates (Σ φ̇ ∂*p/∂φ) and the flow at a point; the particle side through eq. 6
/// alone, so this checks the flows-at-points derivation against the paper.
#[test]
fn rigid_dumbbell_is_two_particles() {
    let parameters = [
        ("mu", 0.3),
        ("M1", 1.7),
        ("d", 0.9),
        ("w", 12.0),
        ("u", 40.0),
        ("g", 9.81),
        ("F", 2.5),
    ];
    let particles = program(DUMBBELL_PARTICLES, &parameters);
    let rigid = program(DUMBBELL_RIGID, &parameters);
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    let mut worst = 0.0_f64;
    for _ in 0..1000 {
        let mut velocity_state: Vec<f64> = (0..6).map(|_| random.next(-3.0, 3.0)).collect();
        velocity_state.push(random.next(0.05, 3.0));
        let mut momenta = [0.0; 3];
        particles.evaluate(Quantity::Momenta, 0.0, &velocity_state, &mut momenta);
        let mut state = velocity_state.clone();
        state[3..6].copy_from_slice(&momenta);
        let (mut a, mut b) = ([0.0; 7], [0.0; 7]);
        particles.state_rate(0.0, &state, &mut a).unwrap();
        rigid.state_rate(0.0, &state, &mut b).unwrap();
        worst = worst.max(gap(&a, &b));
    }
    eprintln!("dumbbell: state rates differ by {worst:e}");
    // Measured 4.3e-15; bound 1e-12 (the issue's).
    assert!(worst < 1e-12, "state rates differ by {worst:e}");
}
