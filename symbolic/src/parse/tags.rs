//! Optional effects: choosing the tagged statements a model is built with.
//!
//! A statement may start with tags, `[drag] force rocket: [-k_d*y'*abs(y')]`. Selecting with
//! a list of tags keeps
//!
//! * every untagged statement, always;
//! * a tagged statement when **all** of its tags are asked for: `[drag, wind] force …` is an
//!   interaction term, in only when both `drag` and `wind` are.
//!
//! Checks are statements like the others, so a check that only holds with an effect is
//! tagged with it. Selection happens on the AST, before names are resolved, so a parameter
//! that only a left-out statement uses is not a parameter of the selected model.

use super::ast::{Statement, SystemAst};
use super::keywords::nearest;

/// A tag asked for that no statement of the model has.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown tag `{tag}`{}; {}", did_you_mean(suggestion.as_deref()), describe_known(known))]
pub struct UnknownTag {
    /// The tag as asked for.
    pub tag: String,
    /// The model's tag nearest to it, if one is a likely typo of it.
    pub suggestion: Option<String>,
    /// Its position in the list asked for (so a caller can point at it).
    pub index: usize,
    /// The model's tags, sorted.
    pub known: Vec<String>,
}

/// ` (did you mean `drag`?)`, or nothing.
fn did_you_mean(suggestion: Option<&str>) -> String {
    suggestion.map_or(String::new(), |s| format!(" (did you mean `{s}`?)"))
}

/// "the model's tags are `a`, `b`", or that it has none.
fn describe_known(known: &[String]) -> String {
    if known.is_empty() {
        "the model has no tagged statements".to_string()
    } else {
        let quoted: Vec<String> = known.iter().map(|t| format!("`{t}`")).collect();
        format!("the model's tags are {}", quoted.join(", "))
    }
}

/// Every tag used by a statement of `ast`, sorted and without repeats.
pub fn known_tags(ast: &SystemAst) -> Vec<String> {
    let mut tags: Vec<String> = ast
        .statements
        .iter()
        .flat_map(|s| s.tags.iter().map(|t| t.node.clone()))
        .collect();
    tags.sort();
    tags.dedup();
    tags
}

/// The model with the effects `with` (see the module documentation for the rule), or one
/// [`UnknownTag`] per asked tag that no statement has.
///
/// ```
/// use varmass_symbolic::parse::{parse_system, select_tags};
/// let rocket = parse_system(
///     "coordinates y
///      mass m: state, rate -mu
///      body rocket: mass m, position [y]
///      potential m*g*y
///      [drag] force rocket: [-k_d*y'*abs(y')]",
/// )
/// .unwrap();
/// assert_eq!(select_tags(&rocket, &[]).unwrap().statements.len(), 4);
/// assert_eq!(select_tags(&rocket, &["drag".into()]).unwrap().statements.len(), 5);
/// let unknown = select_tags(&rocket, &["wind".into()]).unwrap_err();
/// assert_eq!(unknown[0].to_string(), "unknown tag `wind`; the model's tags are `drag`");
/// let typo = select_tags(&rocket, &["darg".into()]).unwrap_err();
/// let message = "unknown tag `darg` (did you mean `drag`?); the model's tags are `drag`";
/// assert_eq!(typo[0].to_string(), message);
/// ```
pub fn select_tags(ast: &SystemAst, with: &[String]) -> Result<SystemAst, Vec<UnknownTag>> {
    let known = known_tags(ast);
    let unknown: Vec<UnknownTag> = with
        .iter()
        .enumerate()
        .filter(|(_, tag)| !known.contains(tag))
        .map(|(index, tag)| UnknownTag {
            tag: tag.clone(),
            suggestion: nearest(tag, known.iter().map(String::as_str)).map(str::to_string),
            index,
            known: known.clone(),
        })
        .collect();
    if !unknown.is_empty() {
        return Err(unknown);
    }
    let statements = ast
        .statements
        .iter()
        .filter(|s| is_selected(s, with))
        .cloned()
        .collect();
    Ok(SystemAst { statements })
}

/// Whether every tag of `statement` is asked for (true for an untagged one).
fn is_selected(statement: &Statement, with: &[String]) -> bool {
    statement.tags.iter().all(|tag| with.contains(&tag.node))
}
