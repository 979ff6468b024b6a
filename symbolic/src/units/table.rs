//! The units of a checked system: every declared or inferred name, and the derived
//! quantities (`H`, `p_x`, `Q_th`, …) whose dimensions follow from the coordinates'.

use super::dimension::Dimension;
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

    /// The unit of the quantity a line of the derivation text defines, from the line's
    /// label: `H`, `p_x`, `Q*_x`, `R1_x`, `d*p_x/dt`, `dp_x/dt`, `x'`, `x''`, `dH/dt`, a
    /// mass `m` or `dm/dt`. Generalized forces on a dimensionless coordinate are in N·m.
    ///
    /// ```
    /// use varmass_symbolic::parse::parse_system;
    /// use varmass_symbolic::units::check_units;
    /// let ast = parse_system("coordinates th; units th: rad, k: J; potential k*th^2").unwrap();
    /// let table = check_units(&ast).unwrap().unwrap();
    /// assert_eq!(table.label_unit("Q*_th").as_deref(), Some("N·m"));
    /// assert_eq!(table.label_unit("H(q,").as_deref(), Some("J"));
    /// assert_eq!(table.label_unit("th''").as_deref(), Some("1/s²"));
    /// ```
    pub fn label_unit(&self, label: &str) -> Option<String> {
        let label = label.split('(').next().unwrap_or(label);
        let generalized = ["Q*_", "R1_", "R2_", "d*p_", "dp_"];
        let torque = generalized.iter().any(|p| label.starts_with(p));
        let per_time = |name: &str, order: i128| {
            let q = self.dimensions.get(name)?;
            q.checked_div(Dimension::TIME.pow(crate::expr::Rational::integer(order))?)
        };
        let dimension = if let Some(rest) = label.strip_suffix("/dt") {
            let rest = rest.strip_prefix('d')?;
            match rest.strip_prefix("*p_") {
                Some(q) => self.quantity(&format!("dp_{q}")),
                None if rest == "H" => Some(Dimension::POWER),
                None => match rest.strip_prefix("p_") {
                    Some(q) => self.quantity(&format!("pdot_{q}")),
                    None => self.quantity(&format!("mdot_{rest}")),
                },
            }
        } else if let Some(q) = label.strip_suffix("''") {
            self.coordinates
                .iter()
                .any(|c| c == q)
                .then(|| per_time(q, 2))?
        } else if let Some(q) = label.strip_suffix('\'') {
            self.coordinates
                .iter()
                .any(|c| c == q)
                .then(|| per_time(q, 1))?
        } else if let Some(q) = label.strip_prefix("Q*_") {
            self.quantity(&format!("Q_{q}"))
        } else if self.masses.iter().any(|m| m == label) {
            self.dimensions.get(label).copied()
        } else {
            self.quantity(label)
        };
        // A generalized force in J is one on a dimensionless coordinate: a torque.
        Some(dimension?.unit(torque))
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
            return Dimension::ENERGY
                .checked_mul(Dimension::TIME)?
                .checked_div(q);
        }
        for prefix in ["Q_", "R1_", "R2_", "dp_", "pdot_"] {
            if let Some(q) = coordinate(prefix) {
                return Dimension::ENERGY.checked_div(q);
            }
        }
        let mass = name.strip_prefix("mdot_")?;
        self.masses.iter().any(|m| m == mass).then_some(())?;
        self.dimensions.get(mass)?.checked_div(Dimension::TIME)
    }
}
