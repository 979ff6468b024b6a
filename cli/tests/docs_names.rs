//! The names the manual gives are the code's names, so that the documents cannot drift from
//! the tool again. The code holds one list of each: the methods are `args::Method` (clap's
//! `--method` values, which scene files read too), the recordable quantities are the
//! registry's (`Quantity::names`) beside the coordinates, velocities and masses. README.md's
//! stepper table, Python's `METHODS`, the `--record` lists of README.md and docs/cli.md and
//! the `--record` help are each held to them, both ways: a name missing from a document or
//! a name the code no longer has fails.

use std::collections::BTreeSet;
use std::path::Path;

use clap::CommandFactory;
use varmass::symbolic::quantity::Quantity;
use varmass_cli::args::{Cli, Method};

/// A file of the repository (the cli crate sits one level below its root).
fn repository_file(path: &str) -> String {
    let full = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path);
    std::fs::read_to_string(&full).unwrap_or_else(|e| panic!("{}: {e}", full.display()))
}

/// What `--record` may name in a model with one coordinate `x` and one mass `m`: the
/// coordinate, its velocity, the mass, and every named quantity of the registry.
fn recordable() -> BTreeSet<String> {
    let mut names: BTreeSet<String> = ["x", "x'", "m"].map(String::from).into();
    names.extend(
        Quantity::names(&["x"], &["m"])
            .into_iter()
            .map(|(name, ..)| name),
    );
    names
}

/// The texts between backticks in `text`.
fn quoted(text: &str) -> Vec<String> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .map(String::from)
        .collect()
}

/// The cells of the column headed `` `--method` `` in the first table that has one, in row
/// order, without their backticks.
fn stepper_table(readme: &str) -> Vec<String> {
    let mut lines = readme
        .lines()
        .skip_while(|l| !(l.starts_with('|') && l.contains("`--method`")));
    let header = lines
        .next()
        .expect("README.md has a table with a `--method` column");
    let column = header
        .split('|')
        .position(|cell| cell.trim() == "`--method`")
        .expect("the header has the column");
    lines
        .skip(1) // the |---| line
        .take_while(|l| l.starts_with('|'))
        .map(|row| {
            row.split('|')
                .nth(column)
                .unwrap_or("")
                .trim()
                .trim_matches('`')
                .to_string()
        })
        .collect()
}

/// The names quoted in `text` from "`--record` takes" to "the model's" (the `let` names
/// and expressions that follow are the model's own).
fn record_list(text: &str, file: &str) -> BTreeSet<String> {
    let start = text
        .find("`--record` takes")
        .unwrap_or_else(|| panic!("{file} says what `--record` takes"));
    let rest = &text[start + "`--record` takes".len()..];
    let end = rest
        .find("the model's")
        .unwrap_or_else(|| panic!("{file}: the list ends"));
    quoted(&rest[..end]).into_iter().collect()
}

/// README.md's table has one row per stepper, each `--method` value once (its order is
/// the reader's, by use, not the enum's), and the text counts them right ("Nine steppers").
#[test]
fn the_readme_stepper_table_has_each_method_once() {
    let readme = repository_file("README.md");
    let table = stepper_table(&readme);
    let mut sorted = table.clone();
    sorted.sort();
    let mut expected = Method::names();
    expected.sort();
    assert_eq!(
        sorted, expected,
        "README.md's stepper table against args::Method"
    );
    const COUNTS: [&str; 13] = [
        "no", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten",
        "eleven", "twelve",
    ];
    let count = format!("{} steppers", COUNTS[table.len().min(12)]);
    assert!(
        readme.to_lowercase().contains(&count),
        "README.md should say \"{count}\""
    );
}

/// The flag `--ID` of `varmass run`, as clap has it.
fn run_flag(id: &str) -> clap::Arg {
    let command = Cli::command();
    let run = command.find_subcommand("run").expect("the run subcommand");
    let flag = run.get_arguments().find(|a| a.get_id() == id);
    flag.unwrap_or_else(|| panic!("no --{id} flag")).clone()
}

/// Python checks `method=` against `varmass.METHODS` before calling the tool (its message
/// lists them): that is the native module's `Method::names`, which must be what `varmass
/// run --method` takes, in the tool's order, and `_checks.py` must hold no list of its own.
#[test]
fn python_methods_are_the_tools() {
    let taken: Vec<String> = run_flag("method")
        .get_possible_values()
        .iter()
        .map(|v| v.get_name().to_string())
        .collect();
    assert_eq!(Method::names(), taken);
    let checks = repository_file("python/varmass/_checks.py");
    assert!(
        checks.contains("METHODS = tuple(_native.METHODS)"),
        "_checks.py should read the native module's METHODS"
    );
    assert!(
        !checks.contains("METHODS = ("),
        "_checks.py should hold no list of methods of its own"
    );
    let native = repository_file("python/src/lib.rs");
    assert!(native.contains("m.add(\"METHODS\", varmass_cli::args::Method::names())"));
}

/// README.md and docs/cli.md list every recordable name and none that is not.
#[test]
fn the_documents_list_every_recordable_name() {
    for file in ["README.md", "docs/cli.md"] {
        let listed = record_list(&repository_file(file), file);
        assert_eq!(
            listed,
            recordable(),
            "{file}'s `--record` list against the registry"
        );
    }
}

/// `varmass run --help` names every recordable quantity under `--record`.
#[test]
fn the_record_help_names_every_recordable_name() {
    let help = run_flag("record")
        .get_help()
        .expect("--record has help")
        .to_string();
    let words: BTreeSet<&str> = help
        .split(|c: char| c == ',' || c == ':' || c == '(' || c == ')' || c.is_whitespace())
        .collect();
    let missing: Vec<String> = recordable()
        .into_iter()
        .filter(|name| !words.contains(name.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "--record's help omits {missing:?}: {help}"
    );
}
