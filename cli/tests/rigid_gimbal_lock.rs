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

use assert_cmd::Command;
use varmass::prelude::*;

mod common;

use common::{data, scratch, scratch_file, varmass};

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

/// The ball turned about n = (0, 1, δ)/√(1 + δ²) from the identity attitude, by Dop853 at
/// 1e-10 to t = 3 (the generated code).
fn turned(delta: f64) -> Result<Solution<6, 12>, Box<RunError<6, 12>>> {
    let ball = Ball { M: 2.0, A: 0.5 };
    let mut velocity_state = SVector::<f64, 12>::zeros();
    velocity_state[6 + 3] = delta * W; // ψ̇
    velocity_state[6 + 4] = W; // θ̇
    let start = ball.momentum_state(0.0, &velocity_state);
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-10,
        absolute_tolerance: 1e-10,
        ..AdaptiveControl::dop853()
    });
    let mut stepper = Dop853::new(&ball, 0.0, start, control).unwrap();
    run(&mut stepper, &RunConfig::until(3.0), &[]).map_err(Box::new)
}

#[test]
fn the_generated_code_ends_at_the_gimbal_lock_with_the_typed_error() {
    let error = turned(DELTA)
        .expect_err("the run cannot pass the gimbal lock")
        .into_step_error();
    let distance = error.time - crossing();
    eprintln!(
        "generated: singular at t* {distance:+e} (t* = {})",
        crossing()
    );
    assert_eq!(
        error.kind,
        StepErrorKind::System(varmass::core::SystemError::SingularMassMatrix)
    );
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

/// `varmass run` of the ball turned about n = (0, 1, δ)/√(1 + δ²), as [`turned`], with
/// `extra` arguments.
fn varmass_turned(delta: f64, extra: &[&std::ffi::OsStr]) -> std::process::Output {
    let model = data("gimbal_lock.vms");
    Command::cargo_bin("varmass")
        .expect("the binary is built")
        .args([
            "run", &model, "--until", "3", "--method", "dop853", "--tol", "1e-10",
        ])
        .args(["--set", "M=2", "--set", "A=0.5"])
        .args(["--init", "x=0", "--init", "y=0", "--init", "z=0"])
        .args(["--init", "psi=0", "--init", "th=0", "--init", "phi=0"])
        .args(["--init", &format!("psi'={}", delta * W)])
        .args(["--init", &format!("th'={W}")])
        .args(extra)
        .output()
        .expect("runs")
}

#[test]
fn varmass_run_ends_at_the_gimbal_lock_with_exit_1_and_the_time() {
    let csv = scratch("gimbal_lock.csv");
    let output = varmass_turned(DELTA, &["--csv".as_ref(), csv.as_os_str()]);
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

/// The ball turned about n = (0, 1, δ)/√(1 + δ²) passes gimbal lock at the distance
/// π/2 − θ_max = asin(cos θ_min) = atan δ (module comment: cos θ_min = δ/√(1 + δ²)), at
/// t* = π/(2 w √(1 + δ²)).
fn closest_approach(delta: f64) -> Option<f64> {
    let solution = turned(delta).expect("the run passes");
    solution.closest_singular_attitude
}

/// `Solution::closest_singular_attitude`: the closest the run's points came to gimbal lock.
/// It cannot be below atan δ (less the state's error, 1e-9 allowed), and the points of the
/// shrinking steps near t* come close to it: measured 1.4e-6 (δ = 5e-3) and 2.5e-5
/// (δ = 0.5, longer steps) above atan δ, relative; bounds about ten times those.
#[test]
fn a_run_records_its_closest_approach_to_gimbal_lock() {
    let delta = 5e-3;
    let closest = closest_approach(delta).expect("a spatial rigid body");
    eprintln!(
        "δ = {delta}: closest {closest:e}, atan δ = {:e}",
        delta.atan()
    );
    assert!(closest >= delta.atan() - 1e-9, "{closest:e}");
    assert!(closest <= delta.atan() * (1.0 + 2e-5), "{closest:e}");
    assert!(closest < varmass::core::GIMBAL_WARNING);
    let far = closest_approach(0.5).expect("a spatial rigid body");
    eprintln!("δ = 0.5: closest {far:e}, atan δ = {:e}", 0.5f64.atan());
    assert!(
        far >= 0.5f64.atan() - 1e-9 && far <= 0.5f64.atan() * (1.0 + 2e-4),
        "{far:e}"
    );
}

/// `varmass run`'s summary warns when the run came within 1e-2 rad of gimbal lock, with
/// the distance (at least atan δ, as above; measured 1.4e-6 above it, relative, bound
/// 2e-5), and says nothing far from it.
#[test]
fn the_summary_warns_near_gimbal_lock() {
    let summary = |delta: f64| {
        let output = varmass_turned(delta, &[]);
        assert_eq!(output.status.code(), Some(0));
        String::from_utf8_lossy(&output.stdout).into_owned()
    };
    let near = summary(5e-3);
    let prefix = "warning: the attitude came within ";
    let line = near
        .lines()
        .find_map(|l| l.strip_prefix(prefix))
        .unwrap_or_else(|| panic!("no warning: {near}"));
    let distance: f64 = line
        .split(' ')
        .next()
        .and_then(|d| d.parse().ok())
        .expect("rad");
    eprintln!("varmass run: within {distance:e} of gimbal lock");
    assert!(
        (5e-3f64.atan() - 1e-9..=5e-3f64.atan() * (1.0 + 2e-5)).contains(&distance),
        "{line}"
    );
    let far = summary(0.5);
    assert!(!far.contains("gimbal lock"), "{far}");
}

/// With `--every` the kept points are the output times only, but the warning reads every
/// accepted step: the same closest approach (at least atan δ; measured 1.4e-6 above it with
/// `--every 1` and 1.6e-4 with `--every 0.3`, whose steps land elsewhere; bound 1e-3).
/// Before, the warning read the kept points and vanished.
#[test]
fn the_warning_reads_every_step_with_every() {
    for every in ["1", "0.3"] {
        let output = varmass_turned(5e-3, &["--every".as_ref(), every.as_ref()]);
        assert_eq!(output.status.code(), Some(0));
        assert_warned_at_atan_delta(&String::from_utf8_lossy(&output.stdout));
    }
}

/// The summary `stdout` warns at a distance from gimbal lock of at least atan δ for δ = 5e-3
/// and at most 1e-3 above it, relative (the bound of the two tests that call it).
fn assert_warned_at_atan_delta(stdout: &str) {
    let distance: f64 = stdout
        .lines()
        .find_map(|l| l.strip_prefix("warning: the attitude came within "))
        .and_then(|l| l.split(' ').next()?.parse().ok())
        .unwrap_or_else(|| panic!("no warning: {stdout}"));
    let floor = 5e-3f64.atan();
    assert!(
        (floor - 1e-9..=floor * (1.0 + 1e-3)).contains(&distance),
        "{distance:e}"
    );
}

/// A scene's summary warns too, over every step of every phase: the ball of [`turned`] as a
/// one-phase scene (padded to the scene's compiled size), δ = 5e-3: the same closest approach
/// as `varmass run` (at least atan δ; bound 1e-3 above it, relative). Before, only
/// `varmass run` warned.
#[test]
fn a_scenes_summary_warns_near_gimbal_lock() {
    let text = format!(
        "model = {:?}\nuntil = 3.0\nmethod = \"dop853\"\ntol = 1e-10\n[set]\nM = 2.0\n\
         A = 0.5\n[init]\nx = 0.0\ny = 0.0\nz = 0.0\npsi = 0.0\nth = 0.0\nphi = 0.0\n\
         \"psi'\" = {:?}\n\"th'\" = {W:?}\n",
        data("gimbal_lock.vms"),
        5e-3 * W,
    );
    let scene = scratch_file("gimbal_lock_scene.toml", &text);
    let (stdout, _) = varmass(&["run", &scene], 0);
    assert_warned_at_atan_delta(&stdout);
}
