//! The units of a checked system: every declared or inferred name, and the derived
//! quantities (`H`, `p_x`, `Q_th`, …) whose dimensions follow from the coordinates'.

use super::dimension::Dimension;
use std::collections::HashMap;

/// What a system with a `units` statement says about dimensions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct UnitTable {
    /// Coordinates, parameters, masses, inertias and definitions with their dimensions.
    pub(crate) dimensions: HashMap<String, Dimension>,
    /// The unit as the `units` statement writes it (`N/m`, `rad`).
    pub(crate) written: HashMap<String, String>,
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

    /// The dimension of a derived quantity a `check` may name: `H`, `L`, `T`, `V` are
    /// energies, `power` a power; for a coordinate q, `p_q` is energy·time / dim(q) and
    /// `Q_q`, `R1_q`, `R2_q`, `dp_q`, `pdot_q` are energy / dim(q); `mdot_m` is dim(m)/s.
    ///
    /// ```
    /// use varmass_symbolic::parse::parse_system;
    /// use varmass_symbolic::units::{check_units, Dimension};
    /// let ast = parse_system("coordinates th; units th: rad, k: N*m; potential k*th^2").unwrap();
    /// let table = check_units(&ast).unwrap().unwrap();
    /// assert_eq!(table.quantity("p_th").unwrap().to_string(), "kg·m²/s");
    /// assert_eq!(table.quantity("Q_th"), Some(Dimension::ENERGY));
    /// ```
    pub fn quantity(&self, name: &str) -> Option<Dimension> {
        match name {
            "H" | "L" | "T" | "V" => return Some(Dimension::ENERGY),
            "power" => return Some(Dimension::POWER),
            _ => {}
        }
        let coordinate = |prefix: &str| {
            let q = name.strip_prefix(prefix)?;
            self.coordinates.iter().any(|c| c == q).then_some(q)?;
            self.dimensions.get(q).copied()
        };
        if let Some(q) = coordinate("p_") {
            return Dimension::ENERGY.mul(Dimension::TIME)?.div(q);
        }
        for prefix in ["Q_", "R1_", "R2_", "dp_", "pdot_"] {
            if let Some(q) = coordinate(prefix) {
                return Dimension::ENERGY.div(q);
            }
        }
        let mass = name.strip_prefix("mdot_")?;
        self.masses.iter().any(|m| m == mass).then_some(())?;
        self.dimensions.get(mass)?.div(Dimension::TIME)
    }
}
