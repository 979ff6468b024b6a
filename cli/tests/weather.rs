//! The weather of RocketPy's public flights (`models/weather/<flight>/`, written by
//! `tools/weather/flights.py` from RocketPy's ERA5 files; docs/weather.md) against RocketPy
//! 1.13's own `Environment` for the same flight (`rocketpy_1.13.csv` and
//! `rocketpy_1.13_knots.csv` beside the tables, made by `tools/weather/rocketpy_reference.py`;
//! neither RocketPy nor a NetCDF reader is needed here):
//!
//! * the converted tables' rows ARE RocketPy's knots (altitude, pressure, temperature, wind
//!   east and north), bit for bit; a row added below the lowest level holds its values, as
//!   RocketPy's constant extrapolation does;
//! * through `varmass run` of `tests/data/library/weather_probe.vms`, climbing through 21
//!   altitudes between the knots: linear tables (`atmosphere_gas.vms`, `wind_local.vms`)
//!   give RocketPy's temperature, pressure and wind to rounding; its density and speed of
//!   sound, which RocketPy interpolates themselves between the knots, and the pchip
//!   tables of `atmosphere_table.vms` differ by the measured amounts below.

mod common;

use std::path::{Path, PathBuf};

use common::{column, csv, root, written};

/// A table file of ours or RocketPy's: `#` lines, a header, rows of numbers.
fn rows(path: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().expect("a number")).collect())
        .collect()
}

/// The flights with a RocketPy reference: their folders under `models/weather/`.
fn flights() -> Vec<PathBuf> {
    let dir = PathBuf::from(root("models/weather"));
    let mut found: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("models/weather/ exists")
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| p.join("rocketpy_1.13.csv").exists())
        .collect();
    found.sort();
    found
}

const TABLES: [&str; 4] = [
    "temperature.csv",
    "pressure.csv",
    "wind_east.csv",
    "wind_north.csv",
];

#[test]
fn the_converted_tables_are_rocketpys_knots_bit_for_bit() {
    let all = flights();
    assert!(all.len() >= 11, "{all:?}");
    for dir in all {
        let [t, p, e, n] = TABLES.map(|f| rows(&dir.join(f)));
        let knots = rows(&dir.join("rocketpy_1.13_knots.csv"));
        // One row more where the site lies below the lowest level: the first, held.
        let extra = t.len() - knots.len();
        assert!(extra <= 1, "{dir:?}");
        for table in [&t, &p, &e, &n] {
            assert_eq!(table.len(), t.len(), "{dir:?}");
        }
        for (i, k) in knots.iter().enumerate() {
            let j = i + extra;
            let ours = [t[j][0], p[j][1], t[j][1], e[j][1], n[j][1]];
            assert_eq!(ours.as_slice(), k.as_slice(), "{dir:?} knot {i}");
            for table in [&p, &e, &n] {
                assert_eq!(table[j][0], t[j][0], "{dir:?} knot {i}: one altitude");
            }
        }
        if extra == 1 {
            assert!(t[0][0] < knots[0][0]);
            let held = [p[0][1], t[0][1], e[0][1], n[0][1]];
            assert_eq!(held.as_slice(), &knots[0][1..], "{dir:?}: held");
        }
    }
}

/// What the probe records, in order.
const RECORD: &str = "altitude,gas_temperature,gas_pressure,gas_rho,gas_a,wind_vx,wind_vy,\
                      wind_wind_speed,wind_heading,air_temperature,air_p,air_rho,air_a";

/// The probe run through `dir`'s tables from RocketPy's first altitude, one of its
/// altitude steps a second: a row per RocketPy altitude, the columns of RECORD.
fn climb(dir: &Path, reference: &[Vec<f64>], elevation: f64) -> Vec<Vec<f64>> {
    let file = |name: &str| dir.join(name).display().to_string();
    let (h0, dh) = (reference[0][0], reference[1][0] - reference[0][0]);
    let set = [
        format!("elevation={elevation}"),
        format!("z={}", h0 - elevation),
        format!("z'={dh}"),
    ];
    let tables = [
        ("air_T_s", "temperature.csv"),
        ("air_p_s", "pressure.csv"),
        ("sounding_T", "temperature.csv"),
        ("sounding_p", "pressure.csv"),
        ("wind_e", "wind_east.csv"),
        ("wind_n", "wind_north.csv"),
    ]
    .map(|(table, name)| format!("{table}={}", file(name)));
    let probe = root("tests/data/library/weather_probe.vms");
    let mut args = vec!["run", probe.as_str(), "--set", "m0=1", "--set", &set[0]];
    args.extend([
        "--init", "x=0", "--init", "y=0", "--init", "x'=0", "--init", "y'=0",
    ]);
    args.extend([
        "--init", &set[1], "--init", &set[2], "--until", "20", "--every", "1",
    ]);
    args.extend(["--method", "dop853", "--tol", "1e-12", "--record", RECORD]);
    for table in &tables {
        args.extend(["--table", table.as_str()]);
    }
    let name = format!("weather_{}.csv", dir.file_name().unwrap().to_str().unwrap());
    let (header, rows) = csv(&written(&args, &name));
    let order: Vec<usize> = RECORD.split(',').map(|n| column(&header, n)).collect();
    rows.iter()
        .map(|r| order.iter().map(|&i| r[i]).collect())
        .collect()
}

/// The flight's elevation, from the header of its tables (`elevation 407.0 m`).
fn elevation(dir: &Path) -> f64 {
    let text = std::fs::read_to_string(dir.join("temperature.csv")).expect("readable");
    let after = text
        .split("elevation ")
        .nth(1)
        .expect("the header names the elevation");
    after.split(' ').next().unwrap().parse().expect("a number")
}

/// RocketPy's air constant, J/(kg K), and ours, R*/M0.
const R_ROCKETPY: f64 = 287.05287;

#[derive(Default, Debug)]
struct Worst {
    linear: f64,
    wind: f64,
    rho: f64,
    a: f64,
    rho_knotwise: f64,
    speed_ours: f64,
    heading_ours: f64,
    speed_rocketpy: f64,
    heading_rocketpy: f64,
    pchip_t: f64,
    pchip_p: f64,
    pchip_rho: f64,
    loglinear_linear: f64,
    loglinear_pchip: f64,
    loglinear_linear_sum: f64,
    loglinear_pchip_sum: f64,
}

/// The pressure interpolated log-linearly in `table` (altitude, pressure rows) at `h`: the
/// hydrostatic pressure of an isothermal layer between two levels, p0 (p1/p0)^s.
fn log_linear(table: &[Vec<f64>], h: f64) -> f64 {
    let i = table
        .partition_point(|r| r[0] <= h)
        .clamp(1, table.len() - 1);
    let (r0, r1) = (&table[i - 1], &table[i]);
    let s = (h - r0[0]) / (r1[0] - r0[0]);
    r0[1] * (r1[1] / r0[1]).powf(s)
}

fn compare(worst: &mut Worst, ours: &[f64], theirs: &[f64], knots: &[Vec<f64>]) {
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let (p, t, rho, a) = (theirs[1], theirs[2], theirs[3], theirs[4]);
    let (speed, heading, u, v) = (theirs[5], theirs[6], theirs[7], theirs[8]);
    assert!(
        (ours[0] - theirs[0]).abs() < 1e-9,
        "{} {}",
        ours[0],
        theirs[0]
    );
    worst.linear = worst.linear.max(rel(ours[1], t)).max(rel(ours[2], p));
    worst.wind = worst.wind.max((ours[5] + u).abs()).max((ours[6] + v).abs());
    worst.rho = worst.rho.max(rel(ours[3], rho));
    worst.a = worst.a.max(rel(ours[4], a));
    // RocketPy's density between knots: the chord of the knots' p/(R T) (its Function
    // arithmetic on one grid), a second formulation of its column.
    // Held below the first knot (the pads below the lowest level).
    let i = knots
        .partition_point(|k| k[0] <= theirs[0])
        .clamp(1, knots.len() - 1);
    let (k0, k1) = (&knots[i - 1], &knots[i]);
    let s = ((theirs[0] - k0[0]) / (k1[0] - k0[0])).max(0.0);
    let [r0, r1] = [k0, k1].map(|k| k[1] / (R_ROCKETPY * k[2]));
    worst.rho_knotwise = worst.rho_knotwise.max(rel(r0 + s * (r1 - r0), rho));
    // Our wind speed and heading are those of the interpolated components.
    worst.speed_ours = worst.speed_ours.max((ours[7] - u.hypot(v)).abs());
    let turn = |x: f64| (x + 540.0) % 360.0 - 180.0;
    let ours_deg = ours[8].to_degrees();
    let components = turn(ours_deg - u.atan2(v).to_degrees()).abs();
    worst.heading_ours = worst.heading_ours.max(components);
    worst.speed_rocketpy = worst.speed_rocketpy.max((ours[7] - speed).abs());
    worst.heading_rocketpy = worst.heading_rocketpy.max(turn(ours_deg - heading).abs());
    worst.pchip_t = worst.pchip_t.max((ours[9] - t).abs());
    worst.pchip_p = worst.pchip_p.max(rel(ours[10], p));
    worst.pchip_rho = worst.pchip_rho.max(rel(ours[11], rho));
}

#[test]
fn between_the_knots_linear_tables_give_rocketpys_atmosphere_and_wind() {
    let mut worst = Worst::default();
    for dir in flights() {
        let reference = rows(&dir.join("rocketpy_1.13.csv"));
        let knots = rows(&dir.join("rocketpy_1.13_knots.csv"));
        let ours = climb(&dir, &reference, elevation(&dir));
        assert_eq!(ours.len(), reference.len(), "{dir:?}");
        let pressure = rows(&dir.join("pressure.csv"));
        for (o, r) in ours.iter().zip(&reference) {
            compare(&mut worst, o, r, &knots);
            let exp = log_linear(&pressure, o[0]);
            // The chord of a convex p0 (p1/p0)^s lies above it.
            assert!(o[2] / exp - 1.0 > -1e-14, "{dir:?} at {} m", o[0]);
            let (linear, pchip) = ((o[2] / exp - 1.0).abs(), (o[10] / exp - 1.0).abs());
            worst.loglinear_linear = worst.loglinear_linear.max(linear);
            worst.loglinear_pchip = worst.loglinear_pchip.max(pchip);
            worst.loglinear_linear_sum += linear;
            worst.loglinear_pchip_sum += pchip;
        }
    }
    println!("{worst:#?}");
    // Linear tables: RocketPy's T, p (relative) and wind (m/s) to rounding. Measured
    // 4.4e-16 and 2.3e-14 m/s (the probe's altitude within ulps of RocketPy's, times the
    // wind's shear); bound 1e-13.
    assert!(worst.linear < 1e-13 && worst.wind < 1e-13, "{worst:?}");
    // RocketPy's density is the chord of the knots' densities (measured 2.2e-16; bound
    // 1e-13); ours is p/(R T) of the chords of p and T: apart by 1.6e-3 at most at these
    // 231 altitudes below 12 km (bound 2e-3); the speed of sound by 7.5e-5 (bound 1e-4).
    assert!(worst.rho_knotwise < 1e-13, "{worst:?}");
    assert!(worst.rho < 2e-3 && worst.a < 1e-4, "{worst:?}");
    // Our wind speed and heading are those of the interpolated east and north wind
    // (measured 2.8e-14 m/s and 1.4e-12 degrees; bounds 1e-12, 1e-10); RocketPy interpolates its speed and its (unwrapped) heading themselves,
    // which turn the other way where the wind turns between two levels: 3.26 m/s and
    // 56.5 degrees apart at most (Andromeda near 1.3 km, a light wind turning), bounds 3.5
    // and 60.
    assert!(
        worst.speed_ours < 1e-12 && worst.heading_ours < 1e-10,
        "{worst:?}"
    );
    assert!(
        worst.speed_rocketpy < 3.5 && worst.heading_rocketpy < 60.0,
        "{worst:?}"
    );
    // atmosphere_table.vms's pchip tables, against RocketPy's chords: T within 0.19 K, p
    // 2.9e-3, rho 2.0e-3 (bounds 0.25 K, 3.5e-3, 2.5e-3).
    assert!(worst.pchip_t < 0.25, "{worst:?}");
    assert!(
        worst.pchip_p < 3.5e-3 && worst.pchip_rho < 2.5e-3,
        "{worst:?}"
    );
    // Against the log-linear pressure (hydrostatic in a thin isothermal layer), the linear
    // chord lies above by up to 4.2e-3, pchip within 1.4e-3 (bounds 5e-3, 1.6e-3), and
    // pchip is the closer over the 231 altitudes: sums of the deviations 0.178 and 0.040.
    println!(
        "log-linear: linear {:e}, pchip {:e}; sums {:e} and {:e}",
        worst.loglinear_linear,
        worst.loglinear_pchip,
        worst.loglinear_linear_sum,
        worst.loglinear_pchip_sum
    );
    assert!(
        worst.loglinear_pchip_sum < worst.loglinear_linear_sum,
        "{worst:?}"
    );
    assert!(
        worst.loglinear_linear < 5e-3 && worst.loglinear_pchip < 1.6e-3,
        "{worst:?}"
    );
}
