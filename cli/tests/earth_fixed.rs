//! The Earth-fixed frame of `models/lib/earth_fixed_wgs84.vms` against an independent Rust
//! implementation of the WGS-84 conversions (`tests/nasa_support`: geodetic → ECEF in
//! closed form, ECEF → geodetic by fixed-point iteration, the NED axes), on a grid of
//! positions from pole to pole (within 1e-5° of each pole and 1e-7° of the equator, the
//! poles themselves) and altitudes 0 … 86 km, read through `varmass run --record`.
//!
//! One probe model holds one instance of the component per grid point, its position and
//! velocity bound to parameters written by the test (`{:?}`: every digit of the double), so
//! one run gives every point at t = 0 and at t = 1 s (the Earth turned by ω_E).

#[path = "../../tests/nasa_support/mod.rs"]
mod nasa_support;

mod common;

use common::{csv, root, scratch_file, written};
use nasa_support::{about, ecef_of_geodetic, geodetic, ned_from_ecef, OMEGA_E};
use varmass::core::nalgebra::Vector3;

/// A grid point: geodetic latitude, longitude, height, and an Earth-relative velocity in NED.
struct Point {
    latitude: f64,
    longitude: f64,
    height: f64,
    ned: Vector3<f64>,
}

fn grid() -> Vec<Point> {
    let latitudes: [f64; 15] = [
        -90.0, -89.99999, -89.9, -45.0, -1e-7, 0.0, 1e-7, 0.3, 30.0, 45.0, 60.0, 89.0, 89.9,
        89.99999, 90.0,
    ];
    let heights = [0.0, 1.0, 9144.0, 30_000.0, 86_000.0];
    let longitudes = [0.0, 0.7, 2.5, -3.0, 3.1];
    let mut points = Vec::new();
    for (i, latitude) in latitudes.iter().enumerate() {
        for (j, &height) in heights.iter().enumerate() {
            points.push(Point {
                latitude: latitude.to_radians(),
                longitude: longitudes[(i + j) % longitudes.len()],
                height,
                ned: Vector3::new(100.0, -50.0 + j as f64, 20.0 - i as f64),
            });
        }
    }
    points
}

/// The probe: a free particle (the run needs a coordinate) and one instance `gK` of the
/// component per point, bound to the inertial position and velocity of the point at t = 0
/// (the inertial frame aligned with the Earth-fixed one then): r = ECEF(φ, λ, h),
/// v = Cᵀ v_NED + ω_E × r.
fn probe(points: &[Point]) -> String {
    let lib = root("models/lib/earth_fixed_wgs84.vms");
    let mut text = String::from("coordinates s\nunits s: m, m0: kg\nparameter m0 = 1\n");
    text += "mass m = m0\nbody probe: mass m, position [s]\n";
    for (k, point) in points.iter().enumerate() {
        let (r, v) = inertial(point);
        let names = ["X", "Y", "Z", "VX", "VY", "VZ"];
        let values = [r.x, r.y, r.z, v.x, v.y, v.z];
        for (name, value) in names.iter().zip(values) {
            text += &format!("parameter {name}{k} = {value:?}\n");
        }
        text += &format!(
            "units X{k}: m, Y{k}: m, Z{k}: m, VX{k}: m/s, VY{k}: m/s, VZ{k}: m/s\n\
             use \"{lib}\" as g{k}: x = X{k}, y = Y{k}, z = Z{k}, vx = VX{k}, vy = VY{k}, vz = VZ{k}\n"
        );
    }
    text
}

fn inertial(point: &Point) -> (Vector3<f64>, Vector3<f64>) {
    let r = ecef_of_geodetic(point.latitude, point.longitude, point.height);
    let ned = ned_from_ecef(point.latitude, point.longitude);
    let v = ned.transpose() * point.ned + (Vector3::z() * OMEGA_E).cross(&r);
    (r, v)
}

/// The largest difference per quantity over the grid, printed.
#[derive(Default, Debug)]
struct Worst {
    height: f64,
    latitude: f64,
    longitude: f64,
    fixed_point_height: f64,
    fixed_point_latitude: f64,
    ned_velocity: f64,
    ned_axes: f64,
    ecef: f64,
    turned_longitude: f64,
}

const QUANTITIES: [&str; 18] = [
    "latitude",
    "longitude",
    "altitude",
    "v_north",
    "v_east",
    "v_down",
    "north_x",
    "north_y",
    "north_z",
    "east_x",
    "east_y",
    "east_z",
    "down_x",
    "down_y",
    "down_z",
    "x_ecef",
    "y_ecef",
    "z_ecef",
];

fn measure(points: &[Point]) -> Worst {
    let file = scratch_file("earth_fixed_probe_grid.vms", &probe(points));
    let record: Vec<String> = (0..points.len())
        .flat_map(|k| QUANTITIES.iter().map(move |q| format!("g{k}_{q}")))
        .collect();
    let record = record.join(",");
    let args = [
        "run", &file, "--init", "s=0", "--until", "1", "--every", "1", "--record", &record,
    ];
    let (header, rows) = csv(&written(&args, "earth_fixed_grid.csv"));
    let at = |row: usize, k: usize, q: &str| {
        let name = format!("g{k}_{q}");
        rows[row][header.iter().position(|h| *h == name).expect("recorded")]
    };
    let mut worst = Worst::default();
    let max = |w: &mut f64, d: f64| *w = w.max(d.abs());
    for (k, point) in points.iter().enumerate() {
        let polar = point.latitude.abs() > 89.99_f64.to_radians();
        // Against the grid (the forward conversion, closed form): φ, λ (not on the polar
        // axis, where any longitude is the point; there ours is atan2(0, 0) = 0), h.
        max(&mut worst.height, at(0, k, "altitude") - point.height);
        max(&mut worst.latitude, at(0, k, "latitude") - point.latitude);
        if point.latitude.abs() < 90f64.to_radians() {
            let d = at(0, k, "longitude") - point.longitude;
            max(&mut worst.longitude, d.sin().atan2(d.cos()));
        }
        // Against the fixed-point inverse, off the poles (its p/cos φ − N is 0/0 there).
        let (r, _) = inertial(point);
        if !polar {
            let (latitude, _, height) = geodetic(r);
            max(&mut worst.fixed_point_height, at(0, k, "altitude") - height);
            max(
                &mut worst.fixed_point_latitude,
                at(0, k, "latitude") - latitude,
            );
        }
        // The Earth-relative velocity in NED, and the NED axes (rows of C; inertial = ECEF
        // at t = 0), off the polar axis where north and east are any pair.
        if point.latitude.abs() < 90f64.to_radians() {
            let ours = Vector3::new(at(0, k, "v_north"), at(0, k, "v_east"), at(0, k, "v_down"));
            max(&mut worst.ned_velocity, (ours - point.ned).norm());
            let c = ned_from_ecef(point.latitude, point.longitude);
            for (i, axis) in ["north", "east", "down"].iter().enumerate() {
                for (j, component) in ["x", "y", "z"].iter().enumerate() {
                    let ours = at(0, k, &format!("{axis}_{component}"));
                    max(&mut worst.ned_axes, ours - c[(i, j)]);
                }
            }
        }
        // At t = 1 s the Earth has turned by ω_E: ECEF = R_z(−ω_E) r, the longitude λ − ω_E.
        let turned = about('z', -OMEGA_E) * r;
        let ours = Vector3::new(at(1, k, "x_ecef"), at(1, k, "y_ecef"), at(1, k, "z_ecef"));
        max(&mut worst.ecef, (ours - turned).norm());
        if point.latitude.abs() < 90f64.to_radians() {
            let d = at(1, k, "longitude") - (point.longitude - OMEGA_E);
            max(&mut worst.turned_longitude, d.sin().atan2(d.cos()));
        }
    }
    eprintln!("{worst:#?}");
    worst
}

/// Measured over the 75 points: height 1.86e-9 m from the grid's and from the fixed-point
/// inverse's (2^-29 m: two units in the last place of a coordinate between 4.2e6 and 8.4e6
/// m, whose own rounding is 4.7e-10 m: the 1e-9 m the issue asked is below one unit, which
/// no double-precision conversion of a rounded position can promise; against a 40-digit
/// iteration the file's height is within 1.5e-9 m, the header's figure); latitude 2.2e-16 rad
/// (the grid's) and 1.1e-16 (the fixed point's), longitude 1.1e-16 rad at t = 0 and at t = 1 s,
/// the NED velocity 4.5e-14 m/s (of ~500 m/s: ω_E × r is 465 m/s), the NED axes 2.2e-16, the
/// ECEF position at t = 1 s 0 (the same rotation, the same roundings). Bounds: 3e-9 m for the
/// heights, 4.5e-16 rad (two roundings of an angle below 4) for the angles and axes, 1.5e-13
/// m/s, 1e-9 m.
#[test]
fn the_earth_fixed_frame_is_the_wgs84_conversion_to_rounding() {
    let points = grid();
    assert_eq!(points.len(), 75);
    let worst = measure(&points);
    let within = [
        (worst.height, 3e-9),
        (worst.fixed_point_height, 3e-9),
        (worst.latitude, 4.5e-16),
        (worst.fixed_point_latitude, 4.5e-16),
        (worst.longitude, 4.5e-16),
        (worst.turned_longitude, 4.5e-16),
        (worst.ned_axes, 4.5e-16),
        (worst.ned_velocity, 1.5e-13),
        (worst.ecef, 1e-9),
    ];
    for (value, bound) in within {
        assert!(value <= bound, "{value:e} > {bound:e}: {worst:?}");
    }
}

/// The comparison can fail: the same grid read by a frame whose Earth does not turn
/// (`--set` of each instance's ω_E to 0) gives the NED velocity ω_E × r wrong, 465 m/s at the
/// equator.
#[test]
fn a_frame_that_does_not_turn_fails_the_comparison() {
    let points: Vec<Point> = grid().into_iter().filter(|p| p.latitude == 0.0).collect();
    let file = scratch_file("earth_fixed_probe_still.vms", &probe(&points));
    let sets: Vec<String> = (0..points.len()).map(|k| format!("g{k}_omega=0")).collect();
    let mut args = vec![
        "run",
        file.as_str(),
        "--init",
        "s=0",
        "--until",
        "1",
        "--every",
        "1",
    ];
    for set in &sets {
        args.extend(["--set", set.as_str()]);
    }
    let record: Vec<String> = (0..points.len()).map(|k| format!("g{k}_v_east")).collect();
    let record = record.join(",");
    args.extend(["--record", record.as_str()]);
    let (header, rows) = csv(&written(&args, "earth_fixed_still.csv"));
    for (k, point) in points.iter().enumerate() {
        let ours = rows[0][header
            .iter()
            .position(|h| *h == format!("g{k}_v_east"))
            .unwrap()];
        let r = ecef_of_geodetic(0.0, point.longitude, point.height).norm();
        // ours = the true east velocity + ω_E r (the Earth's own motion, not taken off)
        assert!(
            ((ours - point.ned.y) - OMEGA_E * r).abs() < 1e-6,
            "{ours} at {k}"
        );
    }
}
