//! The `units` statement in the grammar: entries with spans, and its syntax errors.

use varmass_symbolic::parse::ast::StatementKind;
use varmass_symbolic::parse::parse_system;
use varmass_symbolic::units::expression_text;

#[test]
fn units_parse_into_spanned_entries() {
    let source = "coordinates x\nunits x: m, g: m/s^2,\tI: kg*m^(2)  # comment\nunits c: 1";
    let system = parse_system(source).unwrap();
    let StatementKind::Units(entries) = &system.statements[1].kind else {
        panic!("{:?}", system.statements[1]);
    };
    let shown: Vec<(String, String, &str)> = entries
        .iter()
        .map(|e| {
            let name = e.name.node.clone();
            let unit = &source[e.unit.span.start..e.unit.span.end];
            (name, expression_text(&e.unit), unit)
        })
        .collect();
    assert_eq!(
        shown,
        [
            ("x".to_string(), "m".to_string(), "m"),
            ("g".to_string(), "m/s^2".to_string(), "m/s^2"),
            ("I".to_string(), "kg*m^2".to_string(), "kg*m^(2)"),
        ]
    );
    assert_eq!(
        (entries[1].name.span.line, entries[1].name.span.column),
        (2, 13)
    );
    assert!(matches!(&system.statements[2].kind, StatementKind::Units(e) if e.len() == 1));
}

#[test]
fn units_is_a_keyword_only_at_the_head_of_a_statement() {
    let system = parse_system("coordinates x\npotential units*x").unwrap();
    assert_eq!(system.statements.len(), 2);
}

#[test]
fn a_malformed_units_statement_is_a_positioned_diagnostic() {
    for (source, message, column) in [
        ("units x m", "expected `:` after `x`", 9),
        ("units x:", "expected an expression after `:`", 9),
        ("units", "expected a name after `units`", 6),
        ("units x: m,", "expected a name after `,`", 12),
        (
            "units x: m y: s",
            "unexpected `y`; expected an operator, `,`, `;` or a newline",
            12,
        ),
    ] {
        let errors = parse_system(source).unwrap_err();
        assert_eq!(errors.len(), 1, "{source}: {errors:?}");
        assert_eq!(errors[0].message, message, "{source}");
        assert_eq!(errors[0].span.column, column, "{source}");
    }
}
