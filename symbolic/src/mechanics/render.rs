//! The derivation as a readable report, in text and in LaTeX, in the paper's order:
//! L, p, H, forces, canonical equations, true rates.

use std::collections::HashMap;
use std::fmt::Write;

use super::derivation::{Derivation, VelocitySolve};
use super::model::MassKind;
use crate::expr::{Id, Identity, Symbol};

/// One line of the report: a label (text, LaTeX) and an expression.
struct Line {
    text: String,
    latex: String,
    value: Id,
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
                lines: vec![
                    line("T =", "T =", self.kinetic),
                    line("V =", "V =", self.potential),
                    line("L =", "L =", self.lagrangian),
                ],
            },
            Section {
                heading: "Generalized momenta p = ∂*L/∂q̇ (eq. 8)",
                lines: self.per_coordinate("p_# =", "p_{#} =", &self.momenta),
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
        for (mass, rate) in self.masses.iter().zip(&self.mass_rates) {
            let symbol_id = self.pool.sym(mass.symbol);
            let tex = self.pool.latex(symbol_id);
            let name = &mass.name;
            match mass.kind {
                MassKind::Law(law) => {
                    lines.push(Line {
                        text: format!("{name} ="),
                        latex: tex.clone(),
                        value: law,
                    });
                    lines.push(Line {
                        text: format!("d{name}/dt ="),
                        latex: format!("\\dot{{{tex}}}"),
                        value: *rate,
                    });
                }
                MassKind::State { .. } => lines.push(Line {
                    text: format!("d{name}/dt (state mass) ="),
                    latex: format!("\\dot{{{tex}}}"),
                    value: *rate,
                }),
            }
        }
        Section {
            heading: "Masses (frozen under ∂*, d*/dt)",
            lines,
        }
    }

    /// One line per coordinate: `#` in the labels stands for the coordinate's name, which
    /// both labels spell as declared.
    fn per_coordinate(&self, label: &str, latex: &str, values: &[Id]) -> Vec<Line> {
        self.coordinates
            .iter()
            .zip(values)
            .map(|(c, value)| Line {
                text: label.replace('#', &c.name),
                latex: latex.replace('#', &c.name),
                value: *value,
            })
            .collect()
    }

    fn hamiltonian_section(&self) -> Section {
        let mut lines = vec![line(
            "H = p·q̇ − L =",
            "H = p \\cdot \\dot q - L =",
            self.energy,
        )];
        if let Some(h) = self.hamiltonian {
            lines.push(line("H(q, p, t) =", "H(q, p, t) =", h));
        }
        Section {
            heading: "Hamiltonian (eqs. 9–10)",
            lines,
        }
    }

    fn forces_section(&self) -> Section {
        let mut lines = self.per_coordinate("Q*_# =", "Q^*_{#} =", &self.active_force);
        lines.extend(self.per_coordinate("R1_# =", "R_{1,#} =", &self.reactive_thrust));
        lines.extend(self.per_coordinate("R2_# =", "R_{2,#} =", &self.impact_force));
        Section {
            heading: "Generalized forces: active Q*, reactive thrust R1, impact R2",
            lines,
        }
    }

    /// Eq. 14 in Hamilton form when q̇(q, p) is symbolic, else with q̇ from M q̇ = p − b.
    fn canonical_section(&mut self) -> Section {
        let lines = match self.velocities.clone() {
            VelocitySolve::Symbolic(v) => {
                let mut lines = self.per_coordinate(
                    "#' = ∂*H/∂p_# =",
                    "\\dot{#} = \\frac{\\partial^* H}{\\partial p_{#}} =",
                    &v,
                );
                let rates: Vec<Id> = self
                    .frozen_momentum_rate
                    .clone()
                    .into_iter()
                    .map(|e| self.in_hamilton_form(e).unwrap_or(e))
                    .collect();
                lines.extend(self.per_coordinate(
                    "d*p_#/dt = −∂*H/∂# + Q*_# − R1_# + R2_# =",
                    "\\frac{d^* p_{#}}{dt} = -\\frac{\\partial^* H}{\\partial #} + Q^*_{#} - R_{1,#} + R_{2,#} =",
                    &rates,
                ));
                lines
            }
            VelocitySolve::Numeric => self.per_coordinate(
                "d*p_#/dt = ∂*L/∂# + Q*_# − R1_# + R2_# (q̇ from M q̇ = p − b) =",
                "\\frac{d^* p_{#}}{dt} = \\frac{\\partial^* L}{\\partial #} + Q^*_{#} - R_{1,#} + R_{2,#} =",
                &self.frozen_momentum_rate,
            ),
        };
        Section {
            heading: "Canonical equations (eq. 14)",
            lines,
        }
    }

    fn rates_section(&self) -> Section {
        let mut lines = self.per_coordinate(
            "dp_#/dt = d*p_#/dt + Σ ṁ ∂*p_#/∂m =",
            "\\dot p_{#} = \\frac{d^* p_{#}}{dt} + \\sum_i \\dot m_i \\frac{\\partial^* p_{#}}{\\partial m_i} =",
            &self.momentum_rate,
        );
        if let Some(acc) = &self.accelerations {
            lines.extend(self.per_coordinate("#'' =", "\\ddot{#} =", acc));
        }
        lines.push(line("dH/dt =", "\\frac{dH}{dt} =", self.power));
        Section {
            heading: "True rates, Lagrange form (eq. 6) and energy budget",
            lines,
        }
    }

    /// The whole derivation as plain text. A system with `units` starts with the unit of
    /// every coordinate and parameter, and each line ends with its quantity's unit.
    pub fn to_text(&mut self) -> String {
        let sections = self.sections();
        self.text_of(&sections)
    }

    /// The whole derivation as LaTeX (`align*` environments, one per section).
    pub fn to_latex(&mut self) -> String {
        let sections = self.sections();
        self.latex_of(&sections)
    }

    /// [`to_text`](Self::to_text) and [`to_latex`](Self::to_latex) at once: the sections
    /// (with their substitutions into Hamilton form) are built once for both.
    pub fn to_text_and_latex(&mut self) -> (String, String) {
        let sections = self.sections();
        (self.text_of(&sections), self.latex_of(&sections))
    }

    /// The values of every line, in order.
    fn values(sections: &[Section]) -> Vec<Id> {
        let lines = sections.iter().flat_map(|s| &s.lines);
        lines.map(|l| l.value).collect()
    }

    fn text_of(&self, sections: &[Section]) -> String {
        // One printing walk for every line: the lines share most of their subexpressions.
        let mut values = self.pool.display_all(&Self::values(sections)).into_iter();
        let mut out = self.units_heading();
        for section in sections {
            let _ = writeln!(out, "{}", section.heading);
            for (l, value) in section.lines.iter().zip(values.by_ref()) {
                let unit = self.line_unit(&l.text);
                let _ = writeln!(out, "    {} {value}{unit}", l.text);
            }
        }
        if !self.checks.is_empty() {
            let _ = writeln!(out, "Checks");
            for c in &self.checks {
                let how = match &c.verdict {
                    Identity::Proven => "proven: same canonical form".to_string(),
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

    /// `   [J]` after a line whose label (`H = …`, `p_x =`, `Q*_th =`) names a quantity
    /// with a known unit; empty without units.
    pub(crate) fn line_unit(&self, label: &str) -> String {
        let first = label.split([' ', '=']).next().unwrap_or("");
        self.units
            .as_ref()
            .and_then(|units| units.label_unit(first))
            .map_or(String::new(), |unit| format!("   [{unit}]"))
    }
}

fn line(text: &str, latex: &str, value: Id) -> Line {
    Line {
        text: text.to_string(),
        latex: latex.to_string(),
        value,
    }
}
