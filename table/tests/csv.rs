//! The CSV reader: a header naming the two columns, then points; malformed input is a typed
//! error at its line and column.

use varmass_table::{CsvTable, Interpolation, Outside, ReadErrorKind, Table};

#[test]
fn a_header_comments_blank_lines_and_spaces() {
    let table =
        CsvTable::parse("# from somewhere\naltitude_m, density\n\n0, 1.225\r\n 1000 ,1.112\n")
            .unwrap();
    assert_eq!(
        (table.argument.as_str(), table.value.as_str()),
        ("altitude_m", "density")
    );
    assert_eq!(table.points.arguments(), [0.0, 1000.0]);
    assert_eq!(table.points.values(), [1.225, 1.112]);
}

#[test]
fn a_file_starting_with_data_has_no_header() {
    let e = CsvTable::parse("0, 1\n1, 2\n").unwrap_err();
    assert_eq!(
        (e.line, e.column, e.kind),
        (1, 1, ReadErrorKind::HeaderIsData)
    );
}

#[test]
fn a_value_that_is_not_a_number_names_its_column() {
    let e = CsvTable::parse("x,y\n0,1\n1,  abc\n").unwrap_err();
    assert_eq!((e.line, e.column), (3, 5));
    assert_eq!(
        e.kind,
        ReadErrorKind::NotANumber {
            field: "abc".into()
        }
    );
}

#[test]
fn three_columns_are_refused() {
    let e = CsvTable::parse("x,y\n0,1,2\n").unwrap_err();
    assert_eq!(e.line, 2);
    assert!(
        matches!(e.kind, ReadErrorKind::FieldCount { found: 3, .. }),
        "{e}"
    );
}

#[test]
fn arguments_must_increase() {
    let e = CsvTable::parse("x,y\n0,1\n2,1\n1,1\n").unwrap_err();
    assert_eq!((e.line, e.column), (4, 1));
    assert_eq!(
        e.kind,
        ReadErrorKind::NotIncreasing {
            previous: 2.0,
            knot: 1.0
        }
    );
}

#[test]
fn a_nan_value_is_refused() {
    let e = CsvTable::parse("x,y\n0,1\n1,NaN\n").unwrap_err();
    assert_eq!((e.line, e.column), (3, 3));
    assert_eq!(
        e.kind,
        ReadErrorKind::NotFinite {
            field: "NaN".into()
        }
    );
}

#[test]
fn one_point_is_too_few_and_an_empty_file_has_no_header() {
    let e = CsvTable::parse("x,y\n0,1\n").unwrap_err();
    assert_eq!(
        (e.line, e.kind),
        (2, ReadErrorKind::TooFewPoints { found: 1 })
    );
    let e = CsvTable::parse("").unwrap_err();
    assert_eq!(e.line, 1);
    assert!(matches!(e.kind, ReadErrorKind::MissingHeader { .. }), "{e}");
}

#[test]
fn knots_whose_distance_overflows_are_refused() {
    // 1e308 − (−1e308) = 2e308 overflows to ∞: the chord's slope 1/∞ = 0 is finite, and the
    // table would read zero everywhere (F(0) should be ½). Refused at the second point's line.
    let e = CsvTable::parse("t,F\n-1e308,0\n1e308,1\n").unwrap_err();
    assert_eq!((e.line, e.column), (3, 1));
    let kind = ReadErrorKind::SpacingNotFinite {
        from: (-1e308, 0.0),
        to: (1e308, 1.0),
    };
    assert_eq!(e.kind, kind);
    assert_eq!(
        e.to_string(),
        "line 3, column 1: the distance from (-1e308, 0.0) to (1e308, 1.0) is not finite"
    );
    // Each spacing finite (1e308), the span from the first point not (2e308): refused
    // naming the first point, since the lookups' end slack is a part of the span.
    let e = CsvTable::parse("t,F\n-1e308,0\n0,1\n1e308,2\n").unwrap_err();
    assert_eq!(e.line, 4);
    let kind = ReadErrorKind::SpacingNotFinite {
        from: (-1e308, 0.0),
        to: (1e308, 2.0),
    };
    assert_eq!(e.kind, kind);
    // A span that fits (1.6e308) is read: the chord through (−8e307, 0) and (8e307, 16)
    // has slope 1e-307, so F(0) = 8 (measured 8 exactly; bound 1e-14 relative).
    let points = CsvTable::parse("t,F\n-8e307,0\n8e307,16\n").unwrap().points;
    let table = Table::new(&points, Interpolation::Linear, Outside::Error);
    let middle = table.value(0.0).unwrap();
    assert!((middle - 8.0).abs() <= 8e-14, "{middle}");
}
