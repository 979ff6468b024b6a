//! The DSL's keywords, named once (SPEC §2). The parser and the diagnostics use these
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
/// The time symbol.
pub const TIME: &str = "t";

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
];

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
