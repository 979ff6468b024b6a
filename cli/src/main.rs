//! `varmass`: check, derive and run variable-mass model files without writing Rust.
//!
//! ```text
//! varmass check models/sled.vms
//! varmass derive models/sled.vms --latex
//! varmass run models/sled.vms --set m0=10 … --init x=0 --until 100 --stop-when 'x = 50'
//! ```
//!
//! A run evaluates the derivation at run time ([`varmass::interpret::TapeSystem`]) and
//! integrates it with the core's steppers, the ones generated code uses.
#![warn(missing_docs)]

use std::io::Write;
use std::process::ExitCode;

use clap::parser::ValueSource;
use clap::{ArgMatches, CommandFactory, FromArgMatches};

use varmass_cli::args::{Cli, Command};
use varmass_cli::error::CliError;
use varmass_cli::{commands, run, scene};

fn main() -> ExitCode {
    let matches = Cli::command().get_matches();
    let cli = Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit());
    let result = match cli.command {
        Command::Check(a) => commands::check::check(&a),
        Command::Derive(a) => commands::derive::derive(&a.model, a.latex),
        Command::Run(a) if scene::is_scene(&a.model.file) => {
            scene::run(&a, &given(&matches, "run"))
        }
        Command::Run(a) => run::run(&a),
        Command::Fit(a) => varmass_cli::fit::run_given(&a, &given(&matches, "fit")),
    };
    match result {
        Ok(text) => {
            // A closed pipe (`varmass derive … | head`) is not an error worth a panic.
            let _ = std::io::stdout().write_all(text.as_bytes());
            ExitCode::SUCCESS
        }
        Err(error) => report(&error),
    }
}

/// The ids of the flags of the subcommand `name` given on the command line (not
/// defaulted): a scene refuses those of a run's settings, whatever their value.
fn given(matches: &ArgMatches, name: &str) -> Vec<String> {
    let (Some((given, sub)), Some(command)) = (
        matches.subcommand(),
        Cli::command().find_subcommand(name).cloned(),
    ) else {
        return Vec::new();
    };
    if given != name {
        return Vec::new();
    }
    // The arguments only: the ids also name the derive's argument groups (`RunArgs`).
    command
        .get_arguments()
        .map(|arg| arg.get_id().as_str())
        .filter(|id| sub.value_source(id) == Some(ValueSource::CommandLine))
        .map(str::to_owned)
        .collect()
}

fn report(error: &CliError) -> ExitCode {
    match error {
        CliError::Model { rendered, count } => {
            eprintln!("{rendered}\n");
            let plural = if *count == 1 { "" } else { "s" };
            eprintln!("error: the model does not derive ({count} error{plural})");
        }
        other => eprintln!("error: {other}"),
    }
    ExitCode::from(error.exit_code())
}
