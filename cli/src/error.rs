//! What can go wrong, each with its message and exit code.

use std::path::PathBuf;

/// A failure of the tool. Every variant is printed as `error: …` on stderr.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The model file could not be read.
    #[error("cannot read `{}`: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// An output file could not be written.
    #[error("cannot write `{}`: {reason}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// The model does not derive or a `check` fails: the rendered diagnostics.
    #[error("{rendered}")]
    Model {
        /// Every diagnostic, rendered with file, line, column and caret.
        rendered: String,
        /// How many there are.
        count: usize,
    },
    /// Bad command-line input (an unknown name, an unparsable number, …).
    #[error("{0}")]
    Input(String),
    /// The integration failed.
    #[error("{0}")]
    Run(String),
}

impl CliError {
    /// The process exit code: 1 for a model that fails its checks or a failed run, 2 for
    /// unusable input (as clap does for bad arguments).
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Model { .. } | CliError::Run(_) => 1,
            CliError::Read { .. } | CliError::Write { .. } | CliError::Input(_) => 2,
        }
    }
}
