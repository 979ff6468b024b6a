//! The units of a checked system: every declared or inferred name, and the derived
//! quantities (`H`, `p_x`, `Q_th`, …) whose dimensions follow from the coordinates' by
//! the rules of the registry ([`crate::quantity`]).

use crate::dimension::Dimension;
use crate::quantity::{Named, Quantity};
use rustc_hash::FxHashMap;

/// What a system with a `units` statement says about dimensions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UnitTable {
    /// Coordinates, parameters, masses, inertias and definitions with their dimensions.
    pub(crate) dimensions: FxHashMap<String, Dimension>,
    /// The unit as the `units` statement writes it (`N/m`, `rad`).
    pub(crate) written: FxHashMap<String, String>,
    /// Coordinate names, in declaration order.
    pub(crate) coordinates: Vec<String>,
    /// Mass and inertia names.
    pub(crate) masses: Vec<String>,
}

impl UnitTable {
    /// The dimension of a coordinate, parameter, mass, inertia or definition; the time `t`
    /// is in s.
    pub fn dimension(&self, name: &str) -> Option<Dimension> {
        if name == crate::parse::keywords::TIME {
            return Some(Dimension::TIME);
        }
        self.dimensions.get(name).copied()
    }

    /// The unit of `name` as the `units` statement writes it, if it gives one.
    pub fn written(&self, name: &str) -> Option<&str> {
        self.written.get(name).map(String::as_str)
    }

    /// The unit of a registry quantity on the coordinate or mass `of` (`None` for a
    /// scalar), as the derivation text and the generated docs state it: a generalized
    /// force on a dimensionless coordinate is in N·m.
    ///
    /// ```
    /// use varmass_symbolic::{derive_source, mechanics::Parameters};
    /// use varmass_symbolic::quantity::Quantity;
    /// let source = "coordinates th; units th: rad, k: J, J0: kg*m^2; kinetic J0*th'^2/2; potential k*th^2";
    /// let table = derive_source(source, Parameters::Inferred).unwrap().units.unwrap();
    /// let unit = |q, of| table.quantity_unit(q, of);
    /// assert_eq!(unit(Quantity::ActiveForce, Some("th")).as_deref(), Some("N·m"));
    /// assert_eq!(unit(Quantity::Energy, None).as_deref(), Some("J"));
    /// assert_eq!(unit(Quantity::Accelerations, Some("th")).as_deref(), Some("1/s²"));
    /// ```
    pub fn quantity_unit(&self, quantity: Quantity, of: Option<&str>) -> Option<String> {
        let of = of.and_then(|name| self.dimensions.get(name).copied());
        let dimension = quantity.dimension(of)?;
        Some(dimension.unit(quantity.is_generalized_force()))
    }

    /// The dimension of a derived quantity a `check` may name, by its DSL name (see
    /// [`Quantity::parse`]): `H`, `L`, `T`, `V` are energies, `power` a power; for a
    /// coordinate q, `p_q` is energy·time / dim(q), `Q_q`, `R1_q`, `R2_q`, `dp_q`,
    /// `pdot_q` are energy / dim(q) and `q''` is dim(q)/s²; `mdot_m` is dim(m)/s.
    ///
    /// ```
    /// use varmass_symbolic::{derive_source, mechanics::Parameters};
    /// use varmass_symbolic::units::Dimension;
    /// let source = "coordinates th; units th: rad, k: N*m, J0: kg*m^2; kinetic J0*th'^2/2; potential k*th^2";
    /// let table = derive_source(source, Parameters::Inferred).unwrap().units.unwrap();
    /// assert_eq!(table.quantity("p_th").unwrap().to_string(), "kg·m²/s");
    /// assert_eq!(table.quantity("Q_th"), Some(Dimension::ENERGY));
    /// ```
    pub fn quantity(&self, name: &str) -> Option<Dimension> {
        let coordinates: Vec<&str> = self.coordinates.iter().map(String::as_str).collect();
        let masses: Vec<&str> = self.masses.iter().map(String::as_str).collect();
        let (quantity, index) = Quantity::parse(name, &coordinates, &masses)?;
        let of = match quantity.spec().name {
            Named::PerMass(_) => masses.get(index),
            Named::PerCoordinate { .. } => coordinates.get(index),
            Named::Scalar(_) | Named::Unnamed => None,
        };
        quantity.dimension(of.and_then(|name| self.dimensions.get(*name).copied()))
    }
}
