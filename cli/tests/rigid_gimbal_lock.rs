//! A rigid body driven through its Euler sequence's gimbal lock ends the run with the typed
//! singular-mass-matrix error at that time, in the macro-generated code and in `varmass run`
//! (core::system::RELATIVE_PIVOT_FLOOR; docs/mechanics.md#rigid-bodies).
//!
//! The model (`tests/data/gimbal_lock.vms`): a uniform ball, inertia A about every axis,
//! torque-free, so it turns at a constant rate w about a world-fixed axis
//! n = (0, 1, δ)/√(1 + δ²), started at the identity attitude. In zyx(ψ, θ, φ) at zero
//! angles ω = (φ̇, θ̇, ψ̇), so the start is θ̇ = w, ψ̇ = δ w, φ̇ = 0.
//!
//! Derivation of the crossing. The body x axis e₁ ⊥ n turns about n by α = w√(1+δ²) t:
//! e₁(α) = cos α e₁ + sin α (n × e₁), n × e₁ = (0, δ, −1)/√(1+δ²). In zyx, sin θ = −R₃₁ =
//! −(e₁)_z = sin α/√(1+δ²), so θ is largest at α = π/2, t* = π/(2 w √(1+δ²)), where
//! cos θ = δ/√(1+δ²) ≈ δ. Near it cos²θ ≈ w²(t − t*)² + δ².
//!
//! For the ball T = ½ A (ψ̇² + θ̇² + φ̇² − 2 ψ̇ φ̇ sin θ) (+ the translation), so the angle
//! block of M is A [[1, 0, −sθ], [0, 1, 0], [−sθ, 0, 1]], whose last pivot is A cos²θ:
//! the relative pivot A cos²θ / A falls under √ε = 2⁻²⁶ when |cos θ| < ε^(1/4) ≈ 1.22e-4,
//! i.e. for |t − t*| < 1.22e-4/w when δ ≪ 1.22e-4. With δ = 1e-6 the error must come
//! within that window (a step's stages land in it: the angle rates grow as δ/cos²θ
//! towards it, so the adaptive steps shrink to its scale).

use std::path::PathBuf;

use assert_cmd::Command;
use varmass::prelude::*;

#[variable_mass_system(file = "tests/data/gimbal_lock.vms")]
#[allow(non_snake_case)] // the model's names: M, A
struct Ball {
    M: f64,
    A: f64,
}

const W: f64 = 1.0;
const DELTA: f64 = 1e-6;
/// ε^(1/4) / w: half the width of the window in which the pivot is below the floor.
const WINDOW: f64 = 1.220_703_125e-4 / W;

fn crossing() -> f64 {
    std::f64::consts::FRAC_PI_2 / (W * (1.0 + DELTA * DELTA).sqrt())
}

#[test]
fn the_generated_code_ends_at_the_gimbal_lock_with_the_typed_error() {
    let ball = Ball { M: 2.0, A: 0.5 };
    let mut velocity_state = SVector::<f64, 12>::zeros();
    velocity_state[6 + 3] = DELTA * W; // ψ̇
    velocity_state[6 + 4] = W; // θ̇
    let start = ball.momentum_state(0.0, &velocity_state);
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance: 1e-10,
        ..AdaptiveControl::dop853()
    });
    let mut stepper = Dop853::new(&ball, 0.0, start, control).unwrap();
    let error = run(&mut stepper, &RunConfig::until(3.0), &[])
        .expect_err("the run cannot pass the gimbal lock")
        .into_step_error();
    let distance = error.time - crossing();
    eprintln!(
        "generated: singular at t* {distance:+e} (t* = {})",
        crossing()
    );
    assert_eq!(error.kind, StepErrorKind::SingularMassMatrix);
    assert_at_the_floor(distance);
}

/// The error is reported at the first state whose pivot is under the floor: a stage just
/// inside the window's near edge. Measured: t* − 1.220662e-4 (4.1e-9 inside the edge) in
/// both the generated code and `varmass run`;
/// bound: inside the window's first tenth (1.2e-5), as the shrinking steps' stages are.
fn assert_at_the_floor(distance: f64) {
    assert!(
        (-WINDOW..-0.9 * WINDOW).contains(&distance),
        "t − t* = {distance:e}, window ±{WINDOW:e}"
    );
}

#[test]
fn varmass_run_ends_at_the_gimbal_lock_with_exit_1_and_the_time() {
    let model = format!("{}/tests/data/gimbal_lock.vms", env!("CARGO_MANIFEST_DIR"));
    let csv = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gimbal_lock.csv");
    let output = Command::cargo_bin("varmass")
        .expect("the binary is built")
        .args([
            "run", &model, "--until", "3", "--method", "dop853", "--tol", "1e-10",
        ])
        .args(["--set", "M=2", "--set", "A=0.5"])
        .args(["--init", "x=0", "--init", "y=0", "--init", "z=0"])
        .args(["--init", "psi=0", "--init", "th=0", "--init", "phi=0"])
        .args(["--init", &format!("psi'={}", DELTA * W)])
        .args(["--init", &format!("th'={W}"), "--csv"])
        .arg(&csv)
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    let prefix = "the run failed at t = ";
    let line = stderr
        .lines()
        .find_map(|l| l.split_once(prefix).map(|(_, rest)| rest))
        .unwrap_or_else(|| panic!("no failure line: {stderr}"));
    let (time, what) = line.split_once(": ").expect("t = T: what");
    assert!(what.starts_with("the mass matrix is singular"), "{stderr}");
    assert!(stderr.contains("gimbal lock"), "{stderr}");
    let distance = time.parse::<f64>().expect("a time") - crossing();
    eprintln!("varmass run: singular at t* {distance:+e}");
    assert_at_the_floor(distance);
}
