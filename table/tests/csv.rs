//! The CSV reader: a header naming the two columns, then points; malformed input is a typed
//! error at its line and column.

use varmass_table::{CsvTable, ReadErrorKind};

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
