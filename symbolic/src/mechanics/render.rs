//! The derivation as a readable report, in text and in LaTeX, in the paper's order:
//! L, p, H, forces, canonical equations, true rates.

use std::collections::HashMap;
use std::fmt::Write;

use super::derivation::{Derivation, VelocitySolve};
use super::model::MassKind;
use crate::dimension::Dimension;
use crate::expr::{Id, Identity, Symbol};
use crate::quantity::{Named, Quantity};

/// One line of the report: a label (text, LaTeX), an expression and what it is (for its
/// unit).
struct Line {
    text: String,
    latex: String,
    value: Id,
    of: Of,
}

/// What a line's value is, which decides its unit.
#[derive(Clone, Copy)]
pub(crate) enum Of {
    /// Entry `index` (a coordinate or a mass, none for a scalar) of a registry quantity.
    Quantity(Quantity, usize),
    /// Mass `index`.
    Mass(usize),
    /// q̇ of coordinate `index`.
    Velocity(usize),
}

/// One section: a heading and its lines.
struct Section {
    heading: &'static str,
    lines: Vec<Line>,
}

impl Derivation {
    /// The expressions of the canonical equations in Hamilton form (q, p), when q̇ is solved
    /// symbolically: velocity-form expressions with q̇ = q̇(q, p) substituted.
    pub fn in_hamilton_form(&mut self, e: Id) -> Option<Id> {
        let VelocitySolve::Symbolic(v) = &self.velocities else {
            return None;
        };
        let map: HashMap<Symbol, Id> = self
            .coordinates
            .iter()
            .zip(v)
            .map(|(c, v)| (c.velocity, *v))
            .collect();
        Some(self.pool.substitute(e, &map))
    }

    fn sections(&mut self) -> Vec<Section> {
        vec![
            self.masses_section(),
            Section {
                heading: "Lagrangian L = T − V (eq. 7)",
                lines: [Quantity::Kinetic, Quantity::Potential, Quantity::Lagrangian]
                    .into_iter()
                    .flat_map(|q| self.per_coordinate(q, "{} =", "{} ="))
                    .collect(),
            },
            Section {
                heading: "Generalized momenta p = ∂*L/∂q̇ (eq. 8)",
                lines: self.per_coordinate(Quantity::Momenta, "{} =", "{} ="),
            },
            self.hamiltonian_section(),
            self.forces_section(),
            self.canonical_section(),
            self.rates_section(),
        ]
    }

    /// Each mass law with its rate, or the rate of a state mass.
    fn masses_section(&mut self) -> Section {
        let mut lines = Vec::new();
        let rate_of = |i| Of::Quantity(Quantity::MassRates, i);
        for (i, (mass, rate)) in self.masses.iter().zip(&self.mass_rates).enumerate() {
            let symbol_id = self.pool.sym(mass.symbol);
            let tex = self.pool.latex(symbol_id);
            let name = &mass.name;
            match mass.kind {
                MassKind::Law(law) => {
                    lines.push(Line {
                        text: format!("{name} ="),
                        latex: tex.clone(),
                        value: law,
                        of: Of::Mass(i),
                    });
                    lines.push(Line {
                        text: format!("d{name}/dt ="),
                        latex: format!("\\dot{{{tex}}}"),
                        value: *rate,
                        of: rate_of(i),
                    });
                }
                MassKind::State { .. } => lines.push(Line {
                    text: format!("d{name}/dt (state mass) ="),
                    latex: format!("\\dot{{{tex}}}"),
                    value: *rate,
                    of: rate_of(i),
                }),
            }
        }
        Section {
            heading: "Masses (frozen under ∂*, d*/dt)",
            lines,
        }
    }

    /// One line per value of `quantity` (one per coordinate, or one for a scalar), its
    /// registry label put in place of `{}` in `text` and `latex`.
    fn per_coordinate(&self, quantity: Quantity, text: &str, latex: &str) -> Vec<Line> {
        let values = self.quantity(quantity);
        self.lines_of(quantity, &values, text, latex)
    }

    /// [`Self::per_coordinate`] with other values standing for `quantity` (its Hamilton
    /// form): `#` in `text` and `latex` is the coordinate's name.
    fn lines_of(&self, quantity: Quantity, values: &[Id], text: &str, latex: &str) -> Vec<Line> {
        let names: Vec<&str> = if is_scalar(quantity) {
            vec![""]
        } else {
            self.coordinates.iter().map(|c| c.name.as_str()).collect()
        };
        names
            .iter()
            .zip(values)
            .enumerate()
            .map(|(a, (name, value))| Line {
                text: text
                    .replace("{}", &quantity.text_label(name))
                    .replace('#', name),
                latex: latex
                    .replace("{}", &quantity.latex_label(name))
                    .replace('#', name),
                value: *value,
                of: Of::Quantity(quantity, a),
            })
            .collect()
    }

    fn hamiltonian_section(&self) -> Section {
        let mut lines = self.per_coordinate(
            Quantity::Energy,
            "{} = p·q̇ − L =",
            "{} = p \\cdot \\dot q - L =",
        );
        if let Some(h) = self.hamiltonian {
            lines.extend(self.lines_of(Quantity::Energy, &[h], "{}(q, p, t) =", "{}(q, p, t) ="));
        }
        Section {
            heading: "Hamiltonian (eqs. 9–10)",
            lines,
        }
    }

    fn forces_section(&self) -> Section {
        let forces = [
            Quantity::ActiveForce,
            Quantity::ReactiveThrust,
            Quantity::ImpactForce,
        ];
        let lines = forces
            .into_iter()
            .flat_map(|q| self.per_coordinate(q, "{} =", "{} ="))
            .collect();
        Section {
            heading: "Generalized forces: active Q*, reactive thrust R1, impact R2",
            lines,
        }
    }

    /// Eq. 14 in Hamilton form when q̇(q, p) is symbolic, else with q̇ from M q̇ = p − b.
    fn canonical_section(&mut self) -> Section {
        let lines = match self.velocities.clone() {
            VelocitySolve::Symbolic(v) => {
                let mut lines = self.velocity_lines(
                    &v,
                    "#' = ∂*H/∂p_# =",
                    "\\dot{#} = \\frac{\\partial^* H}{\\partial p_{#}} =",
                );
                let rates: Vec<Id> = self
                    .frozen_momentum_rate
                    .clone()
                    .into_iter()
                    .map(|e| self.in_hamilton_form(e).unwrap_or(e))
                    .collect();
                lines.extend(self.lines_of(
                    Quantity::FrozenMomentumRate,
                    &rates,
                    "{} = −∂*H/∂# + Q*_# − R1_# + R2_# =",
                    "{} = -\\frac{\\partial^* H}{\\partial #} + Q^*_{#} - R_{1,#} + R_{2,#} =",
                ));
                lines
            }
            VelocitySolve::Numeric => self.per_coordinate(
                Quantity::FrozenMomentumRate,
                "{} = ∂*L/∂# + Q*_# − R1_# + R2_# (q̇ from M q̇ = p − b) =",
                "{} = \\frac{\\partial^* L}{\\partial #} + Q^*_{#} - R_{1,#} + R_{2,#} =",
            ),
        };
        Section {
            heading: "Canonical equations (eq. 14)",
            lines,
        }
    }

    fn rates_section(&self) -> Section {
        let mut lines = self.per_coordinate(
            Quantity::MomentumRate,
            "{} = d*p_#/dt + Σ ṁ ∂*p_#/∂m =",
            "{} = \\frac{d^* p_{#}}{dt} + \\sum_i \\dot m_i \\frac{\\partial^* p_{#}}{\\partial m_i} =",
        );
        lines.extend(self.per_coordinate(Quantity::Accelerations, "{} =", "{} ="));
        lines.extend(self.per_coordinate(Quantity::Power, "{} =", "{} ="));
        Section {
            heading: "True rates, Lagrange form (eq. 6) and energy budget",
            lines,
        }
    }

    /// The whole derivation as plain text. A system with `units` starts with the unit of
    /// every coordinate and parameter, and each line ends with its quantity's unit.
    pub fn to_text(&mut self) -> String {
        let sections = self.sections();
        let values = self.pool.display_all(&Self::values(&sections));
        self.text_of(&sections, values)
    }

    /// The whole derivation as LaTeX (`align*` environments, one per section).
    pub fn to_latex(&mut self) -> String {
        let sections = self.sections();
        self.latex_of(&sections)
    }

    /// [`to_text`](Self::to_text) and [`to_latex`](Self::to_latex) at once: the sections
    /// (with their substitutions into Hamilton form) are built once for both.
    pub fn to_text_and_latex(&mut self) -> (String, String) {
        let (text, latex, _) = self.to_text_and_latex_showing(&[]);
        (text, latex)
    }

    /// [`to_text_and_latex`](Self::to_text_and_latex), and the DSL text of each of `shown`
    /// (the emitted doc comments) from the same printing walk: the doc comments show the
    /// quantities the derivation text shows, so printing them apart would print every
    /// shared subexpression twice.
    pub fn to_text_and_latex_showing(&mut self, shown: &[Id]) -> (String, String, Vec<String>) {
        let sections = self.sections();
        let mut roots = Self::values(&sections);
        let line_count = roots.len();
        roots.extend(shown);
        let mut printed = self.pool.display_all(&roots);
        let shown_texts = printed.split_off(line_count);
        let text = self.text_of(&sections, printed);
        (text, self.latex_of(&sections), shown_texts)
    }

    /// The values of every line, in order.
    fn values(sections: &[Section]) -> Vec<Id> {
        let lines = sections.iter().flat_map(|s| &s.lines);
        lines.map(|l| l.value).collect()
    }

    /// The text of `sections`, given the printed value of each line in order (printed in
    /// one walk, [`ExprPool::display_all`]: the lines share most of their subexpressions).
    fn text_of(&self, sections: &[Section], values: Vec<String>) -> String {
        let mut values = values.into_iter();
        let mut out = self.units_heading();
        for section in sections {
            let _ = writeln!(out, "{}", section.heading);
            for (l, value) in section.lines.iter().zip(values.by_ref()) {
                let unit = self.unit_suffix(l.of);
                let _ = writeln!(out, "    {} {value}{unit}", l.text);
            }
        }
        if !self.checks.is_empty() {
            let _ = writeln!(out, "Checks");
            for c in &self.checks {
                let how = match &c.verdict {
                    Identity::Proven => "proven: the difference reduces to 0".to_string(),
                    Identity::Numerical { points } => format!("holds at {points} random points"),
                    other => format!("{other:?}"),
                };
                let _ = writeln!(out, "    {}   [{how}]", c.text);
            }
        }
        out
    }

    fn latex_of(&self, sections: &[Section]) -> String {
        let mut values = self.pool.latex_all(&Self::values(sections)).into_iter();
        let mut out = String::new();
        for section in sections {
            let _ = writeln!(out, "% {}\n\\begin{{align*}}", section.heading);
            let count = section.lines.len();
            for (i, (l, value)) in section.lines.iter().zip(values.by_ref()).enumerate() {
                let end = if i + 1 < count { " \\\\" } else { "" };
                let label = l.latex.trim_end().trim_end_matches('=').trim_end();
                let _ = writeln!(out, "  {label} &= {value}{end}");
            }
            let _ = writeln!(out, "\\end{{align*}}");
        }
        out
    }
}

impl Derivation {
    /// `Units` and `x in m, theta in rad, …`, or nothing for a system without units.
    fn units_heading(&self) -> String {
        match self.units_line() {
            Some(line) => format!("Units (rad is dimensionless)\n    {line}\n"),
            None => String::new(),
        }
    }

    /// `x in m, theta in rad, …`: the unit of every coordinate, then every parameter, as
    /// `units` writes it; `None` for a system without units.
    pub(crate) fn units_line(&self) -> Option<String> {
        let units = self.units.as_ref()?;
        let names = self.coordinates.iter().map(|c| c.name.as_str());
        let names = names.chain(self.parameters.iter().map(|(name, _)| name.as_str()));
        let stated: Vec<String> = names
            .filter_map(|name| {
                let unit = units
                    .written(name)
                    .map(str::to_string)
                    .or_else(|| units.dimension(name).map(|d| d.to_string()))?;
                Some(format!("{name} in {unit}"))
            })
            .collect();
        Some(stated.join(", "))
    }

    /// `   [J]` after a line of the derivation text or a doc comment whose value has a
    /// known unit; empty without units. An unnamed intermediate of the registry (∂*L/∂q,
    /// the mass-flux force, the right side of eq. 6) is shown without one: the DSL has no
    /// name for it that a unit could be stated against.
    pub(crate) fn unit_suffix(&self, of: Of) -> String {
        let Some(units) = self.units.as_ref() else {
            return String::new();
        };
        let unit = match of {
            Of::Quantity(q, _) if q.spec().name == Named::Unnamed => None,
            Of::Quantity(q, i) => {
                let name = match q.spec().name {
                    Named::PerMass(_) => self.masses.get(i).map(|m| m.name.as_str()),
                    Named::Scalar(_) => None,
                    _ => self.coordinates.get(i).map(|c| c.name.as_str()),
                };
                units.quantity_unit(q, name)
            }
            Of::Mass(i) => self
                .masses
                .get(i)
                .and_then(|m| units.dimension(&m.name))
                .map(|d| d.unit(false)),
            Of::Velocity(a) => {
                let name = self.coordinates.get(a).map(|c| c.name.as_str());
                let q = name.and_then(|n| units.dimension(n));
                q.and_then(|q| q.checked_div(Dimension::TIME))
                    .map(|d| d.unit(false))
            }
        };
        unit.map_or(String::new(), |unit| format!("   [{unit}]"))
    }

    /// One line per coordinate for q̇ in closed form.
    fn velocity_lines(&self, values: &[Id], text: &str, latex: &str) -> Vec<Line> {
        self.coordinates
            .iter()
            .zip(values)
            .enumerate()
            .map(|(a, (c, value))| Line {
                text: text.replace('#', &c.name),
                latex: latex.replace('#', &c.name),
                value: *value,
                of: Of::Velocity(a),
            })
            .collect()
    }
}

/// Whether `quantity` has one value (H, L, power), not one per coordinate.
fn is_scalar(quantity: Quantity) -> bool {
    matches!(quantity.spec().name, Named::Scalar(_))
}
