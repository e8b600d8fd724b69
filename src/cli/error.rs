//! The binary's errors: each says what went wrong and where, in words, and maps to an exit code.

use thiserror::Error;

/// An error of a command.
#[derive(Debug, Error)]
pub enum CliError {
    /// Bad input from the user (an expression, an assignment, a scene): already rendered with its
    /// location.
    #[error("{0}")]
    Input(String),
    /// A file that could not be read.
    #[error("error: cannot read {path}: {source}")]
    Io {
        /// The path.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// A claim of `symdyn check` that does not hold.
    #[error("{0}")]
    CheckFailed(String),
}

impl CliError {
    /// The process exit code: 1 for bad input or a failed check, 2 for unreadable files.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::Input(_) | CliError::CheckFailed(_) => 1,
            CliError::Io { .. } => 2,
        }
    }
}
