//! Tags: `[tag]` / `[tag1, tag2]` before a statement, their syntax errors, and the selection
//! rule (untagged always in; a tagged statement in when all its tags are asked for), down
//! to the parameters the derivation then demands.

use varmass_symbolic::parse::{known_tags, parse_system, select_tags};
use varmass_symbolic::{derive, mechanics::Parameters};

const ROCKET: &str = "coordinates y
mass m: state, rate -mu
body rocket: mass m, position [y]
potential m*g*y
outflow rocket: rate mu, relative_velocity [-u_e]
[drag] force rocket: [-k_d*y'*abs(y')]
[drag, wind] force rocket: [k_w*w*abs(w)]   # interaction: the wind's share of the drag
[wind] check R2_y = 0
check R1_y = -mu*u_e";

fn names(with: &[&str]) -> Vec<String> {
    with.iter().map(|s| s.to_string()).collect()
}

/// The lines of the statements `with` selects.
fn selected_lines(with: &[&str]) -> Vec<u32> {
    let ast = parse_system(ROCKET).expect("parses");
    let selected = select_tags(&ast, &names(with)).expect("known tags");
    selected.statements.iter().map(|s| s.span.line).collect()
}

#[test]
fn tags_are_parsed_with_their_spans() {
    let ast = parse_system(ROCKET).expect("parses");
    let tags: Vec<Vec<(&str, u32, u32)>> = ast
        .statements
        .iter()
        .map(|s| {
            s.tags
                .iter()
                .map(|t| (t.node.as_str(), t.span.line, t.span.column))
                .collect()
        })
        .collect();
    assert_eq!(tags[0], vec![]);
    assert_eq!(tags[5], vec![("drag", 6, 2)]);
    assert_eq!(tags[6], vec![("drag", 7, 2), ("wind", 7, 8)]);
    // The statement's span starts at its keyword.
    assert_eq!(
        (ast.statements[5].span.line, ast.statements[5].span.column),
        (6, 8)
    );
    assert_eq!(known_tags(&ast), names(&["drag", "wind"]));
}

#[test]
fn a_statement_is_in_when_all_its_tags_are_asked_for() {
    assert_eq!(selected_lines(&[]), vec![1, 2, 3, 4, 5, 9]);
    assert_eq!(selected_lines(&["drag"]), vec![1, 2, 3, 4, 5, 6, 9]);
    assert_eq!(selected_lines(&["wind"]), vec![1, 2, 3, 4, 5, 8, 9]);
    assert_eq!(
        selected_lines(&["wind", "drag"]),
        vec![1, 2, 3, 4, 5, 6, 7, 8, 9]
    );
}

#[test]
fn an_unknown_tag_names_the_known_ones() {
    let ast = parse_system(ROCKET).expect("parses");
    let unknown = select_tags(&ast, &names(&["drag", "dragg", "gust"])).unwrap_err();
    let found: Vec<(usize, &str)> = unknown.iter().map(|u| (u.index, u.tag.as_str())).collect();
    assert_eq!(found, vec![(1, "dragg"), (2, "gust")]);
    assert_eq!(
        unknown[0].to_string(),
        "unknown tag `dragg` (did you mean `drag`?); the model's tags are `drag`, `wind`"
    );
    assert_eq!(unknown[0].suggestion.as_deref(), Some("drag"));
    assert_eq!(
        unknown[1].to_string(),
        "unknown tag `gust`; the model's tags are `drag`, `wind`"
    );
    let untagged = parse_system("coordinates x\nkinetic x'^2").expect("parses");
    let unknown = select_tags(&untagged, &names(&["drag"])).unwrap_err();
    assert_eq!(
        unknown[0].to_string(),
        "unknown tag `drag`; the model has no tagged statements"
    );
}

#[test]
fn a_parameter_of_a_left_out_statement_is_not_demanded() {
    let ast = parse_system(ROCKET).expect("parses");
    let parameters = |with: &[&str]| -> Vec<String> {
        let selected = select_tags(&ast, &names(with)).expect("known tags");
        let d = derive(&selected, Parameters::Inferred).unwrap_or_else(|e| panic!("{e:?}"));
        d.parameters.into_iter().map(|(name, _)| name).collect()
    };
    assert_eq!(parameters(&[]), names(&["mu", "g", "u_e"]));
    assert_eq!(parameters(&["drag"]), names(&["mu", "g", "u_e", "k_d"]));
    assert_eq!(
        parameters(&["drag", "wind"]),
        names(&["mu", "g", "u_e", "k_d", "k_w", "w"])
    );
    // Declared fields without k_d: fine without drag, an unknown symbol with it.
    let declared = Parameters::Declared(names(&["mu", "u_e", "g"]));
    let without = select_tags(&ast, &[]).expect("known tags");
    assert!(derive(&without, declared.clone()).is_ok());
    let with_drag = select_tags(&ast, &names(&["drag"])).expect("known tags");
    let errors = derive(&with_drag, declared).unwrap_err();
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(errors[0].message.contains("`k_d`"), "{}", errors[0].message);
    assert_eq!((errors[0].span.line, errors[0].span.column), (6, 24));
}

#[test]
fn malformed_tags_are_diagnostics() {
    let cases = [
        (
            "coordinates x\n[] kinetic x'^2",
            "expected a tag name after `[`",
            2,
            2,
        ),
        (
            "coordinates x\n[drag kinetic x'^2",
            "expected `,` or `]` after `drag`",
            2,
            7,
        ),
        (
            "coordinates x\n[drag,] kinetic x'^2",
            "expected a tag name after `,`",
            2,
            7,
        ),
        (
            "coordinates x\n[drag]\nkinetic x'^2",
            "unexpected the end of the line; expected a statement",
            2,
            7,
        ),
    ];
    for (source, message, line, column) in cases {
        let errors = parse_system(source).unwrap_err();
        assert_eq!(errors[0].message, message, "{source}");
        assert_eq!(
            (errors[0].span.line, errors[0].span.column),
            (line, column),
            "{source}"
        );
    }
    // Recovery resumes at a tagged statement after an error.
    let errors = parse_system("coordinates x\nkinetic 1 +\n[drag] kinetic 2 +").unwrap_err();
    assert_eq!(errors.len(), 2, "{errors:?}");
}
