//! `varmass run` flies the six-degree-of-freedom rocket of `models/rocket_6dof.vms` (6
//! coordinates and a state mass: beyond the tool's former 4 × 2 size table) and agrees with
//! the macro-generated code of the same file, run by the same core stepper; and the same
//! rocket turned by a quaternion (`models/rocket_6dof_quaternion.vms`) as the zyx one.

use assert_cmd::Command;
use varmass::prelude::*;

mod common;

use common::{csv, model, scratch};

#[variable_mass_system(file = "../models/rocket_6dof.vms")]
#[allow(non_snake_case)] // the model's names: A_d, C_d
struct Rocket6 {
    mu: f64,
    m_d: f64,
    A_d: f64,
    C_d: f64,
    k_a: f64,
    k_c: f64,
    g_c: f64,
    l: f64,
    u_e: f64,
    delta: f64,
    g: f64,
}

const PARAMETERS: [(&str, f64); 11] = [
    ("mu", 2.0),
    ("m_d", 60.0),
    ("A_d", 30.0),
    ("C_d", 2.0),
    ("k_a", 0.8),
    ("k_c", 0.2),
    ("g_c", 1.0),
    ("l", 2.0),
    ("u_e", 2000.0),
    ("delta", 0.002),
    ("g", 9.81),
];

/// q, q̇ (in `COORDINATES` order) and the grain's mass at t = 0.
const POSITIONS: [f64; 6] = [0.0, 0.0, 0.0, 0.1, 0.05, 0.0];
const RATES: [f64; 6] = [1.0, -0.5, 2.0, 2.0, 0.05, 0.02];
const GRAIN: f64 = 40.0;
const UNTIL: f64 = 3.0;

fn rocket() -> Rocket6 {
    let value = |name: &str| PARAMETERS.iter().find(|(n, _)| *n == name).unwrap().1;
    Rocket6 {
        mu: value("mu"),
        m_d: value("m_d"),
        A_d: value("A_d"),
        C_d: value("C_d"),
        k_a: value("k_a"),
        k_c: value("k_c"),
        g_c: value("g_c"),
        l: value("l"),
        u_e: value("u_e"),
        delta: value("delta"),
        g: value("g"),
    }
}

/// The final [q, m_p] of the macro-generated system run by `stepper`.
fn generated(method: &str) -> Vec<f64> {
    let system = rocket();
    let mut velocity_state = SVector::<f64, 13>::zeros();
    for a in 0..6 {
        velocity_state[a] = POSITIONS[a];
        velocity_state[6 + a] = RATES[a];
    }
    velocity_state[12] = GRAIN;
    let start = system.momentum_state(0.0, &velocity_state);
    let config = RunConfig::until(UNTIL);
    let solution = match method {
        "rk4" => {
            let step = FixedStep { step: 1e-3 };
            let mut stepper = ClassicalRk4::new(&system, 0.0, start, step).unwrap();
            run(&mut stepper, &config, &[]).unwrap()
        }
        _ => {
            let control = StepControl::Adaptive(AdaptiveControl {
                relative_tolerance: 1e-12,
                absolute_tolerance: 1e-12,
                ..AdaptiveControl::dop853()
            });
            let mut stepper = Dop853::new(&system, 0.0, start, control).unwrap();
            run(&mut stepper, &config, &[]).unwrap()
        }
    };
    let (_, last) = solution.last().unwrap();
    let mut out: Vec<f64> = last.as_slice()[..6].to_vec();
    out.push(last[12]);
    out
}

/// The final [q, m_p] of `varmass run` on the model file with `method` and `setting`.
fn tool(method: &str, setting: &str) -> Vec<f64> {
    let table = scratch(format!("rocket_6dof_{method}.csv"));
    let model = model("rocket_6dof.vms");
    let mut cmd = Command::cargo_bin("varmass").expect("the binary is built");
    cmd.args([
        "run",
        &model,
        "--until",
        &UNTIL.to_string(),
        "--method",
        method,
        setting,
    ]);
    for (name, value) in PARAMETERS {
        cmd.args(["--set", &format!("{name}={value}")]);
    }
    let names = ["x", "y", "z", "psi", "th", "phi"];
    for (a, name) in names.iter().enumerate() {
        cmd.args(["--init", &format!("{name}={}", POSITIONS[a])]);
        cmd.args(["--init", &format!("{name}'={}", RATES[a])]);
    }
    cmd.args(["--init", &format!("m_p={GRAIN}")]);
    cmd.args(["--record", "x,y,z,psi,th,phi,m_p", "--csv"])
        .arg(&table);
    cmd.assert().success();
    let (_, rows) = csv(&table);
    let row = rows.last().expect("a row");
    assert_eq!(row[0], UNTIL);
    row[1..].to_vec()
}

fn gap(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / x.abs().max(y.abs()).max(1.0))
        .fold(0.0, f64::max)
}

#[test]
fn the_tool_flies_the_six_dof_rocket_like_the_generated_code() {
    let fixed = gap(&tool("rk4", "--step=1e-3"), &generated("rk4"));
    let adaptive = gap(&tool("dop853", "--tol=1e-12"), &generated("dop853"));
    eprintln!("6-dof rocket, tool against generated code: rk4 {fixed:e}, dop853 {adaptive:e}");
    // Measured: 3.5e-14 (RK4, 3000 steps), 2.0e-14 (DOP853 at 1e-12, its tolerance scaled
    // for the padding); bound 1e-12 (the issue's). The two evaluate the same formulas in
    // different orders, so they differ by rounding, grown along the flight.
    assert!(fixed < 1e-12, "rk4: {fixed:e}");
    assert!(adaptive < 1e-12, "dop853: {adaptive:e}");
}

/// The same rocket turned by a quaternion (`models/rocket_6dof_quaternion.vms`), started at
/// the zyx start's attitude and body rates: by hand, q = q_z(ψ) ⊗ q_y(θ) ⊗ q_x(φ), ω_b =
/// (φ̇ − ψ̇ sin θ, θ̇ cos φ + ψ̇ cos θ sin φ, −θ̇ sin φ + ψ̇ cos θ cos φ), q̇ = ½ q ⊗ (0, ω_b).
/// Its final [x, y, z, m_p] from `varmass run`, DOP853 at 1e-12.
fn tool_quaternion() -> Vec<f64> {
    use varmass::core::nalgebra::{Quaternion, UnitQuaternion, Vector3};
    let [psi, th, phi] = [POSITIONS[3], POSITIONS[4], POSITIONS[5]];
    let [dpsi, dth, dphi] = [RATES[3], RATES[4], RATES[5]];
    let q = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), psi)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), th)
        * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), phi);
    let omega = Vector3::new(
        dphi - dpsi * th.sin(),
        dth * phi.cos() + dpsi * th.cos() * phi.sin(),
        -dth * phi.sin() + dpsi * th.cos() * phi.cos(),
    );
    let dq = q.quaternion() * Quaternion::from_imag(omega) * 0.5;
    let (q, dq) = ([q.w, q.i, q.j, q.k], [dq.w, dq.i, dq.j, dq.k]);
    let table = scratch("rocket_6dof_quaternion.csv");
    let mut cmd = Command::cargo_bin("varmass").expect("the binary is built");
    cmd.args(["run", &model("rocket_6dof_quaternion.vms"), "--until"])
        .args([&UNTIL.to_string(), "--method", "dop853", "--tol=1e-12"]);
    for (name, value) in PARAMETERS {
        cmd.args(["--set", &format!("{name}={value}")]);
    }
    for (a, name) in ["x", "y", "z"].iter().enumerate() {
        cmd.args(["--init", &format!("{name}={}", POSITIONS[a])]);
        cmd.args(["--init", &format!("{name}'={}", RATES[a])]);
    }
    for (k, name) in ["e0", "e1", "e2", "e3"].iter().enumerate() {
        cmd.args(["--init", &format!("{name}={}", q[k])]);
        cmd.args(["--init", &format!("{name}'={}", dq[k])]);
    }
    cmd.args(["--init", &format!("m_p={GRAIN}")]);
    cmd.args(["--record", "x,y,z,m_p", "--csv"]).arg(&table);
    cmd.assert().success();
    let (_, rows) = csv(&table);
    let row = rows.last().expect("a row");
    assert_eq!(row[0], UNTIL);
    row[1..].to_vec()
}

#[test]
fn the_tool_flies_the_quaternion_rocket_as_the_zyx_rocket() {
    let zyx = tool("dop853", "--tol=1e-12");
    let quaternion = tool_quaternion();
    let zyx = [zyx[0], zyx[1], zyx[2], zyx[6]];
    let found = gap(&zyx, &quaternion);
    eprintln!("6-dof rocket, quaternion against zyx through the tool: {found:e}");
    // Measured: 6.2e-13 over the 3 s; the two derivations differ by the steppers' error at
    // 1e-12 (tests/rigid_quaternion.rs: it follows the tolerance). Bound 1e-10.
    assert!(found < 1e-10, "{found:e}");
}
