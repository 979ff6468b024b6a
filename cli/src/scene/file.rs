//! The scene file as written: TOML read by serde's derive into [`SceneFile`], every table
//! `deny_unknown_fields` so that a misspelt key is an error at its line, not a silently
//! ignored setting. Names the model must resolve (parameters, quantities, tags) are kept
//! with their spans ([`Spanned`]) so that a later check points at them too.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Deserializer};
use toml::Spanned;

use crate::args::Method;
use crate::error::CliError;

/// A scene: the model, its first phase (tags, parameters, initial state) and the phases
/// that follow, the run's settings, and what to record and where.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// The model file, relative to the scene file.
    pub model: Spanned<PathBuf>,
    /// The tags of the first phase (`--with`).
    #[serde(default)]
    pub with: Vec<Spanned<String>>,
    /// The parameter values of the first phase (`--set`).
    #[serde(default)]
    pub set: BTreeMap<Spanned<String>, f64>,
    /// A law for each `input` of the model (`--input`'s syntax: an expression of the
    /// input's arguments and the parameters, or a `.csv`/`.eng` file relative to the scene
    /// file), in force in every phase.
    #[serde(default)]
    pub input: BTreeMap<Spanned<String>, String>,
    /// The initial state (`--init`): coordinates, velocities `x'` (0 if unset), state masses.
    #[serde(default)]
    pub init: BTreeMap<Spanned<String>, f64>,
    /// The coordinate that starts resting on its support (a pad, a rail's end) and is held
    /// there until the net force along it lifts the body (docs/scenes.md).
    pub support: Option<Spanned<String>>,
    /// A launch rail the body starts on (docs/scenes.md#a-launch-rail).
    pub rail: Option<Spanned<RailEntry>>,
    /// The start time.
    #[serde(default)]
    pub from: f64,
    /// The end time.
    pub until: f64,
    /// A condition ending the last phase before `until` (`--stop-when` syntax).
    pub stop_when: Option<Spanned<String>>,
    /// The stepper (`--method` names).
    #[serde(default)]
    pub method: MethodName,
    /// The adaptive tolerance (`--tol`).
    pub tol: Option<f64>,
    /// A fixed step (`--step`).
    pub step: Option<f64>,
    /// The most steps each phase may take (`--max-steps`).
    pub max_steps: Option<u64>,
    /// The recorded quantities (`--record` entries), besides `phase`.
    #[serde(default)]
    pub record: Vec<Spanned<String>>,
    /// The CSV to write, relative to the scene file.
    pub csv: Option<PathBuf>,
    /// The phases after the first, in order.
    #[serde(default, rename = "phase")]
    pub phases: Vec<PhaseEntry>,
    /// The roles of the model's quantities in a flight, for its summary and plots
    /// (docs/scenes.md#flight).
    pub flight: Option<Spanned<super::flight::FlightTable>>,
}

/// A phase after the first: when it begins and what changes there.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PhaseEntry {
    /// The condition, watched during the phase before, whose crossing begins this one
    /// (`--stop-when` syntax; `t = 50` for a time).
    pub when: Spanned<String>,
    /// How the state enters the phase.
    #[serde(default)]
    pub carry: CarryRule,
    /// Parameter values changed here (the others carry over): numbers, or expressions of
    /// the change's time `t` evaluated at the change ([`SetValue`]).
    #[serde(default)]
    pub set: BTreeMap<Spanned<String>, SetValue>,
    /// State masses set here (a stage dropped).
    #[serde(default)]
    pub masses: BTreeMap<Spanned<String>, f64>,
    /// Other tags from here on (the same coordinates and state masses).
    pub with: Option<Spanned<Vec<Spanned<String>>>>,
}

/// `[rail]`: the position coordinates of the body's reference point (world axes x east,
/// y north, z up), the rail's inclination above the horizontal and heading clockwise from
/// north (degrees, RocketPy's convention), and the travel of the reference point along the
/// rail until the last rail button leaves it (`exit_travel`, m).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RailEntry {
    /// The coordinates x (east), y (north), z (up) of the body's reference point.
    pub position: Spanned<Vec<Spanned<String>>>,
    /// Degrees above the horizontal: 90 is vertical.
    pub inclination: Spanned<f64>,
    /// Degrees clockwise from north (the y axis) towards which the rail leans.
    #[serde(default)]
    pub heading: f64,
    /// How far the reference point travels along the rail until the last button leaves it
    /// (not the rail's length: that less the distance from the lowest point resting on the
    /// rail to the last button).
    pub exit_travel: Spanned<f64>,
}

/// A value a `[[phase]]` sets: a number, or an expression (a string) of `t`, the time of
/// the change, numbers and parameters, evaluated when the change happens
/// (`drogue_t_open = "t + 1.5"`: docs/scenes.md#a-value-set-at-the-change).
#[derive(Clone, Debug, PartialEq)]
pub enum SetValue {
    /// A number.
    Number(f64),
    /// An expression, as written.
    Expression(String),
}

impl<'de> Deserialize<'de> for SetValue {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(SetValueVisitor)
    }
}

/// Reads a number (an integer too, as `f64` does) or a string.
struct SetValueVisitor;

impl serde::de::Visitor<'_> for SetValueVisitor {
    type Value = SetValue;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a number, or an expression of the change's time `t` in quotes (\"t + 1.5\")")
    }

    fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<SetValue, E> {
        Ok(SetValue::Number(v))
    }

    fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<SetValue, E> {
        Ok(SetValue::Number(v as f64))
    }

    fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<SetValue, E> {
        Ok(SetValue::Number(v as f64))
    }

    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<SetValue, E> {
        Ok(SetValue::Expression(v.to_string()))
    }
}

/// `carry = "separation" | "capture"` (docs/scenes.md).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CarryRule {
    /// q and q̇ continuous, p recomputed.
    #[default]
    Separation,
    /// q and p continuous.
    Capture,
}

/// A `--method` name, read by clap's own table of names.
#[derive(Clone, Copy, Debug)]
pub struct MethodName(pub Method);

impl Default for MethodName {
    fn default() -> Self {
        Self(Method::DormandPrince)
    }
}

impl<'de> Deserialize<'de> for MethodName {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        clap::ValueEnum::from_str(&name, false)
            .map(MethodName)
            .map_err(|_| {
                let known: Vec<String> = <Method as clap::ValueEnum>::value_variants()
                    .iter()
                    .filter_map(clap::ValueEnum::to_possible_value)
                    .map(|v| v.get_name().to_string())
                    .collect();
                serde::de::Error::custom(format!(
                    "unknown method `{name}`; the methods are {}",
                    known.join(", ")
                ))
            })
    }
}

/// The scene file's text and its parsed form.
pub struct Read {
    /// The text, for locating spans.
    pub source: String,
    /// The scene.
    pub scene: SceneFile,
}

/// Reads and parses `path`; a TOML or schema mistake is a [`CliError::Input`] with the
/// file, line and column.
pub fn read(path: &Path) -> Result<Read, CliError> {
    let source = std::fs::read_to_string(path).map_err(|source| CliError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse(source, path)
}

/// Parses the text `source` of the scene file at `path` (a scene read once and run again
/// with other values: `scene::Rerun`).
pub fn parse(source: String, path: &Path) -> Result<Read, CliError> {
    let scene = toml::from_str::<SceneFile>(&source).map_err(|e| {
        let place = e
            .span()
            .map(|span| format!(":{}", line_column(&source, span.start)))
            .unwrap_or_default();
        CliError::Input(format!(
            "{}{place}: {}",
            path.display(),
            e.message().trim_end()
        ))
    })?;
    Ok(Read { source, scene })
}

/// `line:column` (both from 1) of byte `offset` in `source`.
pub fn line_column(source: &str, offset: usize) -> String {
    let before = source.get(..offset).unwrap_or(source);
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    format!("{line}:{column}")
}
