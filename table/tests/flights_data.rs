//! The public flights' inputs (`flights/<name>/flight.toml` and their data files, issue 36;
//! docs/flights.md): every data file reads with this crate's readers as a scene will read
//! it, and the numbers the importer derived (benches/peers/rocketpy/import_flights.py, in
//! Python) agree with what these readers and hand arithmetic give:
//!
//! * the total impulse over [0, burn_time] of the thrust curve as read here (a RASP file
//!   from (0 s, 0 N), linear between points, clipped at the burn time) against
//!   `motor.total_impulse` (RocketPy's own impulse agrees with it to 2e-16,
//!   benches/peers/rocketpy/flights.py checks that), and `exhaust_speed` = impulse / mass;
//! * `propellant_mass` = n ρ π (R² − r²) h of the grains;
//! * the reference point is the centre of dry mass: m cg_z + m_motor dry_cg_z = 0, and the
//!   dry inertia about it is the two parts' by parallel axes;
//! * `exit_travel` = rail length − (upper button − nozzle);
//! * Calisto's atmosphere table against the U.S. Standard Atmosphere 1976's own table
//!   (NOAA-S/T 76-1562, Table I, geometric altitudes 1 to 6 km: pressure to 6e-5, the table
//!   printing five digits; temperature to half its third decimal).
//!
//! The tolerances are a few units of the last place the tomls print (12 decimals) or of
//! the published table; every check fails on a wrong translation (a sign, a term dropped).

use std::path::{Path, PathBuf};

use toml::{Table, Value};
use varmass_table::{CsvTable, Motor, Points};

fn flights_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("flights")
}

/// Every flight: its directory and its parsed flight.toml.
fn flights() -> Vec<(PathBuf, Table)> {
    let mut out: Vec<(PathBuf, Table)> = std::fs::read_dir(flights_dir())
        .expect("flights/ exists")
        .map(|entry| entry.expect("a directory entry").path())
        .filter(|dir| dir.join("flight.toml").exists())
        .map(|dir| {
            let text = std::fs::read_to_string(dir.join("flight.toml")).expect("readable");
            let table: Table = text
                .parse()
                .unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
            (dir, table)
        })
        .collect();
    out.sort_by(|a, b| a.0.cmp(&b.0));
    assert!(
        out.len() >= 9,
        "nine flights and Calisto, found {}",
        out.len()
    );
    out
}

fn num(table: &Table, path: &str) -> f64 {
    let mut value: Option<&Value> = None;
    let mut current = table;
    for key in path.split('.') {
        let v = current.get(key).unwrap_or_else(|| panic!("no key {path}"));
        if let Value::Table(t) = v {
            current = t;
        }
        value = Some(v);
    }
    match value.expect("a key") {
        Value::Float(x) => *x,
        Value::Integer(i) => *i as f64,
        other => panic!("{path} is {other:?}, not a number"),
    }
}

fn pair(table: &Table, section: &str, key: &str) -> [f64; 2] {
    let array = table[section][key].as_array().expect("an array");
    [0, 1].map(|i| array[i].as_float().expect("a float"))
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file))
        .unwrap_or_else(|e| panic!("{}/{file}: {e}", dir.display()))
}

/// The thrust curve as this crate reads it: RASP or CSV.
fn thrust(dir: &Path, file: &str) -> Points {
    let text = read(dir, file);
    if file.ends_with(".eng") {
        Motor::parse(&text)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .thrust
    } else {
        CsvTable::parse(&text)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .points
    }
}

/// The integral of the linear interpolant of `points` over [0, end] (zero outside).
fn impulse_until(points: &Points, end: f64) -> f64 {
    let (t, f) = (points.arguments(), points.values());
    let mut total = 0.0;
    for i in 1..t.len() {
        let (t0, f0) = (t[i - 1], f[i - 1]);
        let (mut t1, mut f1) = (t[i], f[i]);
        if t0 >= end {
            break;
        }
        if t1 > end {
            f1 = f0 + (f1 - f0) * (end - t0) / (t1 - t0);
            t1 = end;
        }
        total += 0.5 * (f0 + f1) * (t1 - t0);
    }
    total
}

fn close(got: f64, want: f64, rel: f64, what: &str) {
    let err = (got - want).abs() / want.abs().max(1e-300);
    assert!(
        err <= rel,
        "{what}: {got} against {want}, {err:.1e} > {rel:.0e}"
    );
}

#[test]
fn every_data_file_reads_as_a_scene_reads_it() {
    for (dir, toml) in flights() {
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let mut files = vec![toml["motor"]["thrust"].as_str().unwrap().to_string()];
        for key in ["power_off", "power_on"] {
            if let Some(file) = toml["drag"][key].as_str() {
                files.push(file.to_string());
            }
        }
        if let Some(file) = toml["fins"]["airfoil"].as_str().filter(|f| *f != "none") {
            files.push(file.to_string());
        }
        if let Some(file) = toml.get("apogee").and_then(|a| a.get("log")) {
            files.push(file.as_str().unwrap().to_string());
        }
        for file in files {
            let points = if file.ends_with(".eng") {
                thrust(&dir, &file)
            } else {
                CsvTable::parse(&read(&dir, &file))
                    .unwrap_or_else(|e| panic!("{name}/{file}: {e}"))
                    .points
            };
            assert!(points.len() >= 2, "{name}/{file}: {} points", points.len());
        }
    }
}

#[test]
fn derived_motor_numbers_match_the_thrust_files() {
    for (dir, toml) in flights() {
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let file = toml["motor"]["thrust"].as_str().unwrap();
        let burn = num(&toml, "motor.burn_time");
        let impulse = impulse_until(&thrust(&dir, file), burn);
        close(
            impulse,
            num(&toml, "motor.total_impulse"),
            1e-12,
            &format!("{name} impulse"),
        );
        let n = num(&toml, "motor.grains.number");
        let rho = num(&toml, "motor.grains.density");
        let (big_r, r) = (
            num(&toml, "motor.grains.outer_radius"),
            num(&toml, "motor.grains.inner_radius"),
        );
        let h = num(&toml, "motor.grains.height");
        let mass = n * rho * std::f64::consts::PI * (big_r * big_r - r * r) * h;
        close(
            mass,
            num(&toml, "motor.propellant_mass"),
            1e-11,
            &format!("{name} propellant"),
        );
        close(
            impulse / mass,
            num(&toml, "motor.exhaust_speed"),
            1e-11,
            &format!("{name} exhaust speed"),
        );
    }
}

#[test]
fn the_reference_point_is_the_centre_of_dry_mass() {
    for (dir, toml) in flights() {
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        let (m, cg) = (num(&toml, "rocket.mass"), num(&toml, "rocket.cg_z"));
        let (mm, cgm) = (num(&toml, "motor.dry_mass"), num(&toml, "motor.dry_cg_z"));
        // the first moment of the dry mass about z = 0, against the scale m |cg| + mm |cgm|
        let moment = m * cg + mm * cgm;
        let scale = m * cg.abs() + mm * cgm.abs() + 1e-12;
        assert!(
            moment.abs() <= 1e-11 * scale.max(1.0),
            "{name}: first moment {moment:e}"
        );
        close(
            num(&toml, "rocket.dry_mass"),
            m + mm,
            1e-12,
            &format!("{name} dry mass"),
        );
        let [ixx, izz] = pair(&toml, "rocket", "inertia");
        let [mxx, mzz] = pair(&toml, "motor", "dry_inertia");
        let [dxx, dzz] = pair(&toml, "rocket", "dry_inertia");
        close(
            dxx,
            ixx + m * cg * cg + mxx + mm * cgm * cgm,
            1e-11,
            &format!("{name} I_xx"),
        );
        close(dzz, izz + mzz, 1e-11, &format!("{name} I_zz"));
        // the nose's tip is the rocket's highest point
        let tip = num(&toml, "nose.tip_z");
        for key in [
            "rail.upper_button_z",
            "rail.lower_button_z",
            "motor.nozzle_z",
        ] {
            assert!(num(&toml, key) < tip, "{name}: {key} above the nose's tip");
        }
        let travel = num(&toml, "rail.length")
            - (num(&toml, "rail.upper_button_z") - num(&toml, "motor.nozzle_z"));
        close(
            num(&toml, "rail.exit_travel"),
            travel,
            1e-11,
            &format!("{name} exit travel"),
        );
    }
}

/// U.S. Standard Atmosphere 1976, Table I (geometric altitude, m; temperature, K; pressure,
/// Pa, as printed: five significant digits).
const US76_TABLE: [(f64, f64, f64); 6] = [
    (1000.0, 281.651, 8.9876e4),
    (2000.0, 275.154, 7.9501e4),
    (3000.0, 268.659, 7.0121e4),
    (4000.0, 262.166, 6.1660e4),
    (5000.0, 255.676, 5.4048e4),
    (6000.0, 249.187, 4.7217e4),
];

#[test]
fn calistos_atmosphere_table_is_the_1976_standard() {
    let dir = flights_dir().join("calisto");
    let text = read(&dir, "atmosphere.csv");
    let rows: Vec<[f64; 3]> = text
        .lines()
        .skip(1)
        .map(|line| {
            let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2]]
        })
        .collect();
    for (h, t, p) in US76_TABLE {
        let row = rows
            .iter()
            .find(|r| r[0] == h)
            .unwrap_or_else(|| panic!("no row at {h} m"));
        assert!(
            (row[2] - t).abs() <= 5e-4,
            "T at {h} m: {} against {t}",
            row[2]
        );
        close(row[1], p, 6e-5, &format!("p at {h} m"));
    }
    // every 5 m, heights increasing, from 1000 to 6000 m
    assert_eq!(rows.len(), 1001);
    assert!(rows
        .windows(2)
        .all(|w| (w[1][0] - w[0][0] - 5.0).abs() < 1e-9));
}
