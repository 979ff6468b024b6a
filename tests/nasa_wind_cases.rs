//! NASA's check-cases 3 (tumbling brick with aerodynamic damping), 7 (dropped sphere in a
//! steady wind) and 8 (dropped sphere in a wind shear) of NASA/TM-2015-218675, flown by the
//! model files of `models/nasa/`, which are built from the library (J2 gravity, the
//! Earth-fixed WGS-84 frame, the 1976 atmosphere at the geodetic altitude, the wind, the
//! body axes and the aerodynamic coefficients), and compared at every time of NASA's CSVs
//! (every 0.1 s to 30 s) for every quantity the scenario records with the median of NASA's
//! simulations and their spread (`validation/nasa/case_NN.csv`), as
//! `tests/nasa_check_cases.rs` does for cases 1 and 2 (the same `nasa_support`).
//! `cargo test --release --test nasa_wind_cases -- --nocapture` prints the tables of
//! docs/validation.md#nasa-check-cases.

mod nasa_support;

use nasa_support::*;
use varmass::core::nalgebra::Vector3;
use varmass::prelude::*;

#[variable_mass_system(file = "models/nasa/case03_tumbling_brick_damping.vms")]
struct BrickWithDamping {
    cd: f64,
}

#[variable_mass_system(file = "models/nasa/case07_sphere_steady_wind.vms")]
struct SphereSteadyWind {
    east0: f64,
}

#[variable_mass_system(file = "models/nasa/case08_sphere_wind_shear.vms")]
struct SphereWindShear {}

const SEQUENCE: &str = "xyx";

/// The start of cases 3, 7 and 8 (as of 1 and 2): latitude 0, longitude 0, 9144 m, at rest
/// relative to the Earth, body x north, y east, z down — xyx(0, −π/2, 0) = R_y(−90°) in the
/// inertial frame, which coincides with the Earth-fixed one at t = 0 — turning at
/// `body_rates` (rad/s) relative to inertial space. Returns the velocity state [q, q̇].
fn start(body_rates: Vector3<f64>) -> SVector<f64, 12> {
    let r = ecef_of_geodetic(0.0, 0.0, 9144.0);
    let v = (Vector3::z() * OMEGA_E).cross(&r);
    let angles = [0.0, -std::f64::consts::FRAC_PI_2, 0.0];
    let body = ned_from_ecef(0.0, 0.0).transpose() * rotation("zyx", [0.0; 3]);
    assert!((rotation(SEQUENCE, angles) - body).norm() < 1e-15);
    let rates = angle_rates(SEQUENCE, angles, body_rates);
    SVector::<f64, 12>::from_column_slice(&[
        r.x, r.y, r.z, angles[0], angles[1], angles[2], v.x, v.y, v.z, rates[0], rates[1], rates[2],
    ])
}

/// Flies `system` from `start` with DOP853 at `tolerance`, landing on every time of the
/// reference.
fn fly<Sys: VariableMassSystem<6, 12>>(
    system: &Sys,
    start: &SVector<f64, 12>,
    reference: &Reference,
    tolerance: f64,
) -> Flight {
    fly_xyx(system, start, reference, tolerance, OMEGA_E)
}

/// The inertial position and velocity are recorded by sims 4, 5 and 6 only; their median
/// is one of the three and their spread their own disagreement. As in cases 1 and 2
/// (tests/nasa_check_cases.rs, the same start and the same measured ratios here for case
/// 3: x 1.01 at 24.9 s, vx 3.09 at 7.3 s, vy 1.11 at 23.7 s), ours lies just beyond the
/// extreme one at a few times; allowed 1.5, 4, 1.5.
const ECI_EXPLAINED: [(&str, f64); 3] = [("x_eci", 1.5), ("vx_eci", 4.0), ("vy_eci", 1.5)];

/// The brick's start: (10, 20, 30) deg/s relative to inertial space (case_03.csv's p, q, r at
/// t = 0; the Aetherion YAML's "10 deg/s − ω_E" for p is not NASA's data).
fn tumbling() -> SVector<f64, 12> {
    start(Vector3::new(10.0, 20.0, 30.0) * std::f64::consts::PI / 180.0)
}

/// Case 3: the brick of case 2 with roll, pitch and yaw damping (C_lp = C_mq = C_nr = −1)
/// and no drag. Measured (DOP853 at 1e-12): body rates p, q, r 9.1e-6, 3.3e-5, 3.7e-6
/// rad/s from the median (spread 5.4e-4, 1.3e-3, 2.8e-4), yaw, pitch, roll 4.9e-5,
/// 1.7e-4, 5.2e-4 rad, altitude 8.2e-7 m, down velocity 6.7e-8 m/s; every quantity within
/// the spread but the inertial ones (ECI_EXPLAINED); q reaches 0.9998 of the spread at
/// 9.6 s, on its edge: ours is sim 4's (below, 4.7e-8 rad/s), the extreme of the five
/// there, where the median is sim 1 and the spread |sim 4 − sim 1|; allowed 1.01 (ours and
/// sim 4 differ by 2.6e-9 rad/s there, either side of the edge). Bounds: about 3×.
#[test]
fn case_3_tumbling_brick_with_damping() {
    let reference = read_reference(3);
    let flight = fly(
        &BrickWithDamping { cd: 0.0 },
        &tumbling(),
        &reference,
        1e-12,
    );
    let rows = compare(&reference, &flight.ours);
    print_table(3, &rows);
    eprintln!(
        "closest to xyx's singular attitude {:.3} rad",
        flight.closest
    );
    // Ours against sim 4: measured p, q, r 4.0e-8, 4.7e-8, 7.7e-8 rad/s over the 30 s, where
    // the simulations differ from each other by up to 1.3e-3; bounds 3×.
    let singles = single_simulations(3, &flight.ours);
    assert_singles(
        &singles,
        &[("sim4_p", 1.2e-7), ("sim4_q", 1.5e-7), ("sim4_r", 2.5e-7)],
    );
    // The damped tumble keeps away from xyx's singular attitude: measured 0.891 rad.
    assert!(flight.closest > 0.8, "{}", flight.closest);
    let mut explained = ECI_EXPLAINED.to_vec();
    explained.push(("q", 1.01));
    assert_rows(
        &rows,
        &explained,
        &[
            ("x_eci", 3.2e-6),
            ("y_eci", 4.5e-8),
            ("z_eci", 2e-12),
            ("vx_eci", 2.4e-9),
            ("vy_eci", 4.3e-9),
            ("vz_eci", 1e-15),
            ("x_ecef", 3.2e-6),
            ("y_ecef", 1.7e-7),
            ("z_ecef", 2e-12),
            ("v_north", 1e-15),
            ("v_east", 1.5e-11),
            ("v_down", 2e-7),
            ("altitude", 2.5e-6),
            ("longitude", 3e-14),
            ("latitude", 1e-15),
            ("gravity", 8e-11),
            ("yaw", 1.5e-4),
            ("pitch", 5e-4),
            ("roll", 1.6e-3),
            ("p", 2.7e-5),
            ("q", 1e-4),
            ("r", 1.1e-5),
        ],
    );
}

/// NASA's data decide the brick's drag coefficient: the Aetherion YAML gives C_D = 0.0 in
/// its parameters and 0.01 in its header comment. With 0.01 the brick (S = 2/9 ft²) falls
/// slower: measured 156 m higher at 30 s, 1.1e6 times NASA's spread (1.4e-4 m), where C_D = 0
/// is 8.2e-7 m from the median (case_3 above).
#[test]
fn nasas_data_decide_the_bricks_drag_coefficient_is_zero() {
    let reference = read_reference(3);
    let flight = fly(
        &BrickWithDamping { cd: 0.01 },
        &tumbling(),
        &reference,
        1e-12,
    );
    let rows = compare(&reference, &flight.ours);
    print_table(3, &rows);
    let altitude = row(&rows, "altitude");
    assert!(
        altitude.deviation > 100.0 && altitude.ratio > 1e5,
        "{altitude:?}"
    );
}

/// The quantities of cases 7 and 8 but x_eci are within NASA's spread; x_eci reaches 1.05
/// of it (at 8.1 s in case 7, 7.7 s in case 8): ours is sim 4's to 2.9e-5 m over the 30 s
/// (below), sims 4, 5, 6 are 3.0e-4 and 3.0e-3 m apart, and where sim 5, the extreme one,
/// passes the median, ours lies 6.3e-7 m beyond it; allowed 1.1.
const SPHERE_EXPLAINED: [(&str, f64); 1] = [("x_eci", 1.1)];

/// Case 7: the sphere with drag (C_D = 0.1) in a steady 6.096 m/s wind towards the east.
/// Measured (DOP853 at 1e-12; the same at 1e-10): east velocity 2.7e-6 m/s from the median
/// (spread 7.4e-4), down velocity 2.2e-4 m/s (spread 3.1e-2), altitude 1.8e-3 m (spread
/// 0.19), ECI x 3.1e-4 m; ratios ≤ 0.95 but x_eci's. Bounds: about 3×.
#[test]
fn case_7_sphere_in_a_steady_wind() {
    let reference = read_reference(7);
    let system = SphereSteadyWind { east0: 6.096 };
    let flight = fly(&system, &start(Vector3::zeros()), &reference, 1e-12);
    let rows = compare(&reference, &flight.ours);
    print_table(7, &rows);
    // Ours against sim 4: measured 2.9e-5 m and 5.4e-6 m/s; bounds 3×.
    let singles = single_simulations(7, &flight.ours);
    assert_singles(&singles, &[("sim4_x_eci", 9e-5), ("sim4_vx_eci", 1.6e-5)]);
    assert_rows(
        &rows,
        &SPHERE_EXPLAINED,
        &sphere_bounds(2.7e-6 * 3.0, 7.7e-12 * 3.0),
    );
}

/// The bounds of cases 7 and 8 (about 3× what each measured; `v_east` and `longitude`
/// given, the one quantity the two winds move apart).
fn sphere_bounds(v_east: f64, longitude: f64) -> Vec<(&'static str, f64)> {
    vec![
        ("x_eci", 1e-3),
        ("y_eci", 1e-4),
        ("z_eci", 1e-15),
        ("vx_eci", 1.5e-4),
        ("vy_eci", 1e-5),
        ("vz_eci", 1e-15),
        ("x_ecef", 5.5e-3),
        ("y_ecef", 1.4e-3),
        ("z_ecef", 2e-14),
        ("v_north", 2e-15),
        ("v_east", v_east),
        ("v_down", 6.7e-4),
        ("altitude", 5.5e-3),
        ("longitude", longitude),
        ("latitude", 1e-15),
        ("gravity", 1.7e-8),
        ("yaw", 1e-15),
        ("pitch", 2e-16),
        ("roll", 1.5e-11),
        ("p", 1e-15),
        ("q", 1e-15),
        ("r", 1e-15),
    ]
}

/// Case 8: the sphere in a wind towards the east of −6.096 m/s + 0.003 h/s (h the geodetic
/// altitude). Measured: east velocity 7.2e-4 m/s from the median at 30 s (0.62 of the
/// spread there), down velocity 2.2e-4 m/s, altitude 1.8e-3 m, ECI x 3.1e-4 m.
#[test]
fn case_8_sphere_in_a_wind_shear() {
    let reference = read_reference(8);
    let flight = fly(
        &SphereWindShear {},
        &start(Vector3::zeros()),
        &reference,
        1e-12,
    );
    let rows = compare(&reference, &flight.ours);
    print_table(8, &rows);
    let singles = single_simulations(8, &flight.ours);
    assert_singles(&singles, &[("sim4_x_eci", 9e-5), ("sim4_vx_eci", 1.6e-5)]);
    assert_rows(&rows, &SPHERE_EXPLAINED, &sphere_bounds(2.2e-3, 2.1e-10));
}

/// The comparison can fail: case 7 in still air (east0 = 0) leaves the spread of the east
/// velocity (measured up to 0.87 m/s off, 2.2e3 times the spread: the wind's drag) and of
/// the longitude (1.1e3 times).
#[test]
fn without_the_wind_the_sphere_leaves_the_spread() {
    let reference = read_reference(7);
    let system = SphereSteadyWind { east0: 0.0 };
    let flight = fly(&system, &start(Vector3::zeros()), &reference, 1e-12);
    let rows = compare(&reference, &flight.ours);
    print_table(7, &rows);
    let east = row(&rows, "v_east");
    assert!(east.deviation > 0.5 && east.ratio > 1e3, "{east:?}");
    assert!(row(&rows, "longitude").ratio > 10.0);
}
