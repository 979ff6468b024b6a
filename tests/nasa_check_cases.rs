//! NASA's six-degree-of-freedom check-cases (NASA/TM-2015-218675, Murri et al., 2015) flown
//! by the model files of `models/nasa/` and compared, at every time of NASA's CSVs (every
//! 0.1 s to 30 s) and for every quantity the scenario records, with the median of NASA's
//! simulations and with their spread (the largest |simulation − median| at that time),
//! stored in `validation/nasa/case_NN.csv` by `validation/nasa/extract.py`.
//!
//! The models are written in an Earth-centred inertial frame; `nasa_support` turns a run
//! into NASA's Earth-fixed quantities (ECEF position, Earth-relative velocity in local NED
//! axes, geodetic altitude, latitude and longitude on the WGS-84 ellipsoid, gravity, the
//! yaw-pitch-roll of the body relative to local NED, body rates relative to inertial space).
//! `cargo test --release --test nasa_check_cases -- --nocapture` prints the tables of
//! docs/validation.md#nasa-check-cases.

mod nasa_support;

use nasa_support::*;
use varmass::core::nalgebra::Vector3;
use varmass::prelude::*;

#[variable_mass_system(file = "models/nasa/case01_dropped_sphere.vms")]
struct DroppedSphere {}

#[variable_mass_system(file = "models/nasa/case02_tumbling_brick.vms")]
struct TumblingBrick {}

const SEQUENCE: &str = "xyx";

/// slug·ft² in kg·m²: slug = 0.45359237 kg × 9.80665 m/s² / 0.3048 m, ft = 0.3048 m.
const SLUG_FT2: f64 = 0.453_592_37 * 9.806_65 / 0.3048 * 0.3048 * 0.3048;

/// The TM's inertias (slug·ft²): the sphere 3.6 about every axis; the brick (Table 4).
fn sphere_inertia() -> Vector3<f64> {
    Vector3::repeat(3.6) * SLUG_FT2
}

fn brick_inertia() -> Vector3<f64> {
    Vector3::new(0.001_894_220, 0.006_211_019, 0.007_194_665) * SLUG_FT2
}

/// A case's start as NASA gives it: geodetic latitude, longitude, altitude, Earth-relative
/// velocity in NED, yaw-pitch-roll relative to NED, body rates relative to inertial space.
struct Start {
    latitude: f64,
    longitude: f64,
    altitude: f64,
    velocity_ned: Vector3<f64>,
    yaw_pitch_roll: [f64; 3],
    body_rates: Vector3<f64>,
}

/// The velocity state [q, q̇] of a start, the Earth turned by `earth_rate` (t = 0: the
/// inertial frame coincides with the Earth-fixed one).
fn velocity_state(start: &Start, earth_rate: f64) -> SVector<f64, 12> {
    let r = ecef_of_geodetic(start.latitude, start.longitude, start.altitude);
    let ned = ned_from_ecef(start.latitude, start.longitude);
    let v = ned.transpose() * start.velocity_ned + (Vector3::z() * earth_rate).cross(&r);
    let [yaw, pitch, roll] = start.yaw_pitch_roll;
    let body = ned.transpose() * rotation("zyx", [yaw, pitch, roll]);
    // xyx(0, -π/2, 0) is R_y(-90°): body x north, y east, z down at latitude and longitude 0,
    // the start of cases 1 and 2 (held here, so another start fails loudly).
    let angles = [0.0, -std::f64::consts::FRAC_PI_2, 0.0];
    assert!(
        (rotation(SEQUENCE, angles) - body).norm() < 1e-15,
        "start attitude"
    );
    let rates = angle_rates(SEQUENCE, angles, start.body_rates);
    SVector::<f64, 12>::from_column_slice(&[
        r.x, r.y, r.z, angles[0], angles[1], angles[2], v.x, v.y, v.z, rates[0], rates[1], rates[2],
    ])
}

/// A flight's quantities at the reference's times, and what it conserves.
struct Conserved {
    flight: Flight,
    /// max |H(t) − H(0)| / |H(0)| (H = T + m U: no force depends on t in the inertial frame)
    energy_drift: f64,
    /// max |h(t) − h(0)| / |h(0)|, h = R I ω_b the spin about the centre in inertial axes
    /// (gravity acts at the centre: no torque)
    spin_drift: f64,
}

/// Flies `system` (principal inertias `inertia`) from `start` with DOP853 at 1e-13,
/// landing on every time of the reference (`nasa_support::fly_xyx`, the Earth turning at
/// `earth_rate` in the conversion too), and measures what it conserves there.
fn fly<Sys: VariableMassSystem<6, 12>>(
    system: &Sys,
    inertia: Vector3<f64>,
    start: &Start,
    reference: &Reference,
    earth_rate: f64,
) -> Conserved {
    let start = velocity_state(start, earth_rate);
    let flight = fly_xyx(system, &start, reference, 1e-13, earth_rate);
    let (mut energy_drift, mut spin_drift) = (0.0_f64, 0.0_f64);
    let (mut energy0, mut spin0) = (None, None);
    for (&t, state) in reference.times.iter().zip(&flight.states) {
        let energy = system.hamiltonian(t, state).expect("H");
        let energy0 = *energy0.get_or_insert(energy);
        energy_drift = energy_drift.max((energy / energy0 - 1.0).abs());
        let rates = system.velocities(t, state).expect("q̇");
        let angles = [state[3], state[4], state[5]];
        let omega = body_rates(SEQUENCE, angles, [rates[3], rates[4], rates[5]]);
        let spin = rotation(SEQUENCE, angles) * inertia.component_mul(&omega);
        let spin0 = *spin0.get_or_insert(spin);
        let drift = (spin - spin0).norm() / spin0.norm().max(f64::MIN_POSITIVE);
        spin_drift = spin_drift.max(drift);
    }
    Conserved {
        flight,
        energy_drift,
        spin_drift,
    }
}

fn report(flight: &Conserved) {
    eprintln!(
        "closest to xyx's singular attitude {:.3} rad; H kept to {:.1e}, the spin to {:.1e}",
        flight.flight.closest, flight.energy_drift, flight.spin_drift
    );
}

/// At latitude 0, longitude 0, 9144 m, at rest relative to the Earth.
fn equator_start(body_rates: Vector3<f64>) -> Start {
    Start {
        latitude: 0.0,
        longitude: 0.0,
        altitude: 9144.0,
        velocity_ned: Vector3::zeros(),
        yaw_pitch_roll: [0.0; 3],
        body_rates,
    }
}

/// The inertial position and velocity are recorded by sims 4, 5 and 6 only, whose spread is
/// their own disagreement at 1e-6 m and 1e-9 m/s (1.6e-13 and 2e-12 relative): sim 4 starts
/// 1.24e-5 m higher (6387281.000012 m) with ω_E r 1.3e-9 m/s larger, sim 6 2.1e-7 m
/// higher; ours starts as sim 5 (6387281 m, 465.76787589315 m/s) and stays within 5.7e-8 m
/// and 1.5e-9 m/s of it (`case_01_sims.csv`, asserted), converged to 3e-9 m (DOP853 at 1e-9 to
/// 3e-14 and Taylor at 1e-15 agree). The median of three is then sim 6, 1.07e-6 m and
/// 7.8e-10 m/s from us, at times just beyond the other two: measured ratios x 1.006 (24.9 s),
/// vx 3.09 (7.3 s), vy 1.11 (23.7 s); allowed 1.5, 4, 1.5.
const ECI_EXPLAINED: [(&str, f64); 3] = [("x_eci", 1.5), ("vx_eci", 4.0), ("vy_eci", 1.5)];

/// Case 1: a sphere dropped without drag. Measured (DOP853 at 1e-13; the same to three
/// digits at 1e-10, so these are distances of the median, not our integration error):
/// ECEF x 1.08e-6 m, y 1.07e-7 m, altitude 5.1e-7 m, down velocity 1.1e-9 m/s, east
/// 2.8e-12 m/s, longitude 1.7e-14 rad, roll 8.1e-15 rad, gravity 5.6e-11 m/s²; the rest at
/// rounding. Bounds: about 3× those (the regression margin), 1e-15 for the rounding ones.
/// NASA's spread is 4.6e-4 m (x), 4.9e-4 m (altitude), 2.1e-4 m/s (east): the median of
/// sims 3-6 agree to ~1e-6 m, sims 1 and 2 lie further out.
#[test]
fn case_1_dropped_sphere_over_a_rotating_earth() {
    let reference = read_reference(1);
    let start = equator_start(Vector3::zeros());
    let flight = fly(
        &DroppedSphere {},
        sphere_inertia(),
        &start,
        &reference,
        OMEGA_E,
    );
    let rows = compare(&reference, &flight.flight.ours);
    print_table(1, &rows);
    report(&flight);
    // Ours against sim 5, which starts as ours does (below): measured 5.1e-8, 5.7e-8 m,
    // 1.5e-9, 1.4e-9 m/s; bounds 3× those.
    let singles = single_simulations(1, &flight.flight.ours);
    let bounds = [
        ("sim5_x_eci", 1.5e-7),
        ("sim5_y_eci", 1.7e-7),
        ("sim5_vx_eci", 4.5e-9),
        ("sim5_vy_eci", 4.5e-9),
    ];
    assert_singles(&singles, &bounds);
    // Measured: the spin stays 0 (no rate, no torque), H to 6.7e-16; bound 1e-14 (rounding).
    assert!(flight.spin_drift == 0.0 && flight.energy_drift < 1e-14);
    assert_rows(
        &rows,
        &ECI_EXPLAINED,
        &[
            ("x_eci", 3e-6),
            ("y_eci", 5e-8),
            ("z_eci", 1e-15),
            ("vx_eci", 2.5e-9),
            ("vy_eci", 4.5e-9),
            ("vz_eci", 1e-15),
            ("x_ecef", 3e-6),
            ("y_ecef", 3e-7),
            ("z_ecef", 1e-12),
            ("v_north", 1e-15),
            ("v_east", 1e-11),
            ("v_down", 3e-9),
            ("altitude", 1.5e-6),
            ("longitude", 5e-14),
            ("latitude", 1e-15),
            ("gravity", 2e-10),
            ("yaw", 1e-15),
            ("pitch", 1e-15),
            ("roll", 3e-14),
            ("p", 1e-15),
            ("q", 1e-15),
            ("r", 1e-15),
        ],
    );
}

/// Case 2: a brick tumbling without aerodynamic loads. Measured (DOP853 at 1e-13, the same
/// at 1e-10): body rates p, q, r 6.3e-7, 8.7e-7, 2.5e-7 rad/s (NASA's spread 5.3e-5,
/// 8.3e-5, 2.0e-5), yaw, pitch, roll 1.5e-6, 8.0e-7, 1.0e-6 rad (spread 2.3e-2, 6.0e-2,
/// 6.5e-2, largest where the pitch nears ±90°), ECEF x 1.07e-6 m, altitude 8.2e-7 m, down
/// velocity 6.8e-9 m/s. Bounds: about 3× those.
#[test]
fn case_2_tumbling_brick() {
    let reference = read_reference(2);
    let deg = std::f64::consts::PI / 180.0;
    let start = equator_start(Vector3::new(10.0, 20.0, 30.0) * deg);
    let flight = fly(
        &TumblingBrick {},
        brick_inertia(),
        &start,
        &reference,
        OMEGA_E,
    );
    let rows = compare(&reference, &flight.flight.ours);
    print_table(2, &rows);
    report(&flight);
    // Ours against sims 1 and 4, which agree with each other as closely: measured yaw,
    // pitch, roll 4.7e-11, 4.4e-11, 4.9e-11 rad (sim 4's yaw 9.8e-11, its file in degrees to
    // 12 digits) and p, q, r 4.9e-12, 6.3e-12, 2.8e-12 rad/s; bounds 3× those.
    let singles = single_simulations(2, &flight.flight.ours);
    let mut bounds = Vec::new();
    for sim in ["sim1", "sim4"] {
        let yaw = if sim == "sim4" { 3e-10 } else { 1.5e-10 };
        for (name, bound) in [("yaw", yaw), ("pitch", 1.5e-10), ("roll", 1.5e-10)] {
            bounds.push((format!("{sim}_{name}"), bound));
        }
        for name in ["p", "q", "r"] {
            bounds.push((format!("{sim}_{name}"), 2e-11));
        }
    }
    let bounds: Vec<(&str, f64)> = bounds.iter().map(|(n, b)| (n.as_str(), *b)).collect();
    assert_singles(&singles, &bounds);
    // The tumble keeps away from xyx's singular attitude (b = 0 or π): measured 0.913 rad.
    // H and the spin h = R I ω: measured 6.7e-16 and 6.6e-15; bound 1e-10 (the issue's).
    assert!(flight.flight.closest > 0.8, "{}", flight.flight.closest);
    assert!(flight.energy_drift < 1e-10 && flight.spin_drift < 1e-10);
    assert_rows(
        &rows,
        &ECI_EXPLAINED,
        &[
            ("x_eci", 3e-6),
            ("y_eci", 5e-8),
            ("z_eci", 3e-12),
            ("vx_eci", 2.5e-9),
            ("vy_eci", 4.5e-9),
            ("vz_eci", 1e-15),
            ("x_ecef", 3e-6),
            ("y_ecef", 2e-8),
            ("z_ecef", 3e-12),
            ("v_north", 1e-15),
            ("v_east", 2e-11),
            ("v_down", 2e-8),
            ("altitude", 2.5e-6),
            ("longitude", 3e-15),
            ("latitude", 1e-15),
            ("gravity", 1e-10),
            ("yaw", 5e-6),
            ("pitch", 2.5e-6),
            ("roll", 3e-6),
            ("p", 2e-6),
            ("q", 2.5e-6),
            ("r", 7.5e-7),
        ],
    );
}

/// The comparison can fail: the same flights on an Earth that does not turn (no ω × r in
/// the start, no turning of the Earth-fixed frame) leave NASA's spread. Measured: case 1's
/// east velocity 0.64 m/s and altitude 15 m off (Coriolis; centrifugal ω² r = 0.034 m/s²
/// over 30 s), case 2's roll 2.2e-3 rad off (ω_E t about the north axis).
#[test]
fn without_the_earths_rotation_the_cases_leave_the_spread() {
    let reference = read_reference(1);
    let start = equator_start(Vector3::zeros());
    let flight = fly(&DroppedSphere {}, sphere_inertia(), &start, &reference, 0.0);
    let rows = compare(&reference, &flight.flight.ours);
    print_table(1, &rows);
    assert!(
        row(&rows, "v_east").deviation > 0.6,
        "{:?}",
        row(&rows, "v_east")
    );
    assert!(
        row(&rows, "altitude").deviation > 10.0,
        "{:?}",
        row(&rows, "altitude")
    );
    assert!(row(&rows, "v_east").ratio > 1e3 && row(&rows, "altitude").ratio > 1e4);

    let reference = read_reference(2);
    let deg = std::f64::consts::PI / 180.0;
    let start = equator_start(Vector3::new(10.0, 20.0, 30.0) * deg);
    let flight = fly(&TumblingBrick {}, brick_inertia(), &start, &reference, 0.0);
    let rows = compare(&reference, &flight.flight.ours);
    print_table(2, &rows);
    assert!(
        row(&rows, "roll").deviation > 2e-3,
        "{:?}",
        row(&rows, "roll")
    );
}
