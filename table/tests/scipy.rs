//! `pchip` and `spline` against SciPy's `PchipInterpolator` and
//! `CubicSpline(bc_type='natural')` on the same data: values and first derivatives at
//! 10⁴ arguments (5000 on each of two data sets, every knot among them). SciPy's numbers are
//! in `tests/data/*_scipy.csv`, written by `tests/data/scipy_reference.py` (SciPy 1.17.1).

use varmass_table::{CsvTable, Cursor, Interpolation, Motor, Outside, Points, Table};

/// SciPy's columns at each argument.
struct Reference {
    x: Vec<f64>,
    pchip: [Vec<f64>; 2],
    spline: [Vec<f64>; 2],
}

fn reference(name: &str) -> Reference {
    let path = format!("{}/tests/data/{name}_scipy.csv", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    let rows: Vec<Vec<f64>> = text
        .lines()
        .filter(|line| !line.starts_with('#') && !line.starts_with('x'))
        .map(|line| line.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let column = |k: usize| rows.iter().map(|row| row[k]).collect::<Vec<f64>>();
    Reference {
        x: column(0),
        pchip: [column(1), column(2)],
        spline: [column(3), column(4)],
    }
}

fn m1670() -> Points {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../models/motors/Cesaroni_M1670.eng"
    );
    Motor::parse(&std::fs::read_to_string(path).unwrap())
        .unwrap()
        .thrust
}

fn wiggle() -> Points {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/wiggle.csv");
    CsvTable::parse(&std::fs::read_to_string(path).unwrap())
        .unwrap()
        .points
}

/// The largest relative difference of our values and of our slopes from SciPy's, each
/// relative to max(|SciPy's|, `floor`·the column's largest |SciPy's|).
fn worst(points: &Points, interpolation: Interpolation, scipy: &Reference, floor: f64) -> [f64; 2] {
    let table = Table::new(points, interpolation, Outside::Error);
    let expected = match interpolation {
        Interpolation::Pchip => &scipy.pchip,
        _ => &scipy.spline,
    };
    let mut cursor = Cursor::default();
    let ours = [
        scipy
            .x
            .iter()
            .map(|&x| table.value_at(x, &mut cursor).unwrap())
            .collect::<Vec<_>>(),
        scipy
            .x
            .iter()
            .map(|&x| table.slope_at(x, &mut cursor).unwrap())
            .collect(),
    ];
    [0, 1].map(|k| {
        let scale = floor * expected[k].iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        ours[k]
            .iter()
            .zip(&expected[k])
            .map(|(a, b)| (a - b).abs() / b.abs().max(scale))
            .fold(0.0, f64::max)
    })
}

#[test]
fn the_samples_are_ten_thousand_and_include_every_knot() {
    let mut total = 0;
    for (name, points) in [("m1670", m1670()), ("wiggle", wiggle())] {
        let scipy = reference(name);
        total += scipy.x.len();
        assert!(points.arguments().iter().all(|knot| scipy.x.contains(knot)));
    }
    assert_eq!(total, 10_000);
}

#[test]
fn pchip_equals_scipys_pchip_interpolator_pointwise() {
    // Same slopes, same coefficients, summed in the same order: measured 0 (bit-identical)
    // on both data sets, values and slopes, pointwise relative (no floor, so the zeros of
    // the thrust curve count too). The bound is the 1e-13.
    for (name, points) in [("m1670", m1670()), ("wiggle", wiggle())] {
        let [value, slope] = worst(&points, Interpolation::Pchip, &reference(name), 0.0);
        assert!(
            value <= 1e-13 && slope <= 1e-13,
            "{name}: {value:e} {slope:e}"
        );
    }
}

#[test]
fn spline_equals_scipys_natural_cubic_spline() {
    // SciPy solves for the knot slopes with LAPACK's pivoted banded LU, we with the Thomas
    // algorithm: the slopes differ in the last bits, and so do the curves. Measured, relative
    // to max(|SciPy's|, 1e-3·max |SciPy's|): values 1.5e-14 (M1670), 5.2e-15 (wiggle); slopes
    // 1.1e-14, 6.5e-14. Pointwise without the floor the slopes differ by up to 5.9e-11
    // relative, next to their zeros, where the slope is a difference of terms 10⁴ times
    // larger and neither program's last bits mean anything. The bound is the 1e-13.
    for (name, points) in [("m1670", m1670()), ("wiggle", wiggle())] {
        let [value, slope] = worst(&points, Interpolation::Spline, &reference(name), 1e-3);
        assert!(
            value <= 1e-13 && slope <= 1e-13,
            "{name}: {value:e} {slope:e}"
        );
    }
}
