//! The `[flight]` table of a scene file (docs/scenes.md#flight): which recordable expression
//! plays each role of a flight (altitude, vertical speed, speed, …), the defaults by the
//! names of the flights' conventions, and each role resolved in every phase's model.

use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;
use varmass::interpret::Program;
use varmass::symbolic::parse::ast::{BinOp, Expr, ExprNode, StatementKind, SystemAst};
use varmass::symbolic::parse::parse_expression;

use crate::args::{ModelArgs, Words};
use crate::error::CliError;
use crate::run::names::observables;
use crate::run::record::{recorded, Recorded, Scope};
use crate::scene::models::Models;

/// The `[flight]` table as written: each role an expression the scene can record.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlightTable {
    /// Height, m (above the launch site or sea level, as the model says).
    pub altitude: Option<Spanned<String>>,
    /// The altitude's rate; derived from the altitude when it is a coordinate (± constants).
    pub vertical_speed: Option<Spanned<String>>,
    /// |V| relative to the ground.
    pub speed: Option<Spanned<String>>,
    /// Mach number.
    pub mach: Option<Spanned<String>>,
    /// Dynamic pressure ½ρV², Pa.
    pub qbar: Option<Spanned<String>>,
    /// |acceleration| (a recorded `x''` is exact: no differencing).
    pub acceleration: Option<Spanned<String>>,
    /// Static margin, calibers.
    pub static_margin: Option<Spanned<String>>,
    /// Angle of attack, rad.
    pub alpha: Option<Spanned<String>>,
    /// Pitch angle (for the attitude panel).
    pub pitch: Option<Spanned<String>>,
    /// Heading angle (for the attitude panel).
    pub heading: Option<Spanned<String>>,
    /// Thrust: the burnout is the first time after which it stays ≤ 0.
    pub thrust: Option<Spanned<String>>,
    /// The landing point's east coordinate.
    pub east: Option<Spanned<String>>,
    /// The landing point's north coordinate.
    pub north: Option<Spanned<String>>,
    /// The burnout time, given instead of a thrust.
    pub burnout: Option<f64>,
    /// A measured flight log to compare with and overlay.
    pub log: Option<LogEntry>,
}

/// `log = { file = "…csv", time = "Time (s)", altitude = "Altitude (m)" }`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LogEntry {
    /// The CSV file, relative to the scene file.
    pub file: Spanned<PathBuf>,
    /// The header of its time column.
    #[serde(default = "default_time")]
    pub time: Spanned<String>,
    /// The header of its altitude column.
    #[serde(default = "default_altitude")]
    pub altitude: Spanned<String>,
}

fn default_time() -> Spanned<String> {
    Spanned::new(0..0, "Time (s)".to_string())
}

fn default_altitude() -> Spanned<String> {
    Spanned::new(0..0, "Altitude (m)".to_string())
}

/// The roles, in the order of the summary, the table and the plot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// `altitude`.
    Altitude,
    /// `vertical_speed`.
    VerticalSpeed,
    /// `speed`.
    Speed,
    /// `mach`.
    Mach,
    /// `qbar`.
    Qbar,
    /// `acceleration`.
    Acceleration,
    /// `static_margin`.
    StaticMargin,
    /// `alpha`.
    Alpha,
    /// `pitch`.
    Pitch,
    /// `heading`.
    Heading,
    /// `thrust`.
    Thrust,
    /// `east`.
    East,
    /// `north`.
    North,
}

/// Every role.
pub const ROLES: [Role; 13] = [
    Role::Altitude,
    Role::VerticalSpeed,
    Role::Speed,
    Role::Mach,
    Role::Qbar,
    Role::Acceleration,
    Role::StaticMargin,
    Role::Alpha,
    Role::Pitch,
    Role::Heading,
    Role::Thrust,
    Role::East,
    Role::North,
];

impl Role {
    /// The role's key in `[flight]`, its column in the flight table, and the name a model
    /// gives the quantity by the conventions (the default).
    pub fn key(self) -> &'static str {
        match self {
            Role::Altitude => "altitude",
            Role::VerticalSpeed => "vertical_speed",
            Role::Speed => "speed",
            Role::Mach => "mach",
            Role::Qbar => "qbar",
            Role::Acceleration => "acceleration",
            Role::StaticMargin => "static_margin",
            Role::Alpha => "alpha",
            Role::Pitch => "pitch",
            Role::Heading => "heading",
            Role::Thrust => "thrust",
            Role::East => "east",
            Role::North => "north",
        }
    }

    fn given(self, table: &FlightTable) -> Option<&Spanned<String>> {
        match self {
            Role::Altitude => table.altitude.as_ref(),
            Role::VerticalSpeed => table.vertical_speed.as_ref(),
            Role::Speed => table.speed.as_ref(),
            Role::Mach => table.mach.as_ref(),
            Role::Qbar => table.qbar.as_ref(),
            Role::Acceleration => table.acceleration.as_ref(),
            Role::StaticMargin => table.static_margin.as_ref(),
            Role::Alpha => table.alpha.as_ref(),
            Role::Pitch => table.pitch.as_ref(),
            Role::Heading => table.heading.as_ref(),
            Role::Thrust => table.thrust.as_ref(),
            Role::East => table.east.as_ref(),
            Role::North => table.north.as_ref(),
        }
    }
}

/// One phase's model as the roles are resolved in it.
pub struct PhaseScope<'a> {
    /// Its program (before it moves into the phase's system).
    pub program: &'a Program,
    /// Its tags.
    pub tags: &'a [String],
    /// Its parameter values.
    pub parameters: &'a [(String, f64)],
}

/// The roles a scene's flight has: each role's expression, and its value in each phase.
pub struct Roles {
    /// The roles present, with the expression of each as written (or defaulted).
    pub present: Vec<(Role, String)>,
    /// For each phase, the resolved expression of each present role, in that order.
    pub columns: Vec<Vec<(String, Recorded)>>,
}

impl Roles {
    /// The expression of `role`, if the flight has it.
    pub fn text(&self, role: Role) -> Option<&str> {
        self.present
            .iter()
            .find(|(r, _)| *r == role)
            .map(|(_, t)| t.as_str())
    }

    /// The index of `role`'s column in the flight table.
    pub fn index(&self, role: Role) -> Option<usize> {
        self.present.iter().position(|(r, _)| *r == role)
    }
}

/// Resolves the roles of `table` in each phase (`phases`, the first first) of the model
/// `model_file`; `at` locates a byte offset of the scene file. A role written but unknown
/// in a phase's model is an error at its line; a role left out takes its default where the
/// first phase's model has one (`altitude`, `speed`, … by name; the vertical speed from an
/// altitude that is a coordinate; speed, acceleration, east and north from the coordinates
/// of a vertical (`y`) or east-north-up (`x, y, z`) model).
pub fn resolve(
    table: &Spanned<FlightTable>,
    phases: &[PhaseScope<'_>],
    model_file: &Path,
    models: &mut Models,
    at: &dyn Fn(usize) -> String,
) -> Result<Roles, CliError> {
    let selected = selected_of(phases, model_file, models)?;
    let first = (&phases[0], &selected[0]);
    let mut present: Vec<(Role, String, usize)> = Vec::new();
    for role in ROLES {
        let text = match role.given(table.get_ref()) {
            Some(given) => Some((given.get_ref().trim().to_string(), given.span().start)),
            None => default(role, &present, first).map(|t| (t, table.span().start)),
        };
        if let Some((text, offset)) = text {
            present.push((role, text, offset));
        }
    }
    if !present.iter().any(|(r, _, _)| *r == Role::Altitude) {
        return Err(CliError::Input(format!(
            "{}: `[flight]` needs `altitude = \"EXPRESSION\"`: the model has no quantity \
             `altitude` (docs/scenes.md#flight)",
            at(table.span().start)
        )));
    }
    if !present.iter().any(|(r, _, _)| *r == Role::VerticalSpeed) {
        return Err(CliError::Input(format!(
            "{}: `[flight]` needs `vertical_speed = \"EXPRESSION\"`: the altitude `{}` is not a \
             coordinate (plus constants) whose rate could be read",
            at(table.span().start),
            present[0].1
        )));
    }
    let mut columns = Vec::with_capacity(phases.len());
    for (k, (phase, ast)) in phases.iter().zip(&selected).enumerate() {
        let mut resolved = Vec::with_capacity(present.len());
        for (role, text, offset) in &present {
            let column = in_phase((phase, ast), text).map_err(|message| {
                CliError::Input(format!(
                    "{} (phase {}): `[flight]` `{} = \"{text}\"`: {message}",
                    at(*offset),
                    k + 1,
                    role.key()
                ))
            })?;
            resolved.push((role.key().to_string(), column));
        }
        columns.push(resolved);
    }
    let present = present.into_iter().map(|(r, t, _)| (r, t)).collect();
    Ok(Roles { present, columns })
}

/// The selected statements of each phase's model (its tags), for its `let`s.
fn selected_of(
    phases: &[PhaseScope<'_>],
    model_file: &Path,
    models: &mut Models,
) -> Result<Vec<SystemAst>, CliError> {
    phases
        .iter()
        .map(|phase| {
            let args = ModelArgs {
                file: model_file.to_path_buf(),
                with: phase.tags.to_vec(),
            };
            models.load(&args).map(|m| m.selected)
        })
        .collect()
}

/// `text` resolved in one phase's model, or the reason it cannot be.
fn in_phase((phase, ast): (&PhaseScope<'_>, &SystemAst), text: &str) -> Result<Recorded, String> {
    let known = observables(phase.program);
    let scope = Scope::new(phase.program, ast, &known, phase.parameters);
    match recorded(text, &scope, Words::Scene) {
        Ok((_, column)) => Ok(column),
        Err(CliError::Input(message)) => {
            // `recorded` names the scene's `record` key; here it is the role's.
            let prefix = format!("`record` `{text}`: ");
            Err(message
                .strip_prefix(&prefix)
                .unwrap_or(&message)
                .to_string())
        }
        Err(other) => Err(other.to_string()),
    }
}

/// The default expression of `role` in the first phase's model, given the roles before it.
fn default(
    role: Role,
    present: &[(Role, String, usize)],
    (phase, ast): (&PhaseScope<'_>, &SystemAst),
) -> Option<String> {
    let has = |text: &str| in_phase((phase, ast), text).is_ok();
    let altitude = present.iter().find(|(r, _, _)| *r == Role::Altitude);
    let vertical = altitude.and_then(|(_, text, _)| rate_of(text, phase.program, ast));
    let position = vertical.as_deref().and_then(|c| position(c, phase.program));
    let named = role.key();
    match role {
        Role::VerticalSpeed => vertical.map(|c| format!("{c}'")),
        _ if has(named) => Some(named.to_string()),
        Role::Speed => position.map(|p| norm(&p, "'")),
        Role::Acceleration => position.map(|p| norm(&p, "''")),
        Role::East | Role::North => {
            let p = position.filter(|p| p.len() == 3)?;
            Some(p[usize::from(role == Role::North)].clone())
        }
        _ => None,
    }
}

/// |d^k r/dt^k| of the position coordinates `p` (`primes` the order): `abs(y')` for one.
fn norm(p: &[String], primes: &str) -> String {
    match p {
        [one] => format!("abs({one}{primes})"),
        _ => {
            let squares: Vec<String> = p.iter().map(|c| format!("{c}{primes}^2")).collect();
            format!("sqrt({})", squares.join(" + "))
        }
    }
}

/// The position coordinates when the vertical one is `vertical`: itself in a model of one
/// coordinate, `x, y, z` when it is `z` of a model with `x` and `y` (east-north-up).
fn position(vertical: &str, program: &Program) -> Option<Vec<String>> {
    let coordinates: Vec<&str> = program.coordinate_names().collect();
    if coordinates.len() == 1 {
        return Some(vec![vertical.to_string()]);
    }
    let enu = vertical == "z" && coordinates.contains(&"x") && coordinates.contains(&"y");
    enu.then(|| ["x", "y", "z"].map(str::to_string).to_vec())
}

/// The coordinate whose velocity is the rate of the altitude `text`: a coordinate, a `let`
/// of one, or either plus or minus constants (numbers, parameters).
fn rate_of(text: &str, program: &Program, ast: &SystemAst) -> Option<String> {
    let node = parse_expression(text).ok()?;
    rate_of_node(&node, program, ast, 0)
}

fn rate_of_node(node: &ExprNode, program: &Program, ast: &SystemAst, depth: u8) -> Option<String> {
    if depth > 16 {
        return None;
    }
    match &*node.node {
        Expr::Name(name) if program.coordinate_names().any(|c| c == name) => Some(name.clone()),
        Expr::Name(name) => {
            let definition = ast.statements.iter().find_map(|s| match &s.kind {
                StatementKind::Let { name: n, value } if n.node == *name => Some(value),
                _ => None,
            })?;
            rate_of_node(definition, program, ast, depth + 1)
        }
        Expr::Binary {
            op: BinOp::Add | BinOp::Sub,
            lhs,
            rhs,
        } => match (constant(lhs, program, ast), constant(rhs, program, ast)) {
            (true, false) => rate_of_node(rhs, program, ast, depth + 1),
            (false, true) => rate_of_node(lhs, program, ast, depth + 1),
            _ => None,
        },
        _ => None,
    }
}

/// Whether `node` is a number or a parameter (constant in time).
fn constant(node: &ExprNode, program: &Program, ast: &SystemAst) -> bool {
    match &*node.node {
        Expr::Number(_) => true,
        Expr::Name(name) => {
            let is_let = ast
                .statements
                .iter()
                .any(|s| matches!(&s.kind, StatementKind::Let { name: n, .. } if n.node == *name));
            !is_let
                && name != "t"
                && program.coordinate_names().all(|c| c != name)
                && program.mass_names().all(|m| m != name)
        }
        _ => false,
    }
}

/// The model file of the scene read from `path`.
pub fn model_file(path: &Path, model: &Path) -> PathBuf {
    path.parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
        .join(model)
}
