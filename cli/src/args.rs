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
    /// Fit parameters (and initial values) of a model to measured data by weighted least
    /// squares, with their standard errors and correlations (docs/sensitivities.md#fitting).
    Fit(Box<crate::fit::FitArgs>),
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
    /// sdirk4, esdirk43, taylor), from the method's floor (100 machine epsilons, 2.2e-14;
    /// taylor 1e-15) to 0.1.
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
    /// The quantities to record, comma-separated: x, x', m, H, L, T, V, power, x'', p_x, Q_x,
    /// R1_x, R2_x, dp_x, pdot_x, mdot_m (for a coordinate x and a mass m), a `let` name, or
    /// NAME=EXPRESSION of these and the parameters (`--record "E=1/2*m*x'^2"`); default:
    /// coordinates, velocities and state masses.
    #[arg(long, value_name = "NAMES")]
    pub record: Vec<String>,
    /// Record the derivatives of the recorded quantities with respect to a parameter
    /// NAME, or to an initial value `init:x`, `init:x'` or `init:m` (a coordinate, a
    /// velocity, a state mass), integrated with the run (forward sensitivities,
    /// docs/sensitivities.md): columns `d(X)/d(NAME)`, and `d(t)/d(NAME)`, non-zero where a
    /// --stop-when event ends the run. Repeatable, up to 6; Dormand–Prince or DOP853.
    #[arg(long = "sensitivity", value_name = "NAME")]
    pub sensitivity: Vec<String>,
    /// Record every DT seconds instead of at every accepted step.
    #[arg(long, value_name = "DT", allow_hyphen_values = true)]
    pub every: Option<f64>,
    /// Write the recorded quantities as CSV (header `t,<names>`).
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
    /// Plot the recorded quantities against t (SVG, or PNG with the `png` feature).
    #[arg(long, value_name = "PATH")]
    pub plot: Option<PathBuf>,
    /// Write a scene's flight summary as JSON (a scene file with a `[flight]` table,
    /// docs/scenes.md#flight).
    #[arg(long, value_name = "PATH")]
    pub summary_json: Option<PathBuf>,
    /// How messages name these settings: as flags, or as the keys of the scene file they
    /// were read from (not a flag).
    #[arg(skip)]
    pub words: Words,
    /// Output times instead of every accepted step, increasing (not a flag: `varmass fit`
    /// sets its data's times).
    #[arg(skip)]
    pub at: Vec<f64>,
    /// Also the rates `d(X)/d(t)` of the recorded quantities along the motion, beside the
    /// sensitivities' columns (not a flag: `varmass fit` fits a log's time offset with
    /// them).
    #[arg(skip)]
    pub rates: bool,
}

/// Where a run's settings were written, so that a message names what its user wrote: the
/// flags of `varmass run`, the keys of a scene file (docs/scenes.md), or the keywords of
/// the Python package's `Model.run`, whose users never typed a flag.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Words {
    /// Command-line flags (`--set`, `--stop-when`, …).
    #[default]
    Flags,
    /// A scene file's keys (`set`, `stop_when`, …).
    Scene,
    /// Python's keywords (`set=`, `stop_when=`, `from_=`, …).
    Python,
}

impl Words {
    /// The setting `flag` (a `varmass run` flag, `--max-steps`) as its user wrote it: the
    /// flag, the scene file's key (`max_steps`: the keys are the flags' names with `_`) or
    /// Python's keyword.
    pub fn setting(self, flag: &str) -> String {
        match self {
            Words::Flags => flag.to_string(),
            Words::Scene => format!("`{}`", key(flag)),
            Words::Python => format!("`{}`", keyword(flag)),
        }
    }

    /// The setting `flag` given `value`, as its user wrote it: `--tol 0.5`, the scene
    /// file's `tol = 0.5`, or Python's `tol=0.5`.
    pub fn given(self, flag: &str, value: &str) -> String {
        match self {
            Words::Flags => format!("{flag} {value}"),
            Words::Scene => format!("`{} = {value}`", key(flag)),
            Words::Python => format!("`{}={value}`", keyword(flag)),
        }
    }

    /// A name (a method's, a tag) as a value of this user's settings: as typed on the
    /// command line, quoted in a scene file or in Python.
    pub fn name(self, name: &str) -> String {
        match self {
            Words::Flags => name.to_string(),
            Words::Scene | Words::Python => format!("\"{name}\""),
        }
    }

    /// A stop condition `condition` written as this user would write it.
    pub fn stop_when(self, condition: &str) -> String {
        match self {
            Words::Flags => format!("--stop-when '{condition}'"),
            Words::Scene => format!("`stop_when = \"{condition}\"`"),
            Words::Python => format!("`stop_when=\"{condition}\"`"),
        }
    }

    /// How to give the parameters `names` values.
    pub fn give_parameters(self, names: &[String]) -> String {
        let each = |f: &dyn Fn(&String) -> String| names.iter().map(f).collect::<Vec<_>>();
        match self {
            Words::Flags => each(&|n| format!("--set {n}=VALUE")).join(" "),
            Words::Scene => each(&|n| format!("`{n} = VALUE` under `[set]`")).join(", "),
            Words::Python => format!(
                "`set={{{}}}`",
                each(&|n| format!("\"{n}\": VALUE")).join(", ")
            ),
        }
    }

    /// How to give the input `name` a law.
    pub fn give_input(self, name: &str) -> String {
        match self {
            Words::Flags => format!("--input '{name}=EXPRESSION'"),
            Words::Scene => format!("`{name} = \"EXPRESSION\"` under `[input]`"),
            Words::Python => format!("`inputs={{\"{name}\": \"EXPRESSION\"}}`"),
        }
    }

    /// How to add the statements tagged `tag` to the run.
    pub fn add_tag(self, tag: &str) -> String {
        match self {
            Words::Flags => format!("`--with {tag}`"),
            Words::Scene => format!("\"{tag}\" to `with`"),
            Words::Python => format!("\"{tag}\" to the model's `with_`"),
        }
    }
}

/// The scene file's key for the flag `flag`: its name with `_` (`--max-steps` → `max_steps`).
fn key(flag: &str) -> String {
    flag.trim_start_matches('-').replace('-', "_")
}

/// Python's keyword for the flag `flag` (`Model.run`'s, `Model.from_file`'s `with_`): the
/// scene key, but where Python spells it otherwise.
fn keyword(flag: &str) -> String {
    match flag {
        "--from" => "from_".to_string(),
        "--with" => "with_".to_string(),
        "--input" => "inputs".to_string(),
        "--table" => "tables".to_string(),
        other => key(other),
    }
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
    /// `ESDIRK4(3)6L[2]SA`, L-stable implicit with an explicit first stage, adaptive (`--tol`)
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

impl Method {
    /// Every method's name as `--method` and a scene's `method` take it, in the enum's
    /// order: the one list of them, which Python's `varmass.METHODS` reads too.
    pub fn names() -> Vec<String> {
        Method::value_variants()
            .iter()
            .filter_map(ValueEnum::to_possible_value)
            .map(|v| v.get_name().to_string())
            .collect()
    }
}
