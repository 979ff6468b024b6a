//! The typed view of a DSL system (docs/dsl.md): statements and expressions, each with its
//! [`Span`]. The AST is purely syntactic: names are not resolved here (that is the
//! `mechanics` stage's job), so `x` in an expression is just [`Expr::Name`].

use super::span::{Span, Spanned};
use std::fmt;

/// An expression node with its position.
pub type ExprNode = Spanned<Box<Expr>>;

/// Binary operators, in the DSL's spelling.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^` (right-associative, binds tighter than unary minus: `-x^2` is `-(x^2)`)
    Pow,
}

impl fmt::Display for BinOp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Pow => "^",
        })
    }
}

/// An expression as written.
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    /// A numeric literal, kept as written (`9.81`, `1e-3`, `2`) so that the engine can turn
    /// it into an exact rational.
    Number(String),
    /// An identifier: a coordinate, parameter, mass, inertia, definition, `t`, or in a
    /// `check` a derived quantity such as `H` or `p_x`.
    Name(String),
    /// `x'` (order 1, a velocity) or `x''` (order 2, an acceleration).
    Derivative {
        /// The coordinate's name.
        name: String,
        /// Number of primes, 1 or 2.
        order: u8,
    },
    /// Unary minus.
    Neg(ExprNode),
    /// A binary operation.
    Binary {
        /// The operator.
        op: BinOp,
        /// Left operand.
        lhs: ExprNode,
        /// Right operand.
        rhs: ExprNode,
    },
    /// A function call such as `sin(theta)` or `atan2(y, x)`. The name is not checked
    /// against the known functions here.
    Call {
        /// The function's name as written, with its span.
        func: Spanned<String>,
        /// The arguments.
        args: Vec<ExprNode>,
    },
}

/// A bracketed vector `[e1, e2, e3]` of 1, 2 or 3 components, with the span of the brackets.
pub type VectorNode = Spanned<Vec<ExprNode>>;

/// A whole system: its statements in source order.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct SystemAst {
    /// The statements, in the order written.
    pub statements: Vec<Statement>,
}

/// One statement with the span of its whole text (keyword to end of line or `;`).
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    /// What the statement says.
    pub kind: StatementKind,
    /// Where it is.
    pub span: Span,
    /// The tags written before the keyword (`[drag] force …`); empty for an untagged
    /// statement. See [`crate::parse::select_tags`] for what they mean.
    pub tags: Vec<Spanned<String>>,
}

/// The statements of the DSL (docs/dsl.md#statements).
#[derive(Clone, Debug, PartialEq)]
pub enum StatementKind {
    /// `coordinates x, y`
    Coordinates(Vec<Spanned<String>>),
    /// `mass m = m0 + c*x` or `mass m: state, rate -mu`
    Mass(MassDecl),
    /// `inertia J = …` (frozen like a mass)
    Inertia(MassDecl),
    /// `let w = …`: a plain definition, inlined, not frozen.
    Let {
        /// The defined name.
        name: Spanned<String>,
        /// Its value.
        value: ExprNode,
    },
    /// `body sled: mass m, position [x]`
    Body(BodyDecl),
    /// `kinetic …`: an extra term of T.
    Kinetic(ExprNode),
    /// `potential …`: a term of V.
    Potential(ExprNode),
    /// `lagrangian …`: a term of L given directly.
    Lagrangian(ExprNode),
    /// `force x: …` (generalized Q*) or `force sled: [ … ]` (applied to a body).
    Force(Load),
    /// `thrust x: …`: the generalized reactive thrust R1 given directly.
    Thrust(Load),
    /// `impact x: …`: the generalized impact force R2 given directly.
    Impact(Load),
    /// `outflow rocket: rate mu, relative_velocity [-u_e]`
    Outflow(Flow),
    /// `inflow sled: velocity [0]`
    Inflow(Flow),
    /// `check lhs = rhs`: an identity verified at derivation time.
    Check {
        /// Left side (usually a derived quantity such as `H`, `p_x` or `x''`).
        lhs: ExprNode,
        /// Right side.
        rhs: ExprNode,
        /// The identity as written, from the left side to the end of the right.
        text: String,
    },
    /// `units x: m, g: m/s^2`: the unit of each name; with it, every term is
    /// dimension-checked (see `docs/dsl.md#units`).
    Units(Vec<UnitDecl>),
    /// `rigid rocket: mass m, inertia J, position [x, y], angle th`: a rigid body.
    Rigid(RigidDecl),
    /// `torque rocket: tau` (planar) or `torque craft: body [..]` (spatial).
    Torque(Load),
    /// `table F(t) = "motors/M1670.eng", outside zero`: a function of one argument read
    /// from a file (docs/tables.md).
    Table(TableDecl),
    /// `input u(t, y, y') [every 0.01]`: a function the user writes in Rust
    /// (docs/inputs.md).
    Input(InputDecl),
    /// `use "lib/thruster.vms" as left: F = 2*F0, on = rocket`: another model file as a
    /// named component (docs/components.md), expanded by [`crate::compose`] before the
    /// derivation.
    Use(UseDecl),
    /// `parameter g0 = 9.80665`: a parameter with its default value (docs/components.md),
    /// replaced by a binding at a use site or by `--set`.
    Parameter(ParameterDecl),
}

/// A `use` statement: `use "FILE" as NAME [: BINDING {, BINDING}]`.
#[derive(Clone, Debug, PartialEq)]
pub struct UseDecl {
    /// The component's file as written (without the quotes), relative to the using file;
    /// the span covers the quotes.
    pub file: Spanned<String>,
    /// The instance's name: the prefix of every name the component declares.
    pub instance: Spanned<String>,
    /// `name = expr`: a name the component reads, bound to an expression of the user's.
    pub bindings: Vec<UseBinding>,
}

/// One `name = expr` of a `use` statement.
#[derive(Clone, Debug, PartialEq)]
pub struct UseBinding {
    /// The component's name being bound.
    pub name: Spanned<String>,
    /// The value, in the using model's names.
    pub value: ExprNode,
}

/// A `parameter` statement: `parameter NAME = NUMBER`.
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterDecl {
    /// The parameter's name.
    pub name: Spanned<String>,
    /// Its default value as written: a number, with an optional sign, in SI units.
    pub default: ExprNode,
    /// The default's value.
    pub value: f64,
}

/// An `input` statement: `input NAME(ARG, …) [every PERIOD]`.
#[derive(Clone, Debug, PartialEq)]
pub struct InputDecl {
    /// The input's name, called as a function.
    pub name: Spanned<String>,
    /// Its arguments as declared: `t`, a coordinate `y` or its velocity `y'`, each with its
    /// number of primes (0 or 1).
    pub arguments: Vec<(Spanned<String>, u8)>,
    /// `every h`: sampled every `h` seconds and held between samples (zero-order hold).
    pub every: Option<Spanned<String>>,
}

/// A `table` statement: `table NAME(ARG) = "FILE" [, OPTION]*` or
/// `table NAME(ARG) = runtime [, OPTION]*`.
#[derive(Clone, Debug, PartialEq)]
pub struct TableDecl {
    /// The table's name, called as a function.
    pub name: Spanned<String>,
    /// The parameter's name inside the statement (at a call the argument is any expression).
    pub parameter: Spanned<String>,
    /// The file as written (without the quotes), relative to the model file; the span
    /// covers the quotes. For `= runtime`, the word `runtime` and its span.
    pub file: Spanned<String>,
    /// `= runtime`: the data come from the struct's field (the macro) or `--table` (the
    /// command line tool), not from a file (docs/tables.md#runtime-tables).
    pub runtime: bool,
    /// `linear` (default), `pchip` or `spline`.
    pub interpolation: varmass_table::Interpolation,
    /// `outside error` (default), `outside zero` or `outside hold`.
    pub outside: varmass_table::Outside,
}

/// The frame a vector is written in: `[..]` the world's, `body [..]` the rigid body's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Frame {
    /// `[..]`: world (inertial) axes.
    #[default]
    World,
    /// `body [..]`: the axes of the rigid body the statement acts on.
    Body,
}

/// A `rigid` declaration (docs/dsl.md#rigid): a rigid body in the plane (`angle`) or in
/// space (`orientation`).
#[derive(Clone, Debug, PartialEq)]
pub struct RigidDecl {
    /// The body's name.
    pub name: Spanned<String>,
    /// The name of its mass (declared by `mass`).
    pub mass: Spanned<String>,
    /// Its inertia about the centre of mass, in the body frame.
    pub inertia: InertiaValue,
    /// The world position of its reference point, 2 (planar) or 3 (spatial) components.
    pub position: VectorNode,
    /// How it is turned.
    pub attitude: Attitude,
    /// `centre [..]`: the centre of mass in the body frame, from the reference point.
    pub centre: Option<VectorNode>,
}

/// The inertia of a rigid body as written.
#[derive(Clone, Debug, PartialEq)]
pub enum InertiaValue {
    /// `inertia J`: planar, about the centre of mass.
    Scalar(ExprNode),
    /// `inertia [A, B, C]`: principal moments along the body axes.
    Principal(VectorNode),
    /// `inertia [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]]`: the full tensor.
    Tensor(Spanned<Vec<VectorNode>>),
}

/// How a rigid body is turned.
#[derive(Clone, Debug, PartialEq)]
pub enum Attitude {
    /// `angle th`: planar, the angle from the world axes to the body axes.
    Angle(ExprNode),
    /// `orientation zyx(psi, th, phi)`: spatial, an intrinsic Euler sequence; or
    /// `orientation quaternion(e0, e1, e2, e3)`, a quaternion (scalar first).
    Orientation {
        /// The sequence as written (`zyx`, or `quaternion`), with its span.
        sequence: Spanned<String>,
        /// Its three angles, in the order of the sequence (a quaternion's four components).
        angles: Vec<ExprNode>,
    },
}

/// One `name: unit` of a `units` statement. The unit is kept as an expression (`kg*m^2`,
/// `m/s^2`, `1`) and read by the `units` module, which reports unknown units.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitDecl {
    /// The name given a unit.
    pub name: Spanned<String>,
    /// Its unit, as written.
    pub unit: ExprNode,
}

/// A `mass` or `inertia` declaration.
#[derive(Clone, Debug, PartialEq)]
pub struct MassDecl {
    /// The frozen symbol's name.
    pub name: Spanned<String>,
    /// How it changes.
    pub law: MassLaw,
}

/// How a mass (or inertia) evolves.
#[derive(Clone, Debug, PartialEq)]
pub enum MassLaw {
    /// `= expr`: a law m(q, t).
    Law(ExprNode),
    /// `: state, rate expr`: a state variable with its own rate ṁ.
    State {
        /// ṁ as an expression.
        rate: ExprNode,
    },
}

/// A `body` declaration: a particle with a frozen mass and a position r(q, t).
#[derive(Clone, Debug, PartialEq)]
pub struct BodyDecl {
    /// The body's name.
    pub name: Spanned<String>,
    /// The name of its mass (declared by `mass`).
    pub mass: Spanned<String>,
    /// Its position in 1, 2 or 3 dimensions.
    pub position: VectorNode,
}

/// The target and value of `force`, `thrust` or `impact`.
#[derive(Clone, Debug, PartialEq)]
pub struct Load {
    /// A coordinate (then the value is generalized, a scalar) or a body (then a vector).
    pub target: Spanned<String>,
    /// The value as written.
    pub value: LoadValue,
    /// The frame of a vector value (`body [..]` or `[..]`).
    pub frame: Frame,
    /// `at [..]`: the body-frame point of a rigid body the force acts at.
    pub at: Option<VectorNode>,
}

/// A scalar (generalized) or vector (applied to a body) load.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadValue {
    /// A generalized component, for a coordinate target.
    Scalar(ExprNode),
    /// A vector in the body's dimensions, for a body target.
    Vector(VectorNode),
}

/// An `inflow` or `outflow` on a body.
#[derive(Clone, Debug, PartialEq)]
pub struct Flow {
    /// The body the mass joins or leaves.
    pub body: Spanned<String>,
    /// `rate …` (Q2 or Q1, ≥ 0). Absent: ṁ for inflow, −ṁ for outflow.
    pub rate: Option<ExprNode>,
    /// The velocity of the mass that arrives or leaves, if given.
    pub velocity: Option<FlowVelocity>,
    /// The frame the velocity is written in (`body [..]` or `[..]`).
    pub frame: Frame,
    /// `at [..]`: the body-frame point of a rigid body where the mass crosses.
    pub at: Option<VectorNode>,
}

/// How the velocity of flowing mass is given.
#[derive(Clone, Debug, PartialEq)]
pub enum FlowVelocity {
    /// `velocity [...]`: absolute velocity u of the mass.
    Absolute(VectorNode),
    /// `relative_velocity [...]`: v_r = u − v relative to the body.
    Relative(VectorNode),
}
