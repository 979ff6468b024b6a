//! The checked model: every name resolved, every expression lowered, every declaration
//! validated (docs/dsl.md). This is the input of the derivation; `build.rs` makes it.

use rustc_hash::FxHashMap;

use super::linear::Matrix;
use super::resolve::{Binding, Parameters};
use crate::expr::{ExprPool, Id, Symbol};
use crate::parse::ast::ExprNode;
use crate::parse::Span;

/// A generalized coordinate and its symbols.
#[derive(Clone, Debug)]
pub struct Coordinate {
    /// Its name, as declared.
    pub name: String,
    /// q.
    pub q: Symbol,
    /// q̇ (`x'`).
    pub velocity: Symbol,
    /// q̈ (`x''`).
    pub acceleration: Symbol,
    /// p (`p_x`).
    pub momentum: Symbol,
    /// Where it was declared.
    pub span: Span,
}

/// How a frozen mass (or inertia) evolves.
#[derive(Clone, Debug)]
pub enum MassKind {
    /// A law m(q, t), as written (may name earlier masses).
    Law(Id),
    /// A state variable with its declared rate ṁ.
    State {
        /// ṁ.
        rate: Id,
    },
}

/// A frozen mass or inertia.
#[derive(Clone, Debug)]
pub struct Mass {
    /// Its name.
    pub name: String,
    /// Its frozen symbol.
    pub symbol: Symbol,
    /// Law or state.
    pub kind: MassKind,
    /// Declared with `inertia` rather than `mass`.
    pub inertia: bool,
    /// Where it was declared.
    pub span: Span,
}

/// A particle (frozen mass and position r(q, t)) or a rigid body, whose `position` is then
/// its centre of mass.
#[derive(Clone, Debug)]
pub struct Body {
    /// Its name.
    pub name: String,
    /// Index into [`Model::masses`].
    pub mass: usize,
    /// r(q, t), 1 to 3 components; for a rigid body the centre of mass r_O + R c.
    pub position: Vec<Id>,
    /// The rotation and inertia of a rigid body (`None` for a particle).
    pub rigid: Option<Rigid>,
    /// Where it was declared.
    pub span: Span,
}

/// What a `rigid` statement adds to a body (docs/mechanics.md#rigid-bodies). Body-frame
/// vectors are turned into world components by `rotation`.
#[derive(Clone, Debug)]
pub struct Rigid {
    /// r_O(q, t): the world position of the reference point `position` names.
    pub origin: Vec<Id>,
    /// R(q, t): body components → world components (2×2 or 3×3).
    pub rotation: Matrix,
    /// ω in body components as a function of q, q̇ (one component in the plane).
    pub angular_velocity: Vec<Id>,
    /// In space, the middle angle of the Euler sequence and whether the sequence is proper
    /// (its first axis is its last, `zxz`): the attitude is singular (gimbal lock) where
    /// that angle's cosine (Tait–Bryan, `zyx`) or sine (proper) vanishes.
    pub euler_middle: Option<(Id, bool)>,
    /// With a quaternion, the kinetic term of its radial rate that makes M regular
    /// (docs/mechanics.md#quaternions), zero on every motion from a q·q̇ = 0 start.
    pub gauge: Option<Id>,
    /// With a quaternion, its components (e0, e1, e2, e3): coordinates or `0`.
    pub quaternion: Option<[Id; 4]>,
    /// The inertia about the centre of mass in body components (1×1 in the plane), frozen.
    pub inertia: Matrix,
    /// c: the centre of mass from the reference point, body components, frozen.
    pub centre: Vec<Id>,
}

/// Which generalized force a load adds to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadKind {
    /// `force`: the active non-potential force Q*.
    Active,
    /// `thrust`: the reactive thrust R1.
    Thrust,
    /// `impact`: the impact force R2.
    Impact,
}

/// Where a load acts.
#[derive(Clone, Debug)]
pub enum LoadTarget {
    /// A generalized component on coordinate `index`.
    Coordinate(usize, Id),
    /// A vector on body `index`.
    Body(usize, Vec<Id>),
    /// A world-component vector on rigid body `body` at its body-frame point `point`.
    Point {
        /// Index into [`Model::bodies`].
        body: usize,
        /// The force, world components.
        vector: Vec<Id>,
        /// Where it acts: body components from the reference point.
        point: Vec<Id>,
    },
    /// A torque on rigid body `body`, body components (one in the plane).
    Torque(usize, Vec<Id>),
}

/// A `force`, `thrust` or `impact` statement.
#[derive(Clone, Debug)]
pub struct Load {
    /// Which force.
    pub kind: LoadKind,
    /// Where and how much.
    pub target: LoadTarget,
    /// The statement.
    pub span: Span,
}

/// The velocity of mass that joins or leaves a body.
#[derive(Clone, Debug)]
pub enum FlowVelocityValue {
    /// Absolute velocity u.
    Absolute(Vec<Id>),
    /// Velocity relative to the body, v_r = u − v.
    Relative(Vec<Id>),
    /// Not given: the mass moves with the body (v_r = 0, no force).
    WithBody,
}

/// An `inflow` or `outflow`.
#[derive(Clone, Debug)]
pub struct Flow {
    /// `true` for inflow (Q2), `false` for outflow (Q1).
    pub inflow: bool,
    /// Index into [`Model::bodies`].
    pub body: usize,
    /// The declared rate (≥ 0), if any.
    pub rate: Option<Id>,
    /// The velocity of the flowing mass, world components.
    pub velocity: FlowVelocityValue,
    /// On a rigid body, the body-frame point where the mass crosses (the reference point
    /// when not given); `None` on a particle.
    pub point: Option<Vec<Id>>,
    /// The statement.
    pub span: Span,
}

/// Which part of L a directly given term belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TermKind {
    /// `kinetic`: added to T.
    Kinetic,
    /// `potential`: added to V.
    Potential,
    /// `lagrangian`: added to L.
    Lagrangian,
}

/// A directly given term of T, V or L.
#[derive(Clone, Debug)]
pub struct Term {
    /// Which part.
    pub kind: TermKind,
    /// Its value.
    pub value: Id,
    /// The statement.
    pub span: Span,
}

/// A `check`, kept as syntax until the derived quantities exist.
#[derive(Clone, Debug)]
pub struct Check {
    /// Left side.
    pub lhs: ExprNode,
    /// Right side.
    pub rhs: ExprNode,
    /// The check as written (`check p_x = m*x'`).
    pub source: String,
    /// The statement.
    pub span: Span,
}

/// A system with every name resolved and every expression lowered.
#[derive(Debug)]
pub struct Model {
    /// The expression arena holding every expression of the model.
    pub pool: ExprPool,
    /// The time symbol.
    pub time: Symbol,
    /// Generalized coordinates, in declaration order.
    pub coordinates: Vec<Coordinate>,
    /// Masses and inertias: state masses first (in declaration order), then laws.
    pub masses: Vec<Mass>,
    /// Parameters (declared, or inferred from use), with their symbols.
    pub parameters: Vec<(String, Symbol)>,
    /// Bodies.
    pub bodies: Vec<Body>,
    /// Loads.
    pub loads: Vec<Load>,
    /// Flows.
    pub flows: Vec<Flow>,
    /// Terms of T, V, L given directly.
    pub terms: Vec<Term>,
    /// Checks, in source order.
    pub checks: Vec<Check>,
    /// Tables, in source order (`tables.rs`).
    pub tables: Vec<super::tables::ModelTable>,
    /// Inputs, in source order (`inputs.rs`).
    pub inputs: Vec<super::inputs::ModelInput>,
    pub(crate) names: FxHashMap<String, Binding>,
    /// Where each declared name (coordinate, mass, inertia, definition, body, table) is
    /// written in its declaration.
    pub(crate) declared_at: FxHashMap<String, Span>,
    pub(crate) parameter_mode: Parameters,
}
