//! The registry of derived quantities: for each quantity a system derives, its DSL name
//! (`H`, `p_x`, `mdot_m`, …), its labels in the derivation text and LaTeX, its dimension
//! rule, where a [`Derivation`] holds it, the generated method that carries it and how the
//! run-time interpreter evaluates it.
//!
//! Everything that lists quantities reads this one table: the reserved names and the
//! `check` bindings of `mechanics`, the units table, the macro's name message, the command
//! line tool's recordable names, the emitter's vector methods, and the interpreter's
//! groups. Not (yet) the lists of *expressions* that evaluators walk: the roots of every
//! equation ([`Derivation::equation_roots`], read by the emitter and the checks of inputs
//! and tables) and the switches' `state_rate_roots` are kept by hand beside the
//! `Derivation`'s fields. [`Quantity::spec`] is one exhaustive `match`, so a new variant
//! without its entry does not compile; `symbolic/tests/quantities.rs` holds every entry to
//! each of those uses (ARCHITECTURE.md, "Add a generated quantity").
//!
//! ```
//! use varmass_symbolic::quantity::{Quantity, Named};
//! let (quantity, index) = Quantity::parse("R1_x", &["x"], &[]).unwrap();
//! assert_eq!((quantity, index), (Quantity::ReactiveThrust, 0));
//! assert_eq!(quantity.spec().text, "R1_#");
//! assert!(matches!(Quantity::Energy.spec().name, Named::Scalar("H")));
//! ```

use crate::dimension::Dimension;
use crate::emit::Method;
use crate::expr::Id;
use crate::mechanics::{Derivation, VelocitySolve};

/// Declares `Quantity` and `Quantity::ALL` from one list, so that `ALL` cannot miss a
/// variant (the order of the list is the order of `ALL`).
macro_rules! quantities {
    ($($(#[$doc:meta])* $variant:ident,)*) => {
        /// A derived quantity of a system, one group of values (a scalar, one value per
        /// coordinate or per mass, or the mass matrix).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum Quantity {
            $($(#[$doc])* $variant,)*
        }

        impl Quantity {
            /// Every quantity: the named ones in the order messages list them, then the
            /// intermediates. The position of each is its [`Quantity::index`] (the
            /// interpreter's group).
            pub const ALL: &'static [Quantity] = &[$(Quantity::$variant,)*];
        }
    };
}

quantities! {
    /// The energy function p·q̇ − L, equal to H on p = ∂*L/∂q̇ (eqs. 9–10) (`H`).
    Energy,
    /// L = T − V (`L`).
    Lagrangian,
    /// T (`T`).
    Kinetic,
    /// V (`V`).
    Potential,
    /// The energy-budget power dH/dt (`power`).
    Power,
    /// p = ∂*L/∂q̇ (eq. 8) (`p_x`).
    Momenta,
    /// Q*, the active force (`Q_x`).
    ActiveForce,
    /// R1, the reactive thrust (`R1_x`).
    ReactiveThrust,
    /// R2, the impact force (`R2_x`).
    ImpactForce,
    /// d*p/dt = ∂*L/∂q + Q* − R1 + R2 (eq. 14) (`dp_x`).
    FrozenMomentumRate,
    /// The true ṗ = d*p/dt + Σᵢ ṁᵢ ∂*p/∂mᵢ (`pdot_x`).
    MomentumRate,
    /// ṁ of every mass, in the runtime's `MASSES` order (`mdot_m`).
    MassRates,
    /// q̈(q, q̇, t) (`x''`); in closed form up to `SYMBOLIC_INVERSE_MAX_DOF` coordinates,
    /// otherwise solved from eq. 6 where it is evaluated.
    Accelerations,
    /// M = ∂²L/∂q̇², row-major (N² values).
    MassMatrix,
    /// ∂*L/∂q, masses frozen (= −∂*H/∂q, eq. 13).
    LagrangianGradient,
    /// Σᵢ ṁᵢ ∂*p/∂mᵢ, the mass-flux term of the true ṗ.
    MassFluxForce,
    /// The right side of M q̈ = d*p/dt − ∂*p/∂q q̇ − ∂*p/∂t (eq. 6).
    AccelerationRhs,
}

/// How a quantity is named in the DSL (in `check`s, `--record`, `units` messages).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Named {
    /// One value with this name.
    Scalar(&'static str),
    /// One value per coordinate `x`: `{prefix}x{suffix}`.
    PerCoordinate {
        /// Before the coordinate's name (`p_`).
        prefix: &'static str,
        /// After it (`''`).
        suffix: &'static str,
    },
    /// One value per mass `m`: `{prefix}m`.
    PerMass(&'static str),
    /// Not nameable: an intermediate of the equations.
    Unnamed,
}

/// The dimension of a quantity, from those of the coordinates and masses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DimensionRule {
    /// An energy (J).
    Energy,
    /// A power (W).
    Power,
    /// Energy·time / dim(q): a generalized momentum.
    Momentum,
    /// Energy / dim(q): a generalized force, a torque (N·m) on a dimensionless q.
    Force,
    /// dim(q) / s².
    Acceleration,
    /// dim(m) / s.
    MassRate,
    /// No single dimension (the mass matrix: one per entry).
    Mixed,
}

/// Where a quantity's values come from and how the interpreter groups them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluated {
    /// Velocity-form expressions, compiled into one tape of the interpreter.
    VelocityForm,
    /// Velocity-form expressions when solved symbolically; else eq. 6 solved numerically
    /// where it is evaluated (the interpreter, the generated `accelerations`).
    SolvedOrNumeric,
}

/// One registry entry.
#[derive(Clone, Copy, Debug)]
pub struct Spec {
    /// The DSL name.
    pub name: Named,
    /// The label in the derivation text and the doc comments, `#` for the coordinate or
    /// mass name (`Q*_#`).
    pub text: &'static str,
    /// The label in LaTeX, `#` as in [`Spec::text`] (`Q^*_{#}`).
    pub latex: &'static str,
    /// The dimension rule.
    pub dimension: DimensionRule,
    /// The trait method that carries it in generated code, if one does.
    pub method: Option<Method>,
    /// The doc comment's title of that method.
    pub doc: &'static str,
    /// How it is evaluated at run time.
    pub evaluated: Evaluated,
}

impl Quantity {
    /// The registry entry of this quantity.
    pub fn spec(self) -> Spec {
        use DimensionRule as D;
        use Named::*;
        let per = |prefix| PerCoordinate { prefix, suffix: "" };
        let v = Evaluated::VelocityForm;
        let entry = |name, text, latex, dimension, method, doc| Spec {
            name,
            text,
            latex,
            dimension,
            method,
            doc,
            evaluated: v,
        };
        match self {
            Quantity::MassRates => entry(
                PerMass("mdot_"),
                "d#/dt",
                "\\dot{#}",
                D::MassRate,
                Some(Method::MassRate),
                "ṁ of every mass along the motion.",
            ),
            Quantity::Momenta => entry(
                per("p_"),
                "p_#",
                "p_{#}",
                D::Momentum,
                Some(Method::Momenta),
                "The generalized momenta p = ∂*L/∂q̇ (eq. 8).",
            ),
            Quantity::MassMatrix => entry(
                Unnamed,
                "M",
                "M",
                D::Mixed,
                Some(Method::MassMatrix),
                "The mass matrix M = ∂²L/∂q̇², masses frozen.",
            ),
            Quantity::Lagrangian => entry(
                Scalar("L"),
                "L",
                "L",
                D::Energy,
                Some(Method::Lagrangian),
                "The Lagrangian L = T − V.",
            ),
            Quantity::Kinetic => entry(Scalar("T"), "T", "T", D::Energy, None, "T"),
            Quantity::Potential => entry(Scalar("V"), "V", "V", D::Energy, None, "V"),
            Quantity::LagrangianGradient => entry(
                Unnamed,
                "∂*L/∂#",
                "\\frac{\\partial^* L}{\\partial #}",
                D::Force,
                Some(Method::LagrangianGradient),
                "∂*L/∂q, masses frozen (= −∂*H/∂q, eq. 13).",
            ),
            Quantity::ActiveForce => entry(
                per("Q_"),
                "Q*_#",
                "Q^*_{#}",
                D::Force,
                Some(Method::ActiveForce),
                "The generalized active force Q* (eq. 22 for the sled).",
            ),
            Quantity::ReactiveThrust => entry(
                per("R1_"),
                "R1_#",
                "R_{1,#}",
                D::Force,
                Some(Method::ReactiveThrust),
                "The generalized reactive thrust R1 = Σ Q1 v_r1 · ∂r/∂q.",
            ),
            Quantity::ImpactForce => entry(
                per("R2_"),
                "R2_#",
                "R_{2,#}",
                D::Force,
                Some(Method::ImpactForce),
                "The generalized impact force R2 = Σ Q2 v_r2 · ∂r/∂q (eq. 23 for the sled).",
            ),
            Quantity::FrozenMomentumRate => entry(
                per("dp_"),
                "d*p_#/dt",
                "\\frac{d^* p_{#}}{dt}",
                D::Force,
                None,
                "d*p/dt (eq. 14)",
            ),
            Quantity::MassFluxForce => entry(
                Unnamed,
                "flux_#",
                "\\sum_i \\dot m_i \\frac{\\partial^* p_{#}}{\\partial m_i}",
                D::Force,
                Some(Method::MassFluxForce),
                "The mass-flux term Σ ṁᵢ ∂*p/∂mᵢ of the true ṗ.",
            ),
            Quantity::MomentumRate => entry(
                per("pdot_"),
                "dp_#/dt",
                "\\dot p_{#}",
                D::Force,
                None,
                "The true ṗ = d*p/dt + Σ ṁᵢ ∂*p/∂mᵢ.",
            ),
            Quantity::AccelerationRhs => entry(
                Unnamed,
                "rhs_#",
                "(M \\ddot q)_{#}",
                D::Force,
                None,
                "The right side of M q̈ (eq. 6).",
            ),
            Quantity::Accelerations => Spec {
                evaluated: Evaluated::SolvedOrNumeric,
                ..entry(
                    PerCoordinate {
                        prefix: "",
                        suffix: "''",
                    },
                    "#''",
                    "\\ddot{#}",
                    D::Acceleration,
                    Some(Method::Accelerations),
                    "q̈(q, q̇, t) from M q̈ = d*p/dt − ∂*p/∂q q̇ − ∂*p/∂t (eq. 6).",
                )
            },
            Quantity::Power => entry(
                Scalar("power"),
                "dH/dt",
                "\\frac{dH}{dt}",
                D::Power,
                Some(Method::Power),
                "The energy-budget power dH/dt = ∂*H/∂t + q̇·(Q* − R1 + R2 + Σ ṁ ∂*p/∂m) + Σ ṁ ∂H/∂m.",
            ),
            Quantity::Energy => entry(
                Scalar("H"),
                "H",
                "H",
                D::Energy,
                Some(Method::Hamiltonian),
                "The Hamiltonian H(q, p, t) = p·q̇ − L (eqs. 9–10).",
            ),
        }
    }

    /// The position of this quantity in [`Quantity::ALL`].
    pub fn index(self) -> usize {
        // ALL holds every variant (one macro declares both), so the search succeeds.
        Quantity::ALL
            .iter()
            .position(|q| *q == self)
            .unwrap_or(usize::MAX)
    }

    /// The expressions of this quantity in `d`, in velocity form; empty when `d` does not
    /// hold it in closed form (accelerations beyond `SYMBOLIC_INVERSE_MAX_DOF`).
    pub fn read(self, d: &Derivation) -> Vec<Id> {
        match self {
            Quantity::MassRates => d.mass_rates.clone(),
            Quantity::Momenta => d.momenta.clone(),
            Quantity::MassMatrix => d.mass_matrix.iter().flatten().copied().collect(),
            Quantity::Lagrangian => vec![d.lagrangian],
            Quantity::Kinetic => vec![d.kinetic],
            Quantity::Potential => vec![d.potential],
            Quantity::LagrangianGradient => d.lagrangian_gradient.clone(),
            Quantity::ActiveForce => d.active_force.clone(),
            Quantity::ReactiveThrust => d.reactive_thrust.clone(),
            Quantity::ImpactForce => d.impact_force.clone(),
            Quantity::FrozenMomentumRate => d.frozen_momentum_rate.clone(),
            Quantity::MassFluxForce => d.mass_flux_force.clone(),
            Quantity::MomentumRate => d.momentum_rate.clone(),
            Quantity::AccelerationRhs => d.acceleration_rhs.clone(),
            Quantity::Accelerations => d.accelerations.clone().unwrap_or_default(),
            Quantity::Power => vec![d.power],
            Quantity::Energy => vec![d.energy],
        }
    }

    /// The quantity and index (coordinate or mass) a DSL name means, if it names one:
    /// `p_x` → (momenta, index of `x`). `coordinates` and `masses` are the names, in order.
    pub fn parse(name: &str, coordinates: &[&str], masses: &[&str]) -> Option<(Quantity, usize)> {
        let find = |list: &[&str], item: &str| list.iter().position(|c| *c == item);
        Quantity::ALL.iter().find_map(|q| {
            let index = match q.spec().name {
                Named::Scalar(s) => (s == name).then_some(0),
                Named::PerCoordinate { prefix, suffix } => {
                    let inner = name.strip_prefix(prefix)?.strip_suffix(suffix)?;
                    find(coordinates, inner)
                }
                Named::PerMass(prefix) => find(masses, name.strip_prefix(prefix)?),
                Named::Unnamed => None,
            }?;
            Some((*q, index))
        })
    }

    /// Every DSL name of every named quantity of a system with these coordinates and
    /// masses, with the quantity and index: what a `check` or `--record` may name.
    pub fn names(coordinates: &[&str], masses: &[&str]) -> Vec<(String, Quantity, usize)> {
        let mut all = Vec::new();
        for &q in Quantity::ALL {
            match q.spec().name {
                Named::Scalar(s) => all.push((s.to_string(), q, 0)),
                Named::PerCoordinate { prefix, suffix } => {
                    for (a, c) in coordinates.iter().enumerate() {
                        all.push((format!("{prefix}{c}{suffix}"), q, a));
                    }
                }
                Named::PerMass(prefix) => {
                    for (i, m) in masses.iter().enumerate() {
                        all.push((format!("{prefix}{m}"), q, i));
                    }
                }
                Named::Unnamed => {}
            }
        }
        all
    }

    /// The label in the derivation text (`Q*_x`), `#` replaced by the coordinate or mass
    /// `name` (empty for a scalar).
    pub fn text_label(self, name: &str) -> String {
        self.spec().text.replace('#', name)
    }

    /// The LaTeX label (`Q^*_{x}`), `#` replaced by `name`.
    pub fn latex_label(self, name: &str) -> String {
        self.spec().latex.replace('#', name)
    }

    /// The dimension of this quantity on a coordinate or mass of dimension `of` (ignored
    /// by the scalars), `None` when it has none or overflows.
    pub fn dimension(self, of: Option<Dimension>) -> Option<Dimension> {
        let per_time = |order: i128| Dimension::TIME.pow(crate::expr::Rational::integer(order));
        match self.spec().dimension {
            DimensionRule::Energy => Some(Dimension::ENERGY),
            DimensionRule::Power => Some(Dimension::POWER),
            DimensionRule::Momentum => Dimension::ENERGY
                .checked_mul(Dimension::TIME)?
                .checked_div(of?),
            DimensionRule::Force => Dimension::ENERGY.checked_div(of?),
            DimensionRule::Acceleration => of?.checked_div(per_time(2)?),
            DimensionRule::MassRate => of?.checked_div(Dimension::TIME),
            DimensionRule::Mixed => None,
        }
    }

    /// Whether a value in J of this quantity is a torque (a force on a dimensionless
    /// coordinate), written N·m.
    pub fn is_generalized_force(self) -> bool {
        self.spec().dimension == DimensionRule::Force
    }
}

/// Names that may not be declared (nor be parameters) because they mean the time or, in
/// `check`s, a derived quantity: `t`, every scalar name of the registry (`H`, `L`, `T`,
/// `V`, `power`) and every prefix of a per-coordinate or per-mass name (`p_`, `Q_`, `R1_`,
/// `R2_`, `dp_`, `pdot_`, `mdot_`).
pub fn is_reserved(name: &str) -> bool {
    name == crate::parse::keywords::TIME
        || Quantity::ALL.iter().any(|q| match q.spec().name {
            Named::Scalar(s) => s == name,
            Named::PerCoordinate { prefix, .. } | Named::PerMass(prefix) => {
                !prefix.is_empty() && name.starts_with(prefix)
            }
            Named::Unnamed => false,
        })
}

/// The reserved names for a message: `` `H`, `L`, `T`, `V`, `power`, `p_…`, … ``, in
/// registry order (a per-coordinate name without a prefix, `x''`, reserves nothing).
pub fn reserved_names() -> String {
    let names = Quantity::ALL.iter().filter_map(|q| match q.spec().name {
        Named::Scalar(s) => Some(format!("`{s}`")),
        Named::PerCoordinate { prefix, .. } | Named::PerMass(prefix) if !prefix.is_empty() => {
            Some(format!("`{prefix}…`"))
        }
        _ => None,
    });
    names.collect::<Vec<_>>().join(", ")
}

/// The velocity-form roots of every quantity the registry holds for `d`, in
/// [`Quantity::ALL`] order, plus q̇ in closed form: what the doc comments show.
pub fn documented_roots(d: &Derivation) -> Vec<Id> {
    let mut roots: Vec<Id> = Quantity::ALL.iter().flat_map(|q| q.read(d)).collect();
    roots.extend(d.hamiltonian);
    roots.extend(d.closed_laws.iter().flatten());
    if let VelocitySolve::Symbolic(v) = &d.velocities {
        roots.extend(v);
    }
    roots
}
