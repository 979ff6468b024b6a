//! The command line, declared with clap's derive API.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

/// Check, derive and run variable-mass model files (the varmass DSL) without writing Rust.
#[derive(Debug, Parser)]
#[command(name = "varmass", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Derive the model and verify its `check`s; exit 1 with every diagnostic if one fails.
    Check(ModelArgs),
    /// Print the whole derivation (masses, L, p, H, forces, canonical equations, power).
    Derive(DeriveArgs),
    /// Integrate the model from an initial state with one of the core's steppers, or run a
    /// scene file (`varmass run SCENE.toml`: phases, docs/scenes.md).
    Run(Box<RunArgs>),
}

/// The model file and the optional effects it is built with.
#[derive(Clone, Debug, PartialEq, Args)]
pub struct ModelArgs {
    /// The model file (varmass DSL).
    pub file: PathBuf,
    /// Include the statements tagged `[TAG]` (repeat for several effects).
    #[arg(long = "with", value_name = "TAG")]
    pub with: Vec<String>,
}

/// `varmass derive`.
#[derive(Debug, Args)]
pub struct DeriveArgs {
    /// The model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// Print LaTeX (`align*` environments) instead of text.
    #[arg(long)]
    pub latex: bool,
}

/// `varmass run`. Numbers after an option may be negative: the numeric options take a
/// value that starts with `-` (`--tol -1e-9` reaches the range check, not clap's "use
/// `-- -1`" tip, which does not apply to options; clap's own negative-number rule does not
/// know exponents like `-1e-9`).
#[derive(Clone, Debug, PartialEq, Args)]
pub struct RunArgs {
    /// The model.
    #[command(flatten)]
    pub model: ModelArgs,
    /// A parameter value, NAME=VALUE (repeat for each parameter).
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// A law for an `input` of the model, NAME=EXPRESSION: a DSL expression of the input's
    /// declared arguments and the parameters (`--input "u=kp*(10 - y) - kd*y'"`), put in
    /// place of each call (repeat for each input).
    #[arg(long = "input", value_name = "NAME=EXPRESSION")]
    pub input: Vec<String>,
    /// The data of a table of the model, NAME=FILE (`.eng` RASP or `.csv`, relative to the
    /// current directory): required by a `table NAME(..) = runtime`, and replacing the file
    /// of a file table; the statement's options hold (repeat for each table).
    #[arg(long = "table", value_name = "NAME=FILE")]
    pub table: Vec<String>,
    /// An initial value: a coordinate `x`, a velocity `x'` (0 if unset) or a state mass `m`.
    #[arg(long = "init", value_name = "NAME=VALUE")]
    pub init: Vec<String>,
    /// The start time.
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "T0",
        allow_hyphen_values = true
    )]
    pub from: f64,
    /// The end time (required, except with a scene file `SCENE.toml`, which gives its own).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub until: Option<f64>,
    /// Stop at the first crossing of a recorded quantity through a value: 'NAME = VALUE'
    /// (either way), 'NAME > VALUE' (rising through it), 'NAME < VALUE' (falling).
    #[arg(long = "stop-when", value_name = "CONDITION")]
    pub stop_when: Vec<String>,
    /// The stepper.
    #[arg(long, value_enum, default_value_t = Method::DormandPrince)]
    pub method: Method,
    /// Relative and absolute tolerance of the adaptive steppers (dormand-prince, dop853,
    /// sdirk4, esdirk43, taylor), from 100 machine epsilons (2.2e-14, what f64 can honour) to 0.1.
    #[arg(
        long,
        value_name = "TOL",
        conflicts_with = "step",
        allow_hyphen_values = true
    )]
    pub tol: Option<f64>,
    /// The fixed step size (required by the fixed-step methods; makes an adaptive one fixed).
    #[arg(long, value_name = "H", allow_hyphen_values = true)]
    pub step: Option<f64>,
    /// The most steps the run may take; a fixed step that needs more
    /// to reach --until is refused before the first step.
    #[arg(long, value_name = "N", default_value_t = 10_000_000)]
    pub max_steps: u64,
    /// A wall-clock limit in seconds: the run fails, with its state, once it has taken longer.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub max_seconds: Option<f64>,
    /// The quantities to record, comma-separated: x, x', x'', p_x, m, mdot_m, H, power, Q_x,
    /// R1_x, R2_x, pdot_x, a `let` name, or NAME=EXPRESSION of these and the parameters
    /// (`--record "E=1/2*m*x'^2"`); default: coordinates, velocities and state masses.
    #[arg(long, value_name = "NAMES")]
    pub record: Vec<String>,
    /// Record every DT seconds instead of at every accepted step.
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    pub every: Option<f64>,
    /// Write the recorded quantities as CSV (header `t,<names>`).
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Plot the recorded quantities against t (SVG, or PNG with the `png` feature).
    #[arg(long, value_name = "PATH")]
    pub plot: Option<PathBuf>,
    /// How messages name these settings: as flags, or as the keys of the scene file they
    /// were read from (not a flag).
    #[arg(skip)]
    pub words: Words,
}

/// Where a run's settings were written, so that a message names what its user wrote: the
/// flags of `varmass run`, or the keys of a scene file (docs/scenes.md), whose user never
/// typed a flag.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Words {
    /// Command-line flags (`--set`, `--stop-when`, …).
    #[default]
    Flags,
    /// A scene file's keys (`set`, `stop_when`, …).
    Scene,
}

impl Words {
    /// The setting `flag` (a `varmass run` flag, `--max-steps`) as its user wrote it: the
    /// flag, or the scene file's key (`max_steps`: the keys are the flags' names with `_`).
    pub fn setting(self, flag: &str) -> String {
        match self {
            Words::Flags => flag.to_string(),
            Words::Scene => format!("`{}`", key(flag)),
        }
    }

    /// The setting `flag` given `value`, as its user wrote it: `--tol 0.5`, or the scene
    /// file's `tol = 0.5`.
    pub fn given(self, flag: &str, value: &str) -> String {
        match self {
            Words::Flags => format!("{flag} {value}"),
            Words::Scene => format!("`{} = {value}`", key(flag)),
        }
    }

    /// A stop condition `condition` written as this user would write it.
    pub fn stop_when(self, condition: &str) -> String {
        match self {
            Words::Flags => format!("--stop-when '{condition}'"),
            Words::Scene => format!("`stop_when = \"{condition}\"`"),
        }
    }

    /// How to give the parameter `name` a value.
    pub fn give_parameter(self, name: &str) -> String {
        match self {
            Words::Flags => format!("--set {name}=VALUE"),
            Words::Scene => format!("`{name} = VALUE` under `[set]`"),
        }
    }
}

/// The scene file's key for the flag `flag`: its name with `_` (`--max-steps` → `max_steps`).
fn key(flag: &str) -> String {
    flag.trim_start_matches('-').replace('-', "_")
}

/// The core's steppers.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// Dormand–Prince 5(4), adaptive (`--tol`) or fixed (`--step`).
    DormandPrince,
    /// DOP853, eighth order, adaptive (`--tol`) or fixed (`--step`): for tight tolerances.
    Dop853,
    /// SDIRK4, L-stable implicit, adaptive (`--tol`) or fixed (`--step`): for stiff models.
    Sdirk4,
    /// ESDIRK4(3)6L[2]SA, L-stable implicit with an explicit first stage, adaptive (`--tol`)
    /// or fixed (`--step`); its error runs above the tolerance: ask two orders tighter.
    Esdirk43,
    /// Classical Runge–Kutta 4, fixed step.
    Rk4,
    /// Explicit Euler, fixed step.
    Euler,
    /// Implicit midpoint, fixed step, Newton on the Jacobian.
    ImplicitMidpoint,
    /// Midpoint discretisation of the corrected Hamilton principle, fixed step.
    Variational,
    /// Taylor's method on the model's Taylor recurrences, order and step from the tolerance
    /// (`--tol`, Jorba & Zou), or order 20 with a fixed `--step`: for the tightest
    /// tolerances.
    Taylor,
}
