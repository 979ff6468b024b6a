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
        let mut sections = Vec::new();
        let mut masses = Vec::new();
        for i in 0..self.masses.len() {
            let (name, symbol, kind) = {
                let m = &self.masses[i];
                (m.name.clone(), m.symbol, m.kind.clone())
            };
            let symbol_id = self.pool.sym(symbol);
            let tex = self.pool.latex(symbol_id);
            match kind {
                MassKind::Law(law) => {
                    masses.push(Line {
                        text: format!("{name} ="),
                        latex: tex.clone(),
                        value: law,
                    });
                    masses.push(Line {
                        text: format!("d{name}/dt ="),
                        latex: format!("\\dot{{{tex}}}"),
                        value: self.mass_rates[i],
                    });
                }
                MassKind::State { .. } => masses.push(Line {
                    text: format!("d{name}/dt (state mass) ="),
                    latex: format!("\\dot{{{tex}}}"),
                    value: self.mass_rates[i],
                }),
            }
        }
        sections.push(Section {
            heading: "Masses (frozen under ∂*, d*/dt)",
            lines: masses,
        });
        sections.push(Section {
            heading: "Lagrangian L = T − V (eq. 7)",
            lines: vec![
                line("T =", "T =", self.kinetic),
                line("V =", "V =", self.potential),
                line("L =", "L =", self.lagrangian),
            ],
        });
        let coords: Vec<(String, String)> = self
            .coordinates
            .iter()
            .map(|c| (c.name.clone(), latex_name(&c.name)))
            .collect();
        let per_coordinate = |label: &str, latex: &str, values: &[Id]| -> Vec<Line> {
            coords
                .iter()
                .zip(values)
                .map(|((name, tex), value)| Line {
                    text: label.replace('#', name),
                    latex: latex.replace('#', tex),
                    value: *value,
                })
                .collect()
        };
        sections.push(Section {
            heading: "Generalized momenta p = ∂*L/∂q̇ (eq. 8)",
            lines: per_coordinate("p_# =", "p_{#} =", &self.momenta.clone()),
        });
        let mut hamilton = vec![line(
            "H = p·q̇ − L =",
            "H = p \\cdot \\dot q - L =",
            self.energy,
        )];
        if let Some(h) = self.hamiltonian {
            hamilton.push(line("H(q, p, t) =", "H(q, p, t) =", h));
        }
        sections.push(Section {
            heading: "Hamiltonian (eqs. 9–10)",
            lines: hamilton,
        });
        let mut forces = per_coordinate("Q*_# =", "Q^*_{#} =", &self.active_force.clone());
        forces.extend(per_coordinate(
            "R1_# =",
            "R_{1,#} =",
            &self.reactive_thrust.clone(),
        ));
        forces.extend(per_coordinate(
            "R2_# =",
            "R_{2,#} =",
            &self.impact_force.clone(),
        ));
        sections.push(Section {
            heading: "Generalized forces: active Q*, reactive thrust R1, impact R2",
            lines: forces,
        });
        let mut canonical = Vec::new();
        match self.velocities.clone() {
            VelocitySolve::Symbolic(v) => {
                canonical.extend(per_coordinate(
                    "#' = ∂*H/∂p_# =",
                    "\\dot{#} = \\frac{\\partial^* H}{\\partial p_{#}} =",
                    &v,
                ));
                let rates: Vec<Id> = self
                    .frozen_momentum_rate
                    .clone()
                    .into_iter()
                    .map(|e| self.in_hamilton_form(e).unwrap_or(e))
                    .collect();
                canonical.extend(per_coordinate(
                    "d*p_#/dt = −∂*H/∂# + Q*_# − R1_# + R2_# =",
                    "\\frac{d^* p_{#}}{dt} = -\\frac{\\partial^* H}{\\partial #} + Q^*_{#} - R_{1,#} + R_{2,#} =",
                    &rates,
                ));
            }
            VelocitySolve::Numeric => {
                canonical.extend(per_coordinate(
                    "d*p_#/dt = ∂*L/∂# + Q*_# − R1_# + R2_# (q̇ from M q̇ = p − b) =",
                    "\\frac{d^* p_{#}}{dt} = \\frac{\\partial^* L}{\\partial #} + Q^*_{#} - R_{1,#} + R_{2,#} =",
                    &self.frozen_momentum_rate.clone(),
                ));
            }
        }
        sections.push(Section {
            heading: "Canonical equations (eq. 14)",
            lines: canonical,
        });
        let mut rates = per_coordinate(
            "dp_#/dt = d*p_#/dt + Σ ṁ ∂*p_#/∂m =",
            "\\dot p_{#} = \\frac{d^* p_{#}}{dt} + \\sum_i \\dot m_i \\frac{\\partial^* p_{#}}{\\partial m_i} =",
            &self.momentum_rate.clone(),
        );
        if let Some(acc) = self.accelerations.clone() {
            rates.extend(per_coordinate("#'' =", "\\ddot{#} =", &acc));
        }
        rates.push(line("dH/dt =", "\\frac{dH}{dt} =", self.power));
        sections.push(Section {
            heading: "True rates, Lagrange form (eq. 6) and energy budget",
            lines: rates,
        });
        sections
    }

    /// The whole derivation as plain text. A system with `units` starts with the unit of
    /// every coordinate and parameter, and each line ends with its quantity's unit.
    pub fn to_text(&mut self) -> String {
        let sections = self.sections();
        let mut out = self.units_heading();
        for section in sections {
            let _ = writeln!(out, "{}", section.heading);
            for l in section.lines {
                let unit = self.line_unit(&l.text);
                let _ = writeln!(out, "    {} {}{unit}", l.text, self.pool.display(l.value));
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

    /// The whole derivation as LaTeX (`align*` environments, one per section).
    pub fn to_latex(&mut self) -> String {
        let sections = self.sections();
        let mut out = String::new();
        for section in sections {
            let _ = writeln!(out, "% {}\n\\begin{{align*}}", section.heading);
            let count = section.lines.len();
            for (i, l) in section.lines.into_iter().enumerate() {
                let end = if i + 1 < count { " \\\\" } else { "" };
                let label = l.latex.trim_end().trim_end_matches('=').trim_end();
                let _ = writeln!(out, "  {label} &= {}{end}", self.pool.latex(l.value));
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

fn latex_name(name: &str) -> String {
    name.to_string()
}
