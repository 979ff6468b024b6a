//! Data whose interpolant overflows though their slopes do not (docs/tables.md#interpolation):
//! refused at load by `pchip` and `spline`, with the line that ends the overflowing piece.

use varmass_table::{
    CsvTable, Interpolation, InvalidPoints, Motor, Outside, Points, ReadErrorKind, Table,
};

/// The review's data (2026-11-26): each chord's slope ±1.5e308 is finite, so a linear table
/// is exact, but the cubics' t = (dᵢ + dᵢ₊₁ − 2δ)/h holds 2δ = 3e308 = ∞ on the first piece.
const PEAKS: &str =
    "t,G\n# a comment and a blank line move the data's lines\n\n0,0\n1,1.5e308\n2,0\n3,1.5e308\n";

#[test]
fn a_linear_table_of_huge_values_is_read_and_finite() {
    let points = CsvTable::parse_for(PEAKS, Interpolation::Linear)
        .unwrap()
        .points;
    let table = Table::checked(&points, Interpolation::Linear, Outside::Error).unwrap();
    // Halfway up the first chord: 0.75e308 (by hand), exact but for rounding.
    let half = table.value(0.5).unwrap();
    assert!((half / 0.75e308 - 1.0).abs() <= 1e-15, "{half}");
    for i in 0..=300 {
        let x = f64::from(i) * 0.01;
        assert!(table.value(x).unwrap().is_finite(), "at {x}");
    }
}

#[test]
fn a_pchip_or_spline_table_whose_cubics_overflow_is_refused_at_its_line() {
    for interpolation in [Interpolation::Pchip, Interpolation::Spline] {
        let error = CsvTable::parse_for(PEAKS, interpolation).unwrap_err();
        // The first piece, from (0, 0) on line 4 to (1, 1.5e308) on line 5.
        assert_eq!((error.line, error.column), (5, 1), "{error}");
        let kind = ReadErrorKind::InterpolantNotFinite {
            interpolation: interpolation.name(),
            from_line: 4,
            from: (0.0, 0.0),
            to: (1.0, 1.5e308),
        };
        assert_eq!(error.kind, kind);
        let name = interpolation.name();
        assert_eq!(
            error.to_string(),
            format!(
                "line 5, column 1: the {name} interpolant from (0.0, 0.0) (line 4) to \
                 (1.0, 1.5e308) is not finite (its values or slopes overflow between the \
                 points)"
            )
        );
        // The same points given as numbers: the typed error names the piece's right end.
        let points = CsvTable::parse(PEAKS).unwrap().points;
        assert_eq!(
            Table::checked(&points, interpolation, Outside::Zero),
            Err(InvalidPoints::InterpolantNotFinite { index: 1 })
        );
    }
}

#[test]
fn a_motor_whose_spline_overflows_is_refused_at_its_line() {
    // The curve starts from (0, 0) (added, on the header's line 1); 1.5e308 at t = 1 s and
    // 0 at 2 s: the first piece overflows as above.
    let text = "M1 75 757 0 3.0 5.0 X\n1 1.5e308\n2 0\n";
    assert!(Motor::parse_for(text, Interpolation::Linear).is_ok());
    let error = Motor::parse_for(text, Interpolation::Spline).unwrap_err();
    assert_eq!(error.line, 2, "{error}");
    assert!(
        matches!(
            error.kind,
            ReadErrorKind::InterpolantNotFinite {
                interpolation: "spline",
                ..
            }
        ),
        "{error}"
    );
}

#[test]
fn accepted_cubics_of_large_values_are_finite_everywhere_on_their_data() {
    // Values 1/150 of the above pass the check; then the lookups and the derivative
    // tables must be finite at every argument of the data (a sweep of 3 001 points).
    let points = Points::new(vec![0.0, 1.0, 2.0, 3.0], vec![0.0, 1e306, 0.0, 1e306]).unwrap();
    for interpolation in [Interpolation::Pchip, Interpolation::Spline] {
        let table = Table::checked(&points, interpolation, Outside::Error).unwrap();
        let slope = table.derivative();
        let curvature = slope.derivative();
        for i in 0..=3000 {
            let x = f64::from(i) * 1e-3;
            for (which, t) in [
                ("value", &table),
                ("slope", &slope),
                ("curvature", &curvature),
            ] {
                let v = t.value(x).unwrap();
                assert!(v.is_finite(), "{interpolation:?} {which} at {x}: {v}");
            }
        }
    }
}

#[test]
fn an_overflowing_slope_prints_its_numbers_as_written() {
    // Before, `{}` printed 1e308 as 309 digits.
    let error = CsvTable::parse("x,F\n0,1e308\n1e-308,-1e308\n").unwrap_err();
    assert_eq!(
        error.to_string(),
        "line 3, column 1: the slope from (0.0, 1e308) to (1e-308, -1e308) is not finite"
    );
}

#[test]
fn a_pchip_whose_curvature_table_overflows_is_refused() {
    // At a tenth of the review's values the pchip's values and slopes are finite, but on the
    // second piece c₃ = 3e307, so the curvature table's 6·c₃ = 1.8e308 overflows (measured:
    // the curvature reads ∞ at t = 1.5). A spline of the same data is finite (its largest
    // curvature, 6e307, measured) and is taken.
    let points = Points::new(vec![0.0, 1.0, 2.0, 3.0], vec![0.0, 1.5e307, 0.0, 1.5e307]).unwrap();
    let curvature = Table::new(&points, Interpolation::Pchip, Outside::Error)
        .derivative()
        .derivative();
    assert!(!curvature.value(1.5).unwrap().is_finite());
    assert_eq!(
        Table::checked(&points, Interpolation::Pchip, Outside::Error),
        Err(InvalidPoints::InterpolantNotFinite { index: 2 })
    );
    let spline = Table::checked(&points, Interpolation::Spline, Outside::Error).unwrap();
    let curvature = spline.derivative().derivative();
    assert!((0..=3000).all(|i| curvature.value(f64::from(i) * 1e-3).unwrap().is_finite()));
}
