//! NASA's check-cases (NASA/TM-2015-218675): the stored medians and spreads of NASA's
//! simulations (`validation/nasa/case_NN.csv`, written by `validation/nasa/extract.py`),
//! the conversion of a run written in an Earth-centred inertial frame to NASA's
//! Earth-fixed quantities, and the comparison table. Written here from the definitions
//! (WGS-84 ellipsoid, NED axes, aerospace yaw-pitch-roll), independently of the derivation.
#![allow(dead_code)]

use std::collections::HashMap;
use varmass::core::nalgebra::{Matrix3, SVector, Vector3};
use varmass::prelude::*;

/// WGS-84 (NIMA TR8350.2): semi-major axis, flattening, Earth rate, GM, J2.
pub const A_E: f64 = 6_378_137.0;
pub const F_E: f64 = 1.0 / 298.257_223_563;
pub const OMEGA_E: f64 = 7.292_115e-5;
pub const MU_E: f64 = 3.986_004_418e14;
pub const J2: f64 = 1.082_629_821_313e-3;

/// The quantities NASA records that a run of ours gives, in the order of the CSV: the
/// inertial (ECI, aligned with ECEF at t = 0) position and velocity, the ECEF position, the
/// Earth-relative velocity in NED axes, geodetic altitude, longitude, latitude, the local
/// gravity, yaw, pitch, roll relative to NED, the body rates relative to inertial space.
pub const QUANTITIES: [&str; 22] = [
    "x_eci",
    "y_eci",
    "z_eci",
    "vx_eci",
    "vy_eci",
    "vz_eci",
    "x_ecef",
    "y_ecef",
    "z_ecef",
    "v_north",
    "v_east",
    "v_down",
    "altitude",
    "longitude",
    "latitude",
    "gravity",
    "yaw",
    "pitch",
    "roll",
    "p",
    "q",
    "r",
];

/// The rounding floor of a quantity: a few units in the last place of its size in double
/// precision (positions ~6.4e6 m, whose ulp is 9.3e-10 m; inertial velocities ~465 m/s,
/// ulp 5.7e-14 m/s; angles ~π, ulp 4.4e-16; g ~9.8 m/s², ulp 1.8e-15). NASA's spread is 0
/// at t = 0 and for quantities that stay 0 (latitude on the equator), where ours and the
/// median may differ by rounding: |ours − median| ≤ spread + floor is "within".
pub fn floor(name: &str) -> f64 {
    match name {
        "x_eci" | "y_eci" | "z_eci" | "x_ecef" | "y_ecef" | "z_ecef" | "altitude" => 1e-8,
        "vx_eci" | "vy_eci" | "vz_eci" | "v_north" | "v_east" | "v_down" => 1e-12,
        "gravity" => 1e-14,
        _ => 2e-15,
    }
}

/// Angles compared modulo 2π.
fn is_wrapped(name: &str) -> bool {
    matches!(name, "yaw" | "roll" | "longitude")
}

/// One case's reference: times, and per quantity the median and the spread at each time.
pub struct Reference {
    pub times: Vec<f64>,
    pub median: HashMap<String, Vec<f64>>,
    pub spread: HashMap<String, Vec<f64>>,
}

/// The named columns of a CSV of `validation/nasa/` (lines starting `#` skipped).
fn read_columns(file: &str) -> Vec<(String, Vec<f64>)> {
    let path = format!("{}/validation/nasa/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let mut columns: Vec<Vec<f64>> = vec![Vec::new(); header.len()];
    for line in lines {
        for (column, field) in columns.iter_mut().zip(line.split(',')) {
            column.push(field.parse().expect("a number"));
        }
    }
    header.iter().map(|h| h.to_string()).zip(columns).collect()
}

pub fn read_reference(case: u32) -> Reference {
    let columns = read_columns(&format!("case_{case:02}.csv"));
    let mut reference = Reference {
        times: columns[0].1.clone(),
        median: HashMap::new(),
        spread: HashMap::new(),
    };
    for (name, column) in columns {
        match name.strip_suffix("_spread") {
            Some(base) => reference.spread.insert(base.to_string(), column),
            None => reference.median.insert(name, column),
        };
    }
    reference
}

/// The largest |ours − simulation| of each column `simNN_NAME` of `case_NN_sims.csv` (the
/// same times as the medians), printed, as (column, deviation).
pub fn single_simulations(case: u32, ours: &HashMap<&str, Vec<f64>>) -> Vec<(String, f64)> {
    let mut found = Vec::new();
    for (column, values) in read_columns(&format!("case_{case:02}_sims.csv"))
        .into_iter()
        .skip(1)
    {
        let name = column.split_once('_').expect("simNN_NAME").1;
        let mut deviation = 0.0_f64;
        for (ours, theirs) in ours[name].iter().zip(&values) {
            let mut difference = ours - theirs;
            if is_wrapped(name) {
                difference = difference.sin().atan2(difference.cos());
            }
            deviation = deviation.max(difference.abs());
        }
        eprintln!("case {case}: max |ours − {column}| = {deviation:.2e}");
        found.push((column, deviation));
    }
    found
}

/// Rotation about a body axis ('x', 'y', 'z') by `angle`.
pub fn about(axis: char, angle: f64) -> Matrix3<f64> {
    let (s, c) = angle.sin_cos();
    match axis {
        'x' => Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c),
        'y' => Matrix3::new(c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c),
        _ => Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0),
    }
}

/// R (body to world) of an intrinsic sequence: R_a1(η1) R_a2(η2) R_a3(η3).
pub fn rotation(sequence: &str, angles: [f64; 3]) -> Matrix3<f64> {
    let axes: Vec<char> = sequence.chars().collect();
    about(axes[0], angles[0]) * about(axes[1], angles[1]) * about(axes[2], angles[2])
}

fn unit(axis: char) -> Vector3<f64> {
    match axis {
        'x' => Vector3::x(),
        'y' => Vector3::y(),
        _ => Vector3::z(),
    }
}

/// Body rates of an intrinsic sequence: ω_b = Σ_k (R_a(k+1) ⋯ R_a3)ᵀ e_ak η̇_k.
pub fn body_rates(sequence: &str, angles: [f64; 3], rates: [f64; 3]) -> Vector3<f64> {
    let axes: Vec<char> = sequence.chars().collect();
    let r3 = about(axes[2], angles[2]);
    let r23 = about(axes[1], angles[1]) * r3;
    r23.transpose() * unit(axes[0]) * rates[0]
        + r3.transpose() * unit(axes[1]) * rates[1]
        + unit(axes[2]) * rates[2]
}

/// The angle rates that give the body rates `omega` (E solved).
pub fn angle_rates(sequence: &str, angles: [f64; 3], omega: Vector3<f64>) -> [f64; 3] {
    let columns: Vec<Vector3<f64>> = (0..3)
        .map(|k| {
            let mut rates = [0.0; 3];
            rates[k] = 1.0;
            body_rates(sequence, angles, rates)
        })
        .collect();
    let e = Matrix3::from_columns(&columns);
    let rates = e
        .lu()
        .solve(&omega)
        .expect("away from the singular attitude");
    [rates[0], rates[1], rates[2]]
}

/// Earth-fixed (ECEF) position of geodetic latitude, longitude and height.
pub fn ecef_of_geodetic(latitude: f64, longitude: f64, height: f64) -> Vector3<f64> {
    let e2 = F_E * (2.0 - F_E);
    let (s, c) = latitude.sin_cos();
    let n = A_E / (1.0 - e2 * s * s).sqrt();
    let (sl, cl) = longitude.sin_cos();
    Vector3::new(
        (n + height) * c * cl,
        (n + height) * c * sl,
        (n * (1.0 - e2) + height) * s,
    )
}

/// Geodetic latitude, longitude and height of an ECEF position, by fixed-point iteration
/// on the latitude (converged to rounding in a few passes below 100 km; 20 passes here).
pub fn geodetic(r: Vector3<f64>) -> (f64, f64, f64) {
    let e2 = F_E * (2.0 - F_E);
    let p = r.x.hypot(r.y);
    let mut latitude = r.z.atan2(p * (1.0 - e2));
    let mut height = 0.0;
    for _ in 0..20 {
        let s = latitude.sin();
        let n = A_E / (1.0 - e2 * s * s).sqrt();
        height = p / latitude.cos() - n;
        latitude = r.z.atan2(p * (1.0 - e2 * n / (n + height)));
    }
    (latitude, r.y.atan2(r.x), height)
}

/// The rows of C (ECEF to NED) at a geodetic latitude and longitude: north, east, down.
pub fn ned_from_ecef(latitude: f64, longitude: f64) -> Matrix3<f64> {
    let (s, c) = latitude.sin_cos();
    let (sl, cl) = longitude.sin_cos();
    Matrix3::new(-s * cl, -s * sl, c, -sl, cl, 0.0, -c * cl, -c * sl, -s)
}

/// |∇U| of the J2 potential U = −μ/r [1 − J2 (a/r)² (3 z²/r² − 1)/2], by hand:
/// ∂U/∂x_i = μ x_i/r³ + k (3 x_i/r⁵ − 15 z² x_i/r⁷) + k 6 z/r⁵ [i = z], k = μ J2 a²/2.
pub fn gravity(r: Vector3<f64>) -> f64 {
    let n = r.norm();
    let k = MU_E * J2 * A_E * A_E / 2.0;
    let radial = MU_E / n.powi(3) + k * (3.0 / n.powi(5) - 15.0 * r.z * r.z / n.powi(7));
    (r * radial + Vector3::z() * (k * 6.0 * r.z / n.powi(5))).norm()
}

/// A run's state at one time, in the inertial frame: position, velocity, attitude
/// angles and their rates in `sequence`.
pub struct Inertial<'a> {
    pub t: f64,
    pub position: Vector3<f64>,
    pub velocity: Vector3<f64>,
    pub sequence: &'a str,
    pub angles: [f64; 3],
    pub angle_rates: [f64; 3],
}

/// NASA's quantities (`QUANTITIES`) of an inertial state, the Earth turned by ω_E t.
pub fn nasa_quantities(state: &Inertial, earth_rate: f64) -> HashMap<&'static str, f64> {
    let to_fixed = about('z', -earth_rate * state.t);
    let r = to_fixed * state.position;
    let omega = Vector3::z() * earth_rate;
    let v = to_fixed * (state.velocity - omega.cross(&state.position));
    let (latitude, longitude, height) = geodetic(r);
    let ned = ned_from_ecef(latitude, longitude);
    let v_ned = ned * v;
    let body_to_ned = ned * to_fixed * rotation(state.sequence, state.angles);
    let pitch = -body_to_ned[(2, 0)].clamp(-1.0, 1.0).asin();
    let yaw = body_to_ned[(1, 0)].atan2(body_to_ned[(0, 0)]);
    let roll = body_to_ned[(2, 1)].atan2(body_to_ned[(2, 2)]);
    let w = body_rates(state.sequence, state.angles, state.angle_rates);
    let (position, velocity) = (state.position, state.velocity);
    let values = [
        position.x,
        position.y,
        position.z,
        velocity.x,
        velocity.y,
        velocity.z,
        r.x,
        r.y,
        r.z,
        v_ned.x,
        v_ned.y,
        v_ned.z,
        height,
        longitude,
        latitude,
        gravity(state.position),
        yaw,
        pitch,
        roll,
        w.x,
        w.y,
        w.z,
    ];
    QUANTITIES.iter().copied().zip(values).collect()
}

/// One quantity's comparison over every stored time.
#[derive(Clone, Debug)]
pub struct Row {
    pub name: String,
    /// max over t of |ours − median|
    pub deviation: f64,
    /// max over t of NASA's spread
    pub spread: f64,
    /// max over t of |ours − median| / (spread(t) + floor) (≤ 1: within at every time)
    pub ratio: f64,
    /// the time of that largest ratio
    pub worst_time: f64,
}

/// Compares `ours[name][i]` (at `reference.times[i]`) with the median and the spread.
pub fn compare(reference: &Reference, ours: &HashMap<&str, Vec<f64>>) -> Vec<Row> {
    let mut rows = Vec::new();
    for name in QUANTITIES {
        let (Some(median), Some(spread)) = (reference.median.get(name), reference.spread.get(name))
        else {
            continue;
        };
        let mut row = Row {
            name: name.to_string(),
            deviation: 0.0,
            spread: 0.0,
            ratio: 0.0,
            worst_time: 0.0,
        };
        for (i, &value) in ours[name].iter().enumerate() {
            let mut difference = value - median[i];
            if is_wrapped(name) {
                difference = difference.sin().atan2(difference.cos());
            }
            assert!(
                difference.is_finite(),
                "{name} at t = {}",
                reference.times[i]
            );
            row.deviation = row.deviation.max(difference.abs());
            row.spread = row.spread.max(spread[i]);
            let ratio = difference.abs() / (spread[i] + floor(name));
            if ratio > row.ratio {
                row.ratio = ratio;
                row.worst_time = reference.times[i];
            }
        }
        rows.push(row);
    }
    rows
}

pub fn print_table(case: u32, rows: &[Row]) {
    eprintln!("NASA check-case {case}: ours against the median of NASA's simulations (SI, rad)");
    eprintln!(
        "| {:<9} | {:>10} | {:>10} | {:>6} | {:>22} |",
        "quantity", "max |Δ|", "max spread", "within", "max |Δ|/(spread+floor)"
    );
    for row in rows {
        let within = if row.ratio <= 1.0 { "yes" } else { "NO" };
        let edge = format!("{:.2e} at {:.1} s", row.ratio, row.worst_time);
        eprintln!(
            "| {:<9} | {:>10.2e} | {:>10.2e} | {:>6} | {:>22} |",
            row.name, row.deviation, row.spread, within, edge
        );
    }
}

/// The xyx angles (a, b, c) of a rotation R = R_x(a) R_y(b) R_x(c), 0 < b < π: from
/// R = [[cos b, sin b sin c, sin b cos c], [sin a sin b, ·, ·], [−cos a sin b, ·, ·]]
/// (multiplied out by hand), b = acos R₀₀, a = atan2(R₁₀, −R₂₀), c = atan2(R₀₁, R₀₂).
pub fn xyx_angles(r: &Matrix3<f64>) -> [f64; 3] {
    let b = r[(0, 0)].clamp(-1.0, 1.0).acos();
    [r[(1, 0)].atan2(-r[(2, 0)]), b, r[(0, 1)].atan2(r[(0, 2)])]
}

/// A start as NASA's scenarios give it, in the inertial frame aligned with the Earth-fixed one
/// at t = 0: the position of geodetic latitude, longitude, height and the inertial velocity,
/// the Earth-relative one `velocity_ned` (north, east, down) plus ω_E × r; and R (body to
/// inertial) of a yaw-pitch-roll relative to NED.
pub fn inertial_start(
    geodetic: [f64; 3],
    velocity_ned: Vector3<f64>,
    yaw_pitch_roll: [f64; 3],
    earth_rate: f64,
) -> (Vector3<f64>, Vector3<f64>, Matrix3<f64>) {
    let [latitude, longitude, height] = geodetic;
    let r = ecef_of_geodetic(latitude, longitude, height);
    let ned = ned_from_ecef(latitude, longitude);
    let v = ned.transpose() * velocity_ned + (Vector3::z() * earth_rate).cross(&r);
    let body = ned.transpose() * rotation("zyx", yaw_pitch_roll);
    (r, v, body)
}

/// The row of `name`.
pub fn row<'a>(rows: &'a [Row], name: &str) -> &'a Row {
    rows.iter().find(|r| r.name == name).expect(name)
}

/// Every quantity within NASA's spread (plus its rounding floor) at every time, but those of
/// `explained` (name, the largest ratio |Δ| / (spread + floor) allowed: see the case), and
/// its largest distance to the median under `bounds` (name, bound).
pub fn assert_rows(rows: &[Row], explained: &[(&str, f64)], bounds: &[(&str, f64)]) {
    assert_eq!(rows.len(), QUANTITIES.len(), "every quantity compared");
    assert_eq!(bounds.len(), QUANTITIES.len(), "a bound for every quantity");
    for row in rows {
        let allowed = explained.iter().find(|(n, _)| *n == row.name);
        let limit = allowed.map_or(1.0, |&(_, ratio)| ratio);
        if row.ratio > 1.0 {
            eprintln!(
                "{}: {:.4}× the spread at {:.1} s",
                row.name, row.ratio, row.worst_time
            );
        }
        assert!(row.ratio <= limit, "outside NASA's spread: {row:?}");
    }
    for &(name, bound) in bounds {
        let row = row(rows, name);
        assert!(
            row.deviation <= bound,
            "{name}: {:e} > {bound:e}",
            row.deviation
        );
    }
}

/// Each column `simNN_NAME` of the single simulations under its bound.
pub fn assert_singles(found: &[(String, f64)], bounds: &[(&str, f64)]) {
    assert_eq!(found.len(), bounds.len(), "a bound for every column");
    for ((column, deviation), &(name, bound)) in found.iter().zip(bounds) {
        assert_eq!(column, name);
        assert!(*deviation <= bound, "{column}: {deviation:e} > {bound:e}");
    }
}

/// A flight of a check-case model (coordinates [x, y, z, a, b, c]: the centre in the inertial
/// frame, the attitude xyx(a, b, c)) at the reference's times.
pub struct Flight {
    /// NASA's quantities at each time.
    pub ours: HashMap<&'static str, Vec<f64>>,
    /// The closest approach to xyx's singular attitude over every step, rad.
    pub closest: f64,
    /// The state [q, p] at each time, for what a case checks besides.
    pub states: Vec<SVector<f64, 12>>,
}

/// Flies `system` from the velocity state `start` ([q, q̇]) with DOP853 at `tolerance`,
/// landing on every time of the reference, and returns NASA's quantities there (the Earth
/// turning at `earth_rate` in the conversion).
pub fn fly_xyx<Sys: VariableMassSystem<6, 12>>(
    system: &Sys,
    start: &SVector<f64, 12>,
    reference: &Reference,
    tolerance: f64,
    earth_rate: f64,
) -> Flight {
    let initial = system.momentum_state(0.0, start);
    let control = StepControl::Adaptive(AdaptiveControl {
        relative_tolerance: tolerance,
        absolute_tolerance: tolerance,
        ..AdaptiveControl::default()
    });
    let mut stepper = Dop853::new(system, 0.0, initial, control).expect("stepper");
    let mut flight = Flight {
        ours: HashMap::new(),
        closest: f64::INFINITY,
        states: Vec::new(),
    };
    for &t in &reference.times {
        let state = match t > 0.0 {
            true => {
                let solution = run(&mut stepper, &RunConfig::until(t).continuing(), &[]).unwrap();
                let closest = solution.closest_singular_attitude.unwrap_or(f64::INFINITY);
                flight.closest = flight.closest.min(closest);
                *solution.states.last().unwrap()
            }
            false => initial,
        };
        let rates = system.velocities(t, &state).expect("q̇");
        let inertial = Inertial {
            t,
            position: Vector3::new(state[0], state[1], state[2]),
            velocity: Vector3::new(rates[0], rates[1], rates[2]),
            sequence: "xyx",
            angles: [state[3], state[4], state[5]],
            angle_rates: [rates[3], rates[4], rates[5]],
        };
        for (name, value) in nasa_quantities(&inertial, earth_rate) {
            flight.ours.entry(name).or_default().push(value);
        }
        flight.states.push(state);
    }
    flight
}
