//! The DSL's keywords, named once (docs/dsl.md). The parser and the diagnostics use these
//! constants, never the literals.

/// `coordinates x, y`
pub const COORDINATES: &str = "coordinates";
/// `mass m = …` / `mass m: state, rate …`
pub const MASS: &str = "mass";
/// `inertia J = …`
pub const INERTIA: &str = "inertia";
/// `let w = …`
pub const LET: &str = "let";
/// `body b: mass m, position [...]`
pub const BODY: &str = "body";
/// `kinetic …`
pub const KINETIC: &str = "kinetic";
/// `potential …`
pub const POTENTIAL: &str = "potential";
/// `lagrangian …`
pub const LAGRANGIAN: &str = "lagrangian";
/// `force x: …`
pub const FORCE: &str = "force";
/// `thrust x: …`
pub const THRUST: &str = "thrust";
/// `impact x: …`
pub const IMPACT: &str = "impact";
/// `outflow b: …`
pub const OUTFLOW: &str = "outflow";
/// `inflow b: …`
pub const INFLOW: &str = "inflow";
/// `check lhs = rhs`
pub const CHECK: &str = "check";
/// `units x: m, g: m/s^2`
pub const UNITS: &str = "units";
/// `: state` in a mass declaration.
pub const STATE: &str = "state";
/// `rate …` option of a state mass or a flow.
pub const RATE: &str = "rate";
/// `position [...]` option of a body.
pub const POSITION: &str = "position";
/// `velocity [...]` option of a flow.
pub const VELOCITY: &str = "velocity";
/// `relative_velocity [...]` option of a flow.
pub const RELATIVE_VELOCITY: &str = "relative_velocity";
/// `rigid b: mass m, inertia J, position [..], angle th`
pub const RIGID: &str = "rigid";
/// `torque b: tau`
pub const TORQUE: &str = "torque";
/// `angle th` option of a planar rigid body.
pub const ANGLE: &str = "angle";
/// `orientation zyx(psi, th, phi)` option of a spatial rigid body.
pub const ORIENTATION: &str = "orientation";
/// `centre [..]` option of a rigid body.
pub const CENTRE: &str = "centre";
/// `at [..]`: the body-frame point of a force or a flow on a rigid body.
pub const AT: &str = "at";
/// The time symbol.
pub const TIME: &str = "t";
/// `table F(t) = "file", …` (docs/tables.md)
pub const TABLE: &str = "table";
/// `input u(t, y, y') [every 0.01]` (docs/inputs.md)
pub const INPUT: &str = "input";
/// The option of an input naming its sample period.
pub const EVERY: &str = "every";
/// The option of a table naming what it is worth outside its data.
pub const OUTSIDE: &str = "outside";
/// `table F(t) = runtime`: the table's data are given at run time (docs/tables.md).
pub const RUNTIME: &str = "runtime";

/// `use "file.vms" as name: a = …` (docs/components.md)
pub const USE: &str = "use";
/// `as name` in a `use` statement.
pub const AS: &str = "as";
/// `parameter g0 = 9.80665`: a parameter with a default value (docs/components.md)
pub const PARAMETER: &str = "parameter";

/// Every statement keyword, for "expected one of" messages.
pub const STATEMENTS: &[&str] = &[
    COORDINATES,
    MASS,
    INERTIA,
    LET,
    BODY,
    KINETIC,
    POTENTIAL,
    LAGRANGIAN,
    FORCE,
    THRUST,
    IMPACT,
    OUTFLOW,
    INFLOW,
    CHECK,
    UNITS,
    RIGID,
    TORQUE,
    TABLE,
    INPUT,
    USE,
    PARAMETER,
];

/// The options of a `table` statement: an interpolation, or `outside` and a rule.
pub const TABLE_OPTIONS: &[&str] = &["linear", "pchip", "spline", OUTSIDE];

/// The rules after `outside` in a `table` statement.
pub const OUTSIDE_RULES: &[&str] = &["error", "zero", "hold"];

/// The options of a `rigid` statement.
pub const RIGID_OPTIONS: &[&str] = &[MASS, INERTIA, POSITION, ANGLE, ORIENTATION, CENTRE];

/// The twelve intrinsic Euler sequences of `orientation` (docs/mechanics.md#rigid-bodies).
pub const EULER_SEQUENCES: &[&str] = &[
    "xyz", "xzy", "yxz", "yzx", "zxy", "zyx", "xyx", "xzx", "yxy", "yzy", "zxz", "zyz",
];

/// `orientation quaternion(e0, e1, e2, e3)`: the attitude as a quaternion of four coordinates,
/// normalized by the derivation (docs/mechanics.md#quaternions), singular nowhere.
pub const QUATERNION: &str = "quaternion";

/// The functions the DSL knows, with their arity.
pub const FUNCTIONS: &[(&str, usize)] = &[
    ("sin", 1),
    ("cos", 1),
    ("tan", 1),
    ("exp", 1),
    ("ln", 1),
    ("sqrt", 1),
    ("abs", 1),
    ("sign", 1),
    ("tanh", 1),
    ("sinh", 1),
    ("cosh", 1),
    ("asin", 1),
    ("acos", 1),
    ("atan", 1),
    ("atan2", 2),
    ("min", 2),
    ("max", 2),
];

/// The options of a `body` statement.
pub const BODY_OPTIONS: &[&str] = &[MASS, POSITION];

/// The options of an `inflow` or `outflow` statement.
pub const FLOW_OPTIONS: &[&str] = &[RATE, VELOCITY, RELATIVE_VELOCITY, AT];

/// The candidate closest to `word` by edit distance (insertions, deletions, substitutions and
/// swaps of neighbouring characters), if it is close enough to be a likely typo: at most 2
/// edits, and fewer edits than `word` has characters (so `t` does not suggest `let`).
///
/// ```
/// use varmass_symbolic::parse::keywords::{closest, STATEMENTS};
/// assert_eq!(closest("forse", STATEMENTS), Some("force"));
/// assert_eq!(closest("xyz", STATEMENTS), None);
/// ```
pub fn closest<'k>(word: &str, candidates: &[&'k str]) -> Option<&'k str> {
    let length = word.chars().count();
    // A word much longer than every candidate is no typo of one; this also keeps the
    // quadratic distance cheap on absurd input.
    let longest = candidates
        .iter()
        .map(|c| c.chars().count())
        .max()
        .unwrap_or(0);
    if length > longest + 2 {
        return None;
    }
    candidates
        .iter()
        .map(|&candidate| (edit_distance(word, candidate), candidate))
        .filter(|&(distance, _)| distance <= 2 && distance < length)
        .min_by_key(|&(distance, _)| distance)
        .map(|(_, candidate)| candidate)
}

/// [`closest`] among names from anywhere (a scope, a table): `name` itself is left out, and
/// the candidates are sorted first so that a tie is decided the same way every time.
///
/// ```
/// use varmass_symbolic::parse::keywords::nearest;
/// assert_eq!(nearest("muu", ["x", "mu", "muu"].into_iter()), Some("mu"));
/// ```
pub fn nearest<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> Option<&'a str> {
    let mut candidates: Vec<&str> = candidates.filter(|c| *c != name).collect();
    candidates.sort_unstable();
    candidates.dedup();
    closest(name, &candidates)
}

/// Optimal-string-alignment distance: Levenshtein plus adjacent transpositions, so `msas`
/// is one edit from `mass` (a swap is the most common typing slip).
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    // Three rolling rows: the transposition case looks two rows back.
    let mut before: Vec<usize> = vec![0; b.len() + 1];
    let mut previous: Vec<usize> = (0..=b.len()).collect();
    let mut current: Vec<usize> = vec![0; b.len() + 1];
    for (i, &ca) in a.iter().enumerate() {
        current[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitution = previous[j] + usize::from(ca != cb);
            let mut best = substitution.min(previous[j + 1] + 1).min(current[j] + 1);
            if i > 0 && j > 0 && a[i - 1] == cb && ca == b[j - 1] {
                best = best.min(before[j - 1] + 1);
            }
            current[j + 1] = best;
        }
        std::mem::swap(&mut before, &mut previous);
        std::mem::swap(&mut previous, &mut current);
    }
    previous[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_each_kind_of_edit_once() {
        assert_eq!(edit_distance("mass", "mass"), 0);
        assert_eq!(edit_distance("mas", "mass"), 1); // insertion
        assert_eq!(edit_distance("masss", "mass"), 1); // deletion
        assert_eq!(edit_distance("forse", "force"), 1); // substitution
        assert_eq!(edit_distance("msas", "mass"), 1); // swap
        assert_eq!(edit_distance("", "let"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }

    #[test]
    fn closest_suggests_only_plausible_typos() {
        assert_eq!(closest("positon", BODY_OPTIONS), Some("position"));
        assert_eq!(closest("inflwo", STATEMENTS), Some("inflow"));
        assert_eq!(closest("t", STATEMENTS), None);
        assert_eq!(closest("banana", STATEMENTS), None);
    }
}
