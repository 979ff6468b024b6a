//! One test per class of syntax error: the message, where it points (line and column, and
//! the text under the span), and that recovery goes on to report later errors.

mod parse_support;

use parse_support::*;
use varmass_symbolic::parse::{parse_expression, parse_system, Diagnostic};

/// (message, line, column, text under the span) of a diagnostic.
fn at(source: &str, d: &Diagnostic) -> (String, u32, u32, String) {
    (
        d.message.clone(),
        d.span.line,
        d.span.column,
        text(source, d.span).to_string(),
    )
}

fn expect(source: &str, message: &str, line: u32, column: u32, under: &str) -> Diagnostic {
    let d = single_error(source);
    assert_eq!(
        at(source, &d),
        (message.to_string(), line, column, under.to_string()),
        "{}",
        d.render(source)
    );
    assert_span_valid(source, d.span);
    d
}

const ALL_STATEMENTS: &str = "coordinates, mass, inertia, let, body, kinetic, potential, \
lagrangian, force, thrust, impact, outflow, inflow, check, units, rigid, torque, table, input, use, \
parameter";

#[test]
fn missing_operand() {
    expect(
        "coordinates x\nmass m = m0 +\n",
        "expected an expression after `+`",
        2,
        14,
        "",
    );
    expect(
        "kinetic a * )",
        "expected an expression after `*`",
        1,
        13,
        ")",
    );
    expect("kinetic -", "expected an expression after `-`", 1, 10, "");
    expect("kinetic 2^", "expected an expression after `^`", 1, 11, "");
    expect(
        "kinetic",
        "expected an expression after `kinetic`",
        1,
        8,
        "",
    );
    expect("let w =", "expected an expression after `=`", 1, 8, "");
    expect(
        "kinetic f(a,)",
        "expected an expression after `,`",
        1,
        13,
        ")",
    );
    expect("kinetic ()", "expected an expression after `(`", 1, 10, ")");
    // Outside parentheses a line break ends the statement, so `b` is a statement of its
    // own (and an unknown one).
    let errors = parse_system("kinetic a +\n  b").unwrap_err();
    assert_eq!(errors.len(), 2);
    assert_eq!(errors[0].message, "expected an expression after `+`");
    assert_eq!((errors[0].span.line, errors[0].span.column), (1, 12));
    assert!(
        errors[0].help.as_deref().unwrap().contains("parentheses"),
        "continuation hint"
    );
    assert!(errors[1].message.starts_with("unknown statement `b`"));
}

#[test]
fn unclosed_brackets_point_at_the_opening_one() {
    let d = expect("kinetic (a + b", "unclosed `(` opened here", 1, 9, "(");
    assert_eq!(
        d.help.as_deref(),
        Some("expected `)` before the end of the input")
    );
    expect(
        "force b: [1, 2; kinetic 1",
        "unclosed `[` opened here",
        1,
        10,
        "[",
    );
    expect("kinetic sin(x + 1", "unclosed `(` opened here", 1, 12, "(");
    // A statement keyword at the start of a later line ends the runaway expression, and
    // that statement is still checked: its own error is reported too.
    let source = "kinetic (a + b\nmass m = 2 +\n";
    let errors = parse_system(source).unwrap_err();
    let found: Vec<_> = errors.iter().map(|d| at(source, d)).collect();
    assert_eq!(
        found,
        [
            (
                "unclosed `(` opened here".to_string(),
                1,
                9,
                "(".to_string()
            ),
            (
                "expected an expression after `+`".to_string(),
                2,
                13,
                String::new()
            ),
        ]
    );
}

#[test]
fn stray_and_mismatched_closing_brackets() {
    let d = expect(
        "kinetic a)",
        "unexpected `)`; expected an operator, `;` or a newline",
        1,
        10,
        ")",
    );
    assert_eq!(
        d.help.as_deref(),
        Some("there is no open `(` for it to close")
    );
    expect(")", "unexpected `)`; expected a statement", 1, 1, ")");
    let d = expect(
        "kinetic (a]",
        "unexpected `]`; expected an operator or `)`",
        1,
        11,
        "]",
    );
    assert_eq!(
        d.help.as_deref(),
        Some("the `(` opened at 1:9 is still open")
    );
    expect(
        "kinetic f(a b)",
        "unexpected `b`; expected an operator, `,` or `)`",
        1,
        13,
        "b",
    );
}

#[test]
fn unknown_statement_suggests_the_closest_keyword() {
    let d = expect(
        "coordinates x\nforse x: 1",
        &format!("unknown statement `forse`; expected one of {ALL_STATEMENTS}"),
        2,
        1,
        "forse",
    );
    assert_eq!(d.help.as_deref(), Some("did you mean `force`?"));
    let d = single_error("banana x");
    assert_eq!(d.help, None, "nothing is close to banana");
    let d = single_error("w = 2");
    assert_eq!(
        d.help.as_deref(),
        Some("to define a name, write `let w = …`")
    );
    let d = expect("+ 1", "unexpected `+`; expected a statement", 1, 1, "+");
    assert!(d
        .help
        .unwrap()
        .starts_with("a statement starts with one of coordinates"));
}

#[test]
fn unknown_duplicate_and_missing_options() {
    let d = expect(
        "body sled: mass m, positon [x]",
        "unknown option `positon` for body; expected `mass` or `position`",
        1,
        20,
        "positon",
    );
    assert_eq!(d.help.as_deref(), Some("did you mean `position`?"));
    expect(
        "outflow r: speed 2",
        "unknown option `speed` for outflow; expected `rate`, `velocity`, `relative_velocity` or `at`",
        1,
        12,
        "speed",
    );
    let d = expect(
        "body b: mass m, position [x], mass n",
        "`mass` given twice for body `b`",
        1,
        31,
        "mass",
    );
    assert_eq!(d.help.as_deref(), Some("first given at 1:9"));
    expect(
        "inflow b: rate 1, rate 2",
        "`rate` given twice for inflow `b`",
        1,
        19,
        "rate",
    );
    expect(
        "body sled: mass m",
        "missing `position` for body `sled`",
        1,
        6,
        "sled",
    );
    expect(
        "body sled: position [x]",
        "missing `mass` for body `sled`",
        1,
        6,
        "sled",
    );
    expect(
        "outflow r: velocity [1], relative_velocity [2]",
        "`relative_velocity` and `velocity` cannot both be given for outflow `r`",
        1,
        26,
        "relative_velocity",
    );
    expect(
        "body b:",
        "expected `mass` or `position` after `:`",
        1,
        8,
        "",
    );
    expect(
        "body b: mass m,",
        "expected `mass` or `position` after `,`",
        1,
        16,
        "",
    );
    expect("body b mass m", "expected `:` after `b`", 1, 8, "mass");
    expect(
        "body b: position x, mass m",
        "expected a vector `[…]` after `position`",
        1,
        18,
        "x",
    );
}

#[test]
fn triple_primes() {
    let d = expect(
        "check x''' = 0",
        "`x'''`: only x' and x'' are allowed",
        1,
        7,
        "x'''",
    );
    assert!(d.help.unwrap().contains("velocity"));
    expect(
        "kinetic phi''''",
        "`phi''''`: only phi' and phi'' are allowed",
        1,
        9,
        "phi''''",
    );
}

#[test]
fn vector_sizes() {
    expect(
        "force b: [1, 2, 3, 4]",
        "a vector has 1 to 3 components, found 4",
        1,
        10,
        "[1, 2, 3, 4]",
    );
    expect(
        "body b: mass m, position []",
        "a vector has 1 to 3 components, found 0",
        1,
        26,
        "[]",
    );
}

#[test]
fn malformed_numbers() {
    let d = expect("kinetic 2x", "malformed number `2x`", 1, 9, "2x");
    assert_eq!(
        d.help.as_deref(),
        Some("a number cannot run into a name; for a product write `2*x`")
    );
    let d = expect("kinetic 1.2.3", "malformed number `1.2.3`", 1, 9, "1.2.3");
    assert!(d.help.unwrap().contains("one decimal point"));
    expect("kinetic 1.", "malformed number `1.`", 1, 9, "1.");
    let d = expect("kinetic 1e + 2", "malformed number `1e`", 1, 9, "1e");
    assert!(d.help.unwrap().contains("exponent"));
    expect("kinetic 2.5E", "malformed number `2.5E`", 1, 9, "2.5E");
    expect(
        "kinetic 1e-3e4",
        "malformed number `1e-3e4`",
        1,
        9,
        "1e-3e4",
    );
}

#[test]
fn characters_outside_the_dsl() {
    let d = expect(
        "kinetic θ",
        "expected an expression after `kinetic`",
        1,
        9,
        "θ",
    );
    assert!(d.help.unwrap().contains("ASCII"));
    let d = expect(
        "kinetic a $ b",
        "unexpected character `$`; expected an operator, `;` or a newline",
        1,
        11,
        "$",
    );
    assert_eq!(d.help.as_deref(), Some("`$` is not part of the DSL"));
    expect(
        "\u{0}",
        "unexpected character `\\0`; expected a statement",
        1,
        1,
        "\u{0}",
    );
    expect(
        "kinetic x '",
        "unexpected `'`; expected an operator, `;` or a newline",
        1,
        11,
        "'",
    );
}

#[test]
fn statement_specific_shapes() {
    expect(
        "mass m",
        "unexpected the end of the input; expected `=` or `:`",
        1,
        7,
        "",
    );
    expect("mass m: rate 2", "expected `state` after `:`", 1, 9, "rate");
    expect(
        "mass m: state rate 2",
        "expected `, rate <expression>` after `state`",
        1,
        15,
        "rate",
    );
    expect("mass m: state, 2", "expected `rate` after `,`", 1, 16, "2");
    expect(
        "coordinates",
        "expected a coordinate name after `coordinates`",
        1,
        12,
        "",
    );
    expect(
        "coordinates x y",
        "unexpected `y`; expected `,`, `;` or a newline",
        1,
        15,
        "y",
    );
    expect("force x 2", "expected `:` after `x`", 1, 9, "2");
    expect(
        "force x:",
        "expected an expression or a vector `[…]` after `:`",
        1,
        9,
        "",
    );
    expect(
        "force b: [1] + 2",
        "unexpected `+`; expected `;` or a newline",
        1,
        14,
        "+",
    );
    expect(
        "check a",
        "unexpected the end of the input; expected an operator or `=`",
        1,
        8,
        "",
    );
    expect(
        "check a = b = c",
        "unexpected `=`; expected an operator, `;` or a newline",
        1,
        13,
        "=",
    );
    expect(
        "inflow b velocity [0]",
        "unexpected `velocity`; expected `:`, `;` or a newline",
        1,
        10,
        "velocity",
    );
    expect("let = 2", "expected a name after `let`", 1, 5, "=");
}

#[test]
fn nesting_limit_is_a_diagnostic() {
    let source = format!("kinetic {}1{}", "(".repeat(300), ")".repeat(300));
    let d = single_error(&source);
    assert!(
        d.message.starts_with("expression nested too deeply"),
        "{}",
        d.message
    );
    assert_eq!(d.span.column, 9 + 200);
}

#[test]
fn recovery_reports_every_broken_statement_and_nothing_else() {
    let source = "\
coordinates x
forse x: 1
mass m = m0 + * c
kinetic (1/2*m*
   x'^2 + )
body sled: mass m, position [x, 1, 2, 3]
potential m*g*x   # fine
check x''' = 0; let w = 2 2
inflow sled: velocity [0]
";
    let errors = parse_system(source).unwrap_err();
    let found: Vec<(String, u32, u32)> = errors
        .iter()
        .map(|d| (d.message.clone(), d.span.line, d.span.column))
        .collect();
    let expected = [
        ("unknown statement `forse`", 2, 1),
        ("expected an expression after `+`", 3, 15),
        ("expected an expression after `+`", 5, 11),
        ("a vector has 1 to 3 components, found 4", 6, 29),
        ("`x'''`: only x' and x'' are allowed", 8, 7),
        (
            "unexpected `2`; expected an operator, `;` or a newline",
            8,
            27,
        ),
    ];
    assert_eq!(found.len(), expected.len(), "{found:#?}");
    for ((message, line, column), (prefix, l, c)) in found.iter().zip(expected) {
        assert!(message.starts_with(prefix), "{message} vs {prefix}");
        assert_eq!((*line, *column), (l, c), "{message}");
    }
}

#[test]
fn recovery_skips_a_broken_multi_line_expression_whole() {
    // The error is on line 2 inside the parentheses; lines 3 and 4 belong to the same
    // statement and must not be reported as statements of their own.
    let source = "kinetic (a +\n  $ b +\n  c\n  + d)\nlet w = 1 +\n";
    let errors = parse_system(source).unwrap_err();
    let lines: Vec<u32> = errors.iter().map(|d| d.span.line).collect();
    assert_eq!(lines, [2, 5], "{errors:#?}");
}

#[test]
fn too_many_errors_stop_with_a_note() {
    let source = "nonsense\n".repeat(500);
    let errors = parse_system(&source).unwrap_err();
    let limit = varmass_symbolic::parse::MAX_DIAGNOSTICS;
    assert_eq!(errors.len(), limit + 1);
    assert!(errors[limit].message.starts_with("too many syntax errors"));
}

#[test]
fn parse_expression_errors() {
    let d = parse_expression("").unwrap_err();
    assert_eq!(
        d.message,
        "expected an expression, found the end of the input"
    );
    let d = parse_expression("a b").unwrap_err();
    assert_eq!(
        d.message,
        "unexpected `b`; expected an operator or the end of the expression"
    );
    assert_eq!(d.span.column, 3);
    let d = parse_expression("x; y").unwrap_err();
    assert_eq!(d.span.column, 2);
}

#[test]
fn render_shows_a_caret_under_the_offending_text() {
    let source = "coordinates x\nmass m = mm mm + c*x\n";
    let d = single_error(source);
    assert_eq!(
        d.render(source),
        "\
error: unexpected `mm`; expected an operator, `;` or a newline
 --> 2:13
  |
2 | mass m = mm mm + c*x
  |             ^^"
    );
    // A diagnostic made by a later stage renders the same way.
    let d = Diagnostic::new(
        varmass_symbolic::Span::from_range(source, 23, 25),
        "unknown symbol `mm`",
    );
    let rendered = d.render(source);
    assert!(rendered.contains(" --> 2:10\n"), "{rendered}");
    assert!(
        rendered.ends_with("2 | mass m = mm mm + c*x\n  |          ^^"),
        "{rendered}"
    );
}

#[test]
fn render_aligns_after_tabs_and_wide_or_combining_characters() {
    // A tab shows as four spaces; `θ` takes one column, `字` two, a combining accent none.
    // (Such characters only reach a rendered line through comments or a later stage's
    // diagnostics, so the span is made here.)
    let source = "kinetic\tθ字e\u{301} + $";
    let dollar = source.find('$').unwrap();
    let span = varmass_symbolic::Span::from_range(source, dollar, dollar + 1);
    assert_eq!(span.column, 16, "the column counts characters");
    let rendered = Diagnostic::new(span, "here").render(source);
    let lines: Vec<&str> = rendered.lines().collect();
    assert_eq!(lines[3], "1 | kinetic    θ字e\u{301} + $");
    // kinetic(7) + tab(4) + θ(1) + 字(2) + e(1) + accent(0) + " + "(3) = 18 columns.
    assert_eq!(lines[4], format!("  | {}^", " ".repeat(18)));
    // Control characters are shown as one replacement character each.
    let source = "a\u{0}b $";
    let span = varmass_symbolic::Span::from_range(source, 4, 5);
    let rendered = Diagnostic::new(span, "here").render(source);
    assert!(
        rendered.ends_with("1 | a\u{fffd}b $\n  |     ^"),
        "{rendered}"
    );
}

#[test]
fn render_multi_line_empty_and_out_of_range_spans() {
    let source = "kinetic (a +\n  b +\n  c\nlet";
    let span = varmass_symbolic::Span::from_range(source, 8, 22);
    let rendered = Diagnostic::new(span, "multi")
        .with_help("a help")
        .render(source);
    assert_eq!(
        rendered,
        "\
error: multi
 --> 1:9
  |
1 | kinetic (a +
  |         ^^^^
...
3 |   c
  | ^^^
  = help: a help"
    );
    // Empty span at the end of the input, after a newline.
    let rendered =
        Diagnostic::new(varmass_symbolic::Span::from_range("ab\n", 3, 3), "end").render("ab\n");
    assert!(rendered.ends_with("2 | \n  | ^"), "{rendered}");
    // A span from another, longer source, and a span ending inside a character: clamped,
    // never a panic.
    let far = varmass_symbolic::Span {
        start: 100,
        end: 200,
        line: 9,
        column: 9,
    };
    assert!(Diagnostic::new(far, "far").render("θ").contains("1 | θ"));
    let inside = varmass_symbolic::Span {
        start: 0,
        end: 1,
        line: 1,
        column: 1,
    };
    assert!(Diagnostic::new(inside, "half")
        .render("θx")
        .ends_with("1 | θx\n  | ^"));
}
