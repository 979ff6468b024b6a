//! Expressions: precedence and associativity, literals, derivatives, calls, spans, and the
//! nesting limits.

mod parse_support;

use parse_support::*;
use varmass_symbolic::parse::ast::Expr;
use varmass_symbolic::parse::parse_expression;

fn shown(source: &str) -> String {
    match parse_expression(source) {
        Ok(node) => show(&node),
        Err(e) => panic!("{}", e.render(source)),
    }
}

#[test]
fn precedence_and_associativity_table() {
    let table = [
        ("1 + 2 * 3", "(1 + (2 * 3))"),
        ("1 * 2 + 3", "((1 * 2) + 3)"),
        ("a - b - c", "((a - b) - c)"),
        ("a / b / c", "((a / b) / c)"),
        ("a - b + c", "((a - b) + c)"),
        ("a / b * c", "((a / b) * c)"),
        ("2^3^2", "(2 ^ (3 ^ 2))"),
        ("-x^2", "(-(x ^ 2))"),
        ("x^-2", "(x ^ (-2))"),
        ("x^-y^2", "(x ^ (-(y ^ 2)))"),
        ("-x*y", "((-x) * y)"),
        ("a*-b", "(a * (-b))"),
        ("a - -b", "(a - (-b))"),
        ("--a", "(-(-a))"),
        ("a*b^c", "(a * (b ^ c))"),
        ("a^b*c", "((a ^ b) * c)"),
        ("(a+b)*c", "((a + b) * c)"),
        ("a*(b+c)", "(a * (b + c))"),
        ("(a^b)^c", "((a ^ b) ^ c)"),
        ("(-x)^2", "((-x) ^ 2)"),
        ("1/2*m*x'^2", "(((1 / 2) * m) * (x' ^ 2))"),
        ("-1/2", "((-1) / 2)"),
        ("((((a))))", "a"),
        ("f(a + b, -c)^2", "(f((a + b), (-c)) ^ 2)"),
        (
            "atan2(y, x) - min(a, max(b, c))",
            "(atan2(y, x) - min(a, max(b, c)))",
        ),
    ];
    for (source, expected) in table {
        assert_eq!(shown(source), expected, "{source}");
    }
}

#[test]
fn number_literals_keep_their_text() {
    for literal in [
        "2",
        "9.81",
        ".5",
        "1e-3",
        "6.02E23",
        "0.000",
        "1E+7",
        "007",
        "12345678901234567890",
    ] {
        let node = parse_expression(literal).unwrap();
        assert_eq!(*node.node, Expr::Number(literal.to_string()));
        assert_eq!((node.span.start, node.span.end), (0, literal.len()));
    }
}

#[test]
fn names_derivatives_and_calls() {
    assert_eq!(
        *parse_expression("_a1").unwrap().node,
        Expr::Name("_a1".into())
    );
    assert_eq!(
        *parse_expression("x'").unwrap().node,
        Expr::Derivative {
            name: "x".into(),
            order: 1
        }
    );
    assert_eq!(
        *parse_expression("phi_2''").unwrap().node,
        Expr::Derivative {
            name: "phi_2".into(),
            order: 2
        }
    );
    // Blanks between a function and its `(` are allowed; an empty argument list parses
    // (arity is checked later, against the known functions).
    assert_eq!(shown("sin (x)"), "sin(x)");
    assert_eq!(shown("f()"), "f()");
}

#[test]
fn whitespace_newlines_and_comments_inside_an_expression() {
    assert_eq!(shown("  a +\n b # note\n * c  "), "(a + (b * c))");
    assert_eq!(shown("\t(a\n+\nb)\n"), "(a + b)");
}

#[test]
fn spans_cover_exactly_each_node() {
    let source = "a + (b*c)^2 - f(x', 2)";
    let root = parse_expression(source).unwrap();
    let texts: Vec<&str> = nodes(&root).iter().map(|n| text(source, n.span)).collect();
    assert_eq!(
        texts,
        [
            "a + (b*c)^2 - f(x', 2)",
            "a + (b*c)^2",
            "f(x', 2)",
            "a",
            "(b*c)^2",
            "x'",
            "2",
            "(b*c)",
            "2",
            "b",
            "c"
        ]
    );
    let Expr::Call { func, .. } = &*nodes(&root)[2].node else {
        panic!("not a call")
    };
    assert_eq!(text(source, func.span), "f");
    for node in nodes(&root) {
        assert_span_valid(source, node.span);
    }
}

#[test]
fn spans_count_columns_in_characters_and_lines_from_one() {
    let source = "# θ is written theta\n\t(θθ)\n  + theta";
    // The comment holds multi-byte characters: columns are characters, not bytes.
    let root = parse_expression(&source.replace("(θθ)", "(ab)")).unwrap();
    let Expr::Binary { rhs, lhs, .. } = &*root.node else {
        panic!("not binary")
    };
    assert_eq!((lhs.span.line, lhs.span.column), (2, 2));
    assert_eq!((rhs.span.line, rhs.span.column), (3, 5));
    let source = "θ + ab";
    let error = parse_expression(source).unwrap_err();
    assert_eq!((error.span.line, error.span.column), (1, 1));
    let source = "ab + θ";
    let error = parse_expression(source).unwrap_err();
    assert_eq!((error.span.line, error.span.column), (1, 6));
    assert_eq!(text(source, error.span), "θ");
}

#[test]
fn nesting_up_to_the_limit_parses_and_beyond_is_a_diagnostic() {
    let limit = varmass_symbolic::parse::MAX_NESTING as usize;
    let parens = |n: usize| format!("{}x{}", "(".repeat(n), ")".repeat(n));
    assert_eq!(shown(&parens(limit)), "x");
    let error = parse_expression(&parens(limit + 1)).unwrap_err();
    assert!(
        error.message.starts_with("expression nested too deeply"),
        "{}",
        error.message
    );
    assert_eq!(error.span.column as usize, limit + 1);

    let minus = |n: usize| format!("{}x", "-".repeat(n));
    assert!(parse_expression(&minus(limit)).is_ok());
    assert!(parse_expression(&minus(limit + 1)).is_err());

    let powers = |n: usize| format!("x{}", "^x".repeat(n));
    assert!(parse_expression(&powers(limit)).is_ok());
    assert!(parse_expression(&powers(limit + 1)).is_err());

    // Mixed: brackets in calls and signs count alike.
    let calls = |n: usize| format!("{}x{}", "f(-".repeat(n / 2), ")".repeat(n / 2));
    assert!(parse_expression(&calls(limit)).is_ok());
    assert!(parse_expression(&calls(limit + 2)).is_err());
}

#[test]
fn tree_depth_is_bounded_even_for_flat_chains() {
    let depth = varmass_symbolic::parse::MAX_DEPTH as usize;
    // A chain of n terms is a left-leaning tree of depth n.
    let chain = |n: usize| vec!["a"; n].join(" + ");
    assert!(parse_expression(&chain(depth)).is_ok());
    let error = parse_expression(&chain(depth + 1)).unwrap_err();
    assert!(
        error.message.starts_with("expression too deep"),
        "{}",
        error.message
    );
    // Depth is the longest path, not the size: five parenthesized chains of 300 side by
    // side under one product (1500 terms) parse, while the same five chains nested in one
    // another (depth about 5 × 300, with as many operations) are refused.
    let side_by_side = vec![format!("({})", chain(300)); 5].join("*");
    assert_eq!(side_by_side.matches('+').count(), 5 * 299);
    assert!(parse_expression(&side_by_side).is_ok());
    let mut nested = chain(300);
    for _ in 0..4 {
        nested = format!("({nested}) + {}", chain(299));
    }
    assert_eq!(
        nested.matches('+').count(),
        side_by_side.matches('+').count()
    );
    let error = parse_expression(&nested).unwrap_err();
    assert!(
        error.message.starts_with("expression too deep"),
        "depth 1500 must be refused as too deep: {}",
        error.message
    );
}

#[test]
fn the_deepest_accepted_input_fits_a_small_stack() {
    // Test threads get 2 MiB; run the worst accepted inputs on 1 MiB to keep a margin for
    // callers with smaller stacks or less optimized builds.
    let limit = varmass_symbolic::parse::MAX_NESTING as usize;
    let inputs = [
        format!("{}x{}", "(".repeat(limit), ")".repeat(limit)),
        format!("{}x{}", "f(".repeat(limit), ")".repeat(limit)),
        format!("x{}", "^-x".repeat(limit / 2)),
        format!("{}x{}", "(".repeat(limit + 50), ")".repeat(limit + 50)),
        format!(
            "kinetic {}x{}",
            "[".repeat(limit + 50),
            "]".repeat(limit + 50)
        ),
    ];
    let handle = std::thread::Builder::new()
        .stack_size(1 << 20)
        .spawn(move || {
            for input in &inputs {
                let _ = parse_expression(input);
                let _ = varmass_symbolic::parse::parse_system(input);
            }
        })
        .unwrap();
    assert!(handle.join().is_ok());
}
