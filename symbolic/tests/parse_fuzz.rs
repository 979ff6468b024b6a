//! Property tests: the parser never panics, whatever the input, and its diagnostics and
//! spans are always well formed; printing an expression tree and parsing it back gives the
//! same tree.
//!
//! Case counts default to what keeps this file under a few seconds in the test profile;
//! set `VARMASS_FUZZ_CASES` to run each property that many times instead. The random
//! inputs come from a fixed seed, so CI runs the same cases every time; set
//! `VARMASS_FUZZ_SEED` (any `u64`) to search elsewhere in longer local runs.

mod parse_support;

use parse_support::*;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};
use varmass_symbolic::parse::ast::{BinOp, SystemAst};
use varmass_symbolic::parse::{parse_expression, parse_system, Diagnostic};

/// The seed CI uses; `VARMASS_FUZZ_SEED` replaces it.
const DEFAULT_SEED: u64 = 20261123;

fn seed() -> u64 {
    std::env::var("VARMASS_FUZZ_SEED")
        .ok()
        .and_then(|v| v.trim().parse().ok())
        .unwrap_or(DEFAULT_SEED)
}

fn config(default: u32) -> Config {
    Config {
        cases: fuzz_cases(default),
        rng_seed: RngSeed::Fixed(seed()),
        failure_persistence: None,
        ..Config::default()
    }
}

/// Checks everything that must hold of any parse result, beyond not panicking: spans are
/// valid for the source, statements come in order without overlapping, an error result
/// has at least one diagnostic, and every diagnostic renders.
fn check_result(source: &str, result: &Result<SystemAst, Vec<Diagnostic>>) {
    match result {
        Ok(system) => {
            let mut end = 0;
            for statement in &system.statements {
                assert_span_valid(source, statement.span);
                assert!(statement.span.start >= end, "statements overlap");
                end = statement.span.end;
                for root in statement_expressions(statement) {
                    for node in nodes(root) {
                        assert_span_valid(source, node.span);
                        assert!(
                            statement.span.start <= node.span.start
                                && node.span.end <= statement.span.end,
                            "a node outside its statement"
                        );
                    }
                }
            }
        }
        Err(errors) => {
            assert!(!errors.is_empty());
            assert!(errors.len() <= varmass_symbolic::parse::MAX_DIAGNOSTICS + 1);
            for error in errors {
                assert_span_valid(source, error.span);
                assert!(!error.message.is_empty());
                let rendered = error.render(source);
                assert!(
                    rendered.contains(&format!("--> {}:{}", error.span.line, error.span.column))
                );
            }
        }
    }
}

/// Pieces of DSL text and troublemakers: keywords, names, numbers, operators, brackets,
/// separators, comments, primes, and characters the DSL does not use.
fn dsl_piece() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => prop::sample::select(vec![
            "coordinates", "mass", "inertia", "let", "body", "kinetic", "potential",
            "lagrangian", "force", "thrust", "impact", "outflow", "inflow", "check", "state",
            "rate", "position", "velocity", "relative_velocity", "x", "m", "sin", "t", "_a",
            "[drag] ", "[a, b]",
        ])
        .prop_map(str::to_string),
        4 => prop::sample::select(vec![
            " ", " ", "\n", ";", ",", ":", "=", "+", "-", "*", "/", "^", "(", ")", "[", "]",
            "'", "''", "#", ".", "e", "E", "\t", "\r\n",
        ])
        .prop_map(str::to_string),
        1 => "[0-9]{1,3}(\\.[0-9]{0,2})?([eE][+-]?[0-9]{0,2})?",
        1 => prop::sample::select(vec!["θ", "\u{0}", "$", "字", "é", "\u{301}", "\u{feff}", "@", "\"", "\\"])
            .prop_map(str::to_string),
    ]
}

fn dsl_string() -> impl Strategy<Value = String> {
    prop::collection::vec(dsl_piece(), 0..60).prop_map(|pieces| pieces.concat())
}

/// One edit of a source, applied on characters so the result stays valid UTF-8.
#[derive(Clone, Debug)]
enum Mutation {
    Insert(prop::sample::Index, char),
    Delete(prop::sample::Index, usize),
    Swap(prop::sample::Index, prop::sample::Index),
    Duplicate(prop::sample::Index, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let chars = prop::sample::select(
        "()[],:;=+-*/^'#.\n xm0eθ\u{0}"
            .chars()
            .collect::<Vec<char>>(),
    );
    prop_oneof![
        (any::<prop::sample::Index>(), chars).prop_map(|(i, c)| Mutation::Insert(i, c)),
        (any::<prop::sample::Index>(), 1usize..8).prop_map(|(i, n)| Mutation::Delete(i, n)),
        (any::<prop::sample::Index>(), any::<prop::sample::Index>())
            .prop_map(|(i, j)| Mutation::Swap(i, j)),
        (any::<prop::sample::Index>(), 1usize..12).prop_map(|(i, n)| Mutation::Duplicate(i, n)),
    ]
}

fn mutate(source: &str, mutations: &[Mutation]) -> String {
    let mut chars: Vec<char> = source.chars().collect();
    for mutation in mutations {
        let len = chars.len().max(1);
        match mutation {
            Mutation::Insert(i, c) => {
                let at = i.index(chars.len() + 1);
                chars.insert(at, *c);
            }
            Mutation::Delete(i, n) => {
                let at = i.index(len).min(chars.len());
                let end = (at + n).min(chars.len());
                chars.drain(at..end);
            }
            Mutation::Swap(i, j) => {
                if !chars.is_empty() {
                    let (a, b) = (i.index(chars.len()), j.index(chars.len()));
                    chars.swap(a, b);
                }
            }
            Mutation::Duplicate(i, n) => {
                let at = i.index(len).min(chars.len());
                let end = (at + n).min(chars.len());
                let copy: Vec<char> = chars[at..end].to_vec();
                chars.splice(end..end, copy);
            }
        }
    }
    chars.into_iter().collect()
}

/// An expression tree, independent of the parser's AST.
#[derive(Clone, Debug)]
enum Tree {
    Number(String),
    Name(String),
    Derivative(String, u8),
    Neg(Box<Tree>),
    Binary(BinOp, Box<Tree>, Box<Tree>),
    Call(String, Vec<Tree>),
}

fn name() -> impl Strategy<Value = String> {
    "[a-zA-Z_][a-zA-Z0-9_]{0,4}"
}

fn tree() -> impl Strategy<Value = Tree> {
    let leaf = prop_oneof![
        "[0-9]{1,4}(\\.[0-9]{1,3})?([eE][+-]?[0-9]{1,2})?".prop_map(Tree::Number),
        "\\.[0-9]{1,3}".prop_map(Tree::Number),
        name().prop_map(Tree::Name),
        (name(), 1u8..=2).prop_map(|(n, o)| Tree::Derivative(n, o)),
    ];
    leaf.prop_recursive(6, 48, 3, |inner| {
        prop_oneof![
            inner.clone().prop_map(|t| Tree::Neg(Box::new(t))),
            (
                prop::sample::select(vec![
                    BinOp::Add,
                    BinOp::Sub,
                    BinOp::Mul,
                    BinOp::Div,
                    BinOp::Pow
                ]),
                inner.clone(),
                inner.clone()
            )
                .prop_map(|(op, l, r)| Tree::Binary(op, Box::new(l), Box::new(r))),
            (name(), prop::collection::vec(inner, 0..3)).prop_map(|(f, args)| Tree::Call(f, args)),
        ]
    })
}

/// Prints a tree fully parenthesized. `loose` spreads it over lines and blanks (legal
/// inside parentheses) so that the parser sees different text from the expected print.
fn print(tree: &Tree, loose: bool) -> String {
    let gap = if loose { " \n\t " } else { " " };
    match tree {
        Tree::Number(text) | Tree::Name(text) => text.clone(),
        Tree::Derivative(name, order) => format!("{name}{}", "'".repeat(*order as usize)),
        Tree::Neg(inner) => format!("(-{})", print(inner, loose)),
        Tree::Binary(op, l, r) => format!("({}{gap}{op}{gap}{})", print(l, loose), print(r, loose)),
        Tree::Call(f, args) => {
            let args: Vec<String> = args.iter().map(|a| print(a, loose)).collect();
            format!("{f}({})", args.join(&format!(",{gap}")))
        }
    }
}

proptest! {
    #![proptest_config(config(10_000))]

    #[test]
    fn random_dsl_text_never_panics(source in dsl_string()) {
        let result = parse_system(&source);
        check_result(&source, &result);
        if let Err(error) = parse_expression(&source) {
            assert_span_valid(&source, error.span);
            let _ = error.render(&source);
        }
    }
}

/// A model with tagged statements (optional effects).
const TAGGED: &str = "coordinates y
mass m: state, rate -mu
body rocket: mass m, position [y]
[drag] force rocket: [-k_d*y'*abs(y')]
[drag, wind] force rocket: [k_w*w]
[drag] check Q_y = -k_d*y'*abs(y')";

proptest! {
    #![proptest_config(config(4_000))]

    #[test]
    fn mutated_examples_never_panic(
        example in prop::sample::select(vec![SLED_PAPER, SLED_BODY, ROCKET, EVERY_STATEMENT, TAGGED]),
        mutations in prop::collection::vec(mutation(), 1..5),
    ) {
        let source = mutate(example, &mutations);
        let result = parse_system(&source);
        check_result(&source, &result);
    }
}

proptest! {
    #![proptest_config(config(2_000))]

    #[test]
    fn printed_trees_parse_back_to_themselves(tree in tree(), loose in any::<bool>()) {
        let source = print(&tree, loose);
        let parsed = parse_expression(&source)
            .map_err(|e| TestCaseError::fail(e.render(&source)))?;
        // `show` prints the parsed tree in exactly the tight form of `print`.
        prop_assert_eq!(show(&parsed), print(&tree, false));
        // And each node's span is the text of that node alone.
        for node in nodes(&parsed) {
            let alone = parse_expression(text(&source, node.span))
                .map_err(|e| TestCaseError::fail(e.to_string()))?;
            prop_assert_eq!(show(&alone), show(node));
        }
    }
}

#[test]
fn huge_inputs_are_handled() {
    let cases = [
        "(".repeat(100_000),
        "-".repeat(100_000),
        format!("kinetic {}", "x^".repeat(50_000)),
        format!("kinetic {}", vec!["a"; 50_000].join("+")),
        "kinetic x\n".repeat(20_000),
        "θ".repeat(100_000),
        format!("coordinates {}", vec!["x"; 50_000].join(", ")),
        format!("let {} = 1", "a".repeat(100_000)),
        "\u{0}".repeat(10_000),
        "# comment ; (\n".repeat(10_000),
    ];
    for source in &cases {
        let result = parse_system(source);
        check_result(source, &result);
    }
}
