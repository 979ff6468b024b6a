//! NASA's check-cases 6 (sphere with drag), 9 (eastward cannonball) and 10 (northward
//! cannonball) of NASA/TM-2015-218675 flown by the model files of `models/nasa/`, built
//! from the library (J2 gravity, the Earth-fixed frame, the 1976 atmosphere at the geodetic
//! altitude, drag against the Earth-relative velocity), and compared at every time of
//! NASA's CSVs (every 0.1 s to 30 s) and for every quantity the scenario records with the
//! median of NASA's simulations and with their spread (`validation/nasa/case_NN.csv`), as
//! `tests/nasa_check_cases.rs` does for cases 1 and 2 (the same helpers,
//! `tests/nasa_support`). `cargo test --release --test nasa_drag_cases -- --nocapture`
//! prints the tables of docs/validation.md#check-cases-6-9-and-10-drag-on-a-rotating-earth.
//!
//! Also the drag components against closed forms: a vertical fall at constant density and
//! cd (`models/lib/drag.vms`), and a coast against a cd linear in the Mach number
//! (`models/lib/drag_mach.vms`, its table given at run time).

mod nasa_support;

use nasa_support::*;
use std::collections::HashMap;
use varmass::core::nalgebra::Vector3;
use varmass::prelude::*;

#[variable_mass_system(file = "models/nasa/case06_sphere_with_drag.vms")]
struct SphereWithDrag {}

#[variable_mass_system(file = "models/nasa/case09_eastward_cannonball.vms")]
struct EastwardCannonball {}

#[variable_mass_system(file = "models/nasa/case10_northward_cannonball.vms")]
struct NorthwardCannonball {}

const SEQUENCE: &str = "xyx";
const FT: f64 = 0.3048;

/// A case's start as NASA's scenario gives it.
struct Start {
    /// geodetic latitude, longitude (rad), altitude (m)
    geodetic: [f64; 3],
    /// Earth-relative velocity, north, east, down (m/s)
    velocity_ned: Vector3<f64>,
    /// relative to NED (rad)
    yaw_pitch_roll: [f64; 3],
    /// relative to inertial space, body axes (rad/s)
    body_rates: Vector3<f64>,
}

/// The velocity state [q, q̇] of a start in the inertial frame (aligned with the Earth-fixed
/// one at t = 0), the attitude in xyx angles (away from b = 0, π: asserted).
fn velocity_state(start: &Start) -> SVector<f64, 12> {
    let (r, v, body) = inertial_start(
        start.geodetic,
        start.velocity_ned,
        start.yaw_pitch_roll,
        OMEGA_E,
    );
    let angles = xyx_angles(&body);
    assert!(
        (rotation(SEQUENCE, angles) - body).norm() < 1e-15,
        "attitude"
    );
    assert!(angles[1].sin() > 0.5, "far from xyx's singular attitude");
    let rates = angle_rates(SEQUENCE, angles, start.body_rates);
    SVector::<f64, 12>::from_column_slice(&[
        r.x, r.y, r.z, angles[0], angles[1], angles[2], v.x, v.y, v.z, rates[0], rates[1], rates[2],
    ])
}

/// Flies `system` from `start` with DOP853 at 1e-13, landing on every time of the
/// reference, and returns NASA's quantities there.
fn fly<Sys: VariableMassSystem<6, 12>>(
    system: &Sys,
    start: &Start,
    reference: &Reference,
) -> HashMap<&'static str, Vec<f64>> {
    fly_xyx(system, &velocity_state(start), reference, 1e-13, OMEGA_E).ours
}

/// Writes our quantities at the reference's times to `target/tmp/nasa_case_NN_ours.csv`
/// (header `t,` and `QUANTITIES`), to hold them to single simulations by hand.
fn write_ours(case: u32, reference: &Reference, ours: &HashMap<&'static str, Vec<f64>>) {
    let mut text = format!("t,{}\n", QUANTITIES.join(","));
    for (i, t) in reference.times.iter().enumerate() {
        let values: Vec<String> = QUANTITIES
            .iter()
            .map(|q| format!("{:?}", ours[q][i]))
            .collect();
        text += &format!("{t:?},{}\n", values.join(","));
    }
    let path = format!(
        "{}/nasa_case_{case:02}_ours.csv",
        env!("CARGO_TARGET_TMPDIR")
    );
    std::fs::write(&path, text).expect("writable");
}

/// The Earth's rate in body axes of a body at rest relative to the Earth at latitude 0,
/// longitude 0 with the yaw `yaw` (pitch and roll 0): ω_E along north, which is body
/// (cos yaw, −sin yaw, 0).
fn turning_with_the_earth(yaw: f64) -> Vector3<f64> {
    Vector3::new(yaw.cos(), -yaw.sin(), 0.0) * OMEGA_E
}

/// Case 6's inertial position and velocity, recorded by sims 4, 5 and 6 only, whose spread is
/// their own disagreement (sim 4 starts 1.24e-5 m higher, as in case 1; sim 6's density,
/// 2.1e-5 from the standard's, drifts it 3.3e-3 m by 30 s): at 7.4 s the median is sim 4,
/// 7.8e-6 m from ours where sim 5 is 3.8e-7 m; at 18.7 s the three agree on vy to 1.1e-10
/// m/s and lie 1.4e-9 to 1.5e-9 m/s (3e-12 of 465.7 m/s) from ours, which is converged to
/// 1.7e-13 m/s (DOP853 at 1e-10, 1e-12, 3e-14). Measured ratios: x 1.0499 (7.4 s), y 1.1426
/// (25.7 s), vy 24.67 (18.7 s); allowed 1.3, 1.4, 30.
const CASE_6_EXPLAINED: [(&str, f64); 3] = [("x_eci", 1.3), ("y_eci", 1.4), ("vy_eci", 30.0)];

/// The ECEF position, recorded by sims 1, 3, 5 and 6 only: two of them (1, 3), whose density
/// is 5.7e-4 to 2.8e-3 from the standard's formulas, 1.3 m from ours after 30 s, two (5, 6),
/// within 1e-5 of the formulas, 4.3e-3 and 0.1 m from ours. The median of four, the mean of the middle two, lies halfway between the
/// groups and the spread is half their gap; ours, with sim 5, is a few mm beyond it. Measured
/// (case 9): x 1.0065 (22.9 s), y 1.0059 (1.5 s); allowed 1.05.
const CASE_9_EXPLAINED: [(&str, f64); 2] = [("x_ecef", 1.05), ("y_ecef", 1.05)];

/// The ECEF position as in case 9, measured x 1.0065 (20.7 s), z 1.0060 (1.5 s); and the
/// pitch: sims 1, 2 and 6 tilt their NED axes with the geocentric latitude, 7.2e-6 to 7.5e-6
/// rad below the geodetic one's at 30 s (e² φ = 6.69e-3 × 1.08e-3 = 7.3e-6 rad), so the median
/// of five is one of them and ours, 2.2e-10 rad from sim 4, is at the spread's edge: 1.0004
/// (4.3 s). Allowed 1.05.
const CASE_10_EXPLAINED: [(&str, f64); 3] = [("x_ecef", 1.05), ("z_ecef", 1.05), ("pitch", 1.05)];

#[test]
fn case_6_sphere_with_drag() {
    let reference = read_reference(6);
    // TM scenario 6: at 30 000 ft, at rest relative to the Earth, level (yaw 0), not
    // rotating relative to inertial space (NASA's p, q, r are 0 at t = 0, spread 2e-20).
    let start = Start {
        geodetic: [0.0, 0.0, 30_000.0 * FT],
        velocity_ned: Vector3::zeros(),
        yaw_pitch_roll: [0.0; 3],
        body_rates: Vector3::zeros(),
    };
    let ours = fly(&SphereWithDrag {}, &start, &reference);
    write_ours(6, &reference, &ours);
    let rows = compare(&reference, &ours);
    print_table(6, &rows);
    let singles = single_simulations(6, &ours);
    assert_singles(
        &singles,
        &[
            ("sim4_x_eci", 3.8e-5),
            ("sim4_vx_eci", 8e-6),
            ("sim4_altitude", 2.2e-5),
            ("sim4_v_down", 8e-6),
        ],
    );
    assert_rows(
        &rows,
        &CASE_6_EXPLAINED,
        &[
            ("x_eci", 1e-3),
            ("y_eci", 2e-7),
            ("z_eci", 1e-15),
            ("vx_eci", 1.5e-4),
            ("vy_eci", 1.2e-8),
            ("vz_eci", 1e-15),
            ("x_ecef", 5.5e-3),
            ("y_ecef", 3e-4),
            ("z_ecef", 2e-14),
            ("v_north", 5e-15),
            ("v_east", 2e-6),
            ("v_down", 6.5e-4),
            ("altitude", 5.5e-3),
            ("longitude", 4e-11),
            ("latitude", 1e-15),
            ("gravity", 1.7e-8),
            ("yaw", 1e-15),
            ("pitch", 1e-15),
            ("roll", 3e-13),
            ("p", 1e-15),
            ("q", 1e-15),
            ("r", 1e-15),
        ],
    );
}

#[test]
fn case_9_eastward_cannonball() {
    let reference = read_reference(9);
    // TM scenario 9: from the ground at 1000 ft/s east and 1000 ft/s up, yaw 90° (body x
    // east), turning with the Earth (NASA's q = −ω_E at t = 0).
    let yaw = std::f64::consts::FRAC_PI_2;
    let start = Start {
        geodetic: [0.0, 0.0, 0.0],
        velocity_ned: Vector3::new(0.0, 1000.0, -1000.0) * FT,
        yaw_pitch_roll: [yaw, 0.0, 0.0],
        body_rates: turning_with_the_earth(yaw),
    };
    let ours = fly(&EastwardCannonball {}, &start, &reference);
    write_ours(9, &reference, &ours);
    let rows = compare(&reference, &ours);
    print_table(9, &rows);
    let singles = single_simulations(9, &ours);
    assert_singles(
        &singles,
        &[
            ("sim4_altitude", 1.7e-3),
            ("sim4_v_east", 9e-5),
            ("sim4_v_down", 6.5e-5),
            ("sim4_longitude", 3.3e-10),
        ],
    );
    assert_rows(
        &rows,
        &CASE_9_EXPLAINED,
        &[
            ("x_eci", 1.3e-2),
            ("y_eci", 1.7e-2),
            ("z_eci", 1e-12),
            ("vx_eci", 5e-4),
            ("vy_eci", 7.5e-4),
            ("vz_eci", 4e-14),
            ("x_ecef", 2.1),
            ("y_ecef", 2.2),
            ("z_ecef", 1.2e-12),
            ("v_north", 6e-14),
            ("v_east", 3.5e-2),
            ("v_down", 3e-2),
            ("altitude", 0.82),
            ("longitude", 1.5e-7),
            ("latitude", 1e-15),
            ("gravity", 4.2e-6),
            ("yaw", 1e-15),
            ("pitch", 2.6e-9),
            ("roll", 1e-15),
            ("p", 1e-15),
            ("q", 7e-12),
            ("r", 1e-15),
        ],
    );
}

#[test]
fn case_10_northward_cannonball() {
    let reference = read_reference(10);
    // TM scenario 10: from the ground at 1000 ft/s north and 1000 ft/s up, yaw 0 (body x
    // north), turning with the Earth (NASA's p = ω_E at t = 0).
    let start = Start {
        geodetic: [0.0, 0.0, 0.0],
        velocity_ned: Vector3::new(1000.0, 0.0, -1000.0) * FT,
        yaw_pitch_roll: [0.0; 3],
        body_rates: turning_with_the_earth(0.0),
    };
    let ours = fly(&NorthwardCannonball {}, &start, &reference);
    write_ours(10, &reference, &ours);
    let rows = compare(&reference, &ours);
    print_table(10, &rows);
    let singles = single_simulations(10, &ours);
    assert_singles(
        &singles,
        &[
            ("sim4_altitude", 1.7e-3),
            ("sim4_v_north", 9e-5),
            ("sim4_v_down", 6.5e-5),
            ("sim4_latitude", 3.3e-10),
            ("sim4_pitch", 3.3e-10),
        ],
    );
    assert_rows(
        &rows,
        &CASE_10_EXPLAINED,
        &[
            ("x_eci", 1.3e-2),
            ("y_eci", 1.5e-6),
            ("z_eci", 1.7e-2),
            ("vx_eci", 5e-4),
            ("vy_eci", 1e-7),
            ("vz_eci", 7.5e-4),
            ("x_ecef", 2.1),
            ("y_ecef", 3.3e-3),
            ("z_ecef", 2.2),
            ("v_north", 3.6e-2),
            ("v_east", 1.2e-4),
            ("v_down", 3.2e-2),
            ("altitude", 0.9),
            ("longitude", 4.5e-10),
            ("latitude", 3.5e-7),
            ("gravity", 4.3e-6),
            ("yaw", 1e-15),
            ("pitch", 2.2e-5),
            ("roll", 1e-10),
            ("p", 1e-15),
            ("q", 1e-15),
            ("r", 1e-15),
        ],
    );
}

#[variable_mass_system(file = "tests/data/library/drag_fall.vms")]
struct DragFall {
    m0: f64,
    rho0: f64,
    cd: f64,
    area: f64,
}

#[variable_mass_system(file = "tests/data/library/drag_mach_coast.vms")]
struct DragMachCoast {
    m0: f64,
    rho0: f64,
    a0: f64,
    area: f64,
    drag_cd: varmass::core::table::Tabulated,
}

/// Flies a one-coordinate system from (q, q̇) to each of `times`; returns (q, q̇) there.
fn fly_1d<Sys: VariableMassSystem<1, 2>>(
    system: &Sys,
    start: [f64; 2],
    times: &[f64],
) -> Vec<[f64; 2]> {
    let initial = system.momentum_state(0.0, &SVector::<f64, 2>::from_column_slice(&start));
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: 1e-13,
        absolute_tolerance: 1e-13,
        ..AdaptiveControl::default()
    });
    let mut stepper = Dop853::new(system, 0.0, initial, control).expect("stepper");
    times
        .iter()
        .map(|&t| {
            let solution = run(&mut stepper, &RunConfig::until(t).continuing(), &[]).unwrap();
            let state = *solution.states.last().unwrap();
            [state[0], system.velocities(t, &state).expect("q̇")[0]]
        })
        .collect()
}

/// A vertical fall at constant density and cd through `lib/drag.vms` against its closed form.
/// By hand: m z̈ = −m g − k ż|ż| (k = ½ ρ cd S; the component's force −½ ρ |V| V cd S along z
/// with V = (0, 0, ż)). Falling, u = −ż > 0: u̇ = g − (k/m) u², solved by u = v_T tanh(g t/v_T)
/// with v_T = √(m g/k) (u̇ = g sech² = g (1 − tanh²) = g − g u²/v_T²), u(0) = 0; and
/// z = z₀ − (v_T²/g) ln cosh(g t/v_T) (its derivative −v_T tanh).
#[test]
fn drag_falls_to_the_terminal_velocity_of_the_closed_form() {
    let system = DragFall {
        m0: 2.0,
        rho0: 1.225,
        cd: 0.47,
        area: 0.0182,
    };
    let g: f64 = 9.80665;
    let k: f64 = 0.5 * 1.225 * 0.47 * 0.0182;
    let v_t = (2.0 * g / k).sqrt();
    let times: Vec<f64> = (1..=40).map(|i| 0.5 * i as f64).collect();
    let flown = fly_1d(&system, [0.0, 0.0], &times);
    let (mut worst_v, mut worst_z) = (0.0_f64, 0.0_f64);
    for (&t, [z, v]) in times.iter().zip(&flown) {
        let x = g * t / v_t;
        worst_v = worst_v.max((v + v_t * x.tanh()).abs() / v_t);
        worst_z = worst_z.max((z + v_t * v_t / g * x.cosh().ln()).abs() / (v_t * t));
    }
    eprintln!(
        "drag fall: v_T {v_t:.3} m/s, max |Δv|/v_T {worst_v:.1e}, |Δz|/(v_T t) {worst_z:.1e}"
    );
    // Measured: 9.3e-16 and 7.0e-16; bound 1e-13 (100×: DOP853's error at its tolerance
    // here, which a closed form of the wrong drag would exceed by orders of magnitude).
    assert!(
        worst_v < 1e-13 && worst_z < 1e-13,
        "{worst_v:e} {worst_z:e}"
    );
}

/// A coast through `lib/drag_mach.vms` with cd = k_c M (a linear table through (0, 0): exact)
/// against its closed form. By hand: m ẍ = −½ ρ S (k_c ẋ/a) ẋ² for ẋ > 0, i.e. ẍ = −c ẋ³,
/// c = ρ S k_c/(2 m a); d(1/ẋ²)/dt = −2 ẍ/ẋ³ = 2c, so ẋ = v₀/√(1 + 2 c v₀² t) and
/// x = (√(1 + 2 c v₀² t) − 1)/(c v₀) (its derivative v₀/√(…)).
#[test]
fn drag_from_a_mach_table_decelerates_as_the_closed_form() {
    use varmass_table::Points;
    let k_c = 0.2;
    let points = Points::new(vec![0.0, 5.0], vec![0.0, 5.0 * k_c]).expect("points");
    let system = DragMachCoast {
        m0: 1.0,
        rho0: 1.2,
        a0: 340.0,
        area: 0.01,
        drag_cd: DragMachCoast::tabulate_drag_cd(&points),
    };
    let c = 1.2 * 0.01 * k_c / (2.0 * 1.0 * 340.0);
    let v0 = 600.0;
    let times: Vec<f64> = (1..=20).map(|i| 0.5 * i as f64).collect();
    let flown = fly_1d(&system, [0.0, v0], &times);
    let (mut worst_v, mut worst_x) = (0.0_f64, 0.0_f64);
    for (&t, [x, v]) in times.iter().zip(&flown) {
        let s = (1.0 + 2.0 * c * v0 * v0 * t).sqrt();
        worst_v = worst_v.max((v - v0 / s).abs() / (v0 / s));
        worst_x = worst_x.max((x - (s - 1.0) / (c * v0)).abs() / x);
    }
    eprintln!("Mach coast: max |Δv|/v {worst_v:.1e}, |Δx|/x {worst_x:.1e}");
    // Measured: 1.2e-15 (v) and below it (x); bound 1e-13 (~100×, as the fall above).
    assert!(
        worst_v < 1e-13 && worst_x < 1e-13,
        "{worst_v:e} {worst_x:e}"
    );
}
