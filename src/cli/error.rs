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
    /// A file that could not be written (or created), or stdout failing for a reason other than a
    /// closed pipe.
    #[error("error: cannot write {path}: {source}")]
    Write {
        /// The path.
        path: String,
        /// The cause.
        source: std::io::Error,
    },
    /// Stdout was closed by its reader (`symdyn derive … | head`): nothing more to print, and not a
    /// failure; the binary exits quietly with status 0.
    #[error("")]
    StdoutClosed,
    /// A claim of `symdyn check` that does not hold.
    #[error("{0}")]
    CheckFailed(String),
}

impl CliError {
    /// The process exit code: 1 for bad input or a failed check, 2 for files that cannot be read or
    /// written, 0 for a closed stdout.
    pub fn exit_code(&self) -> u8 {
        match self {
            CliError::StdoutClosed => 0,
            CliError::Input(_) | CliError::CheckFailed(_) => 1,
            CliError::Io { .. } | CliError::Write { .. } => 2,
        }
    }
}
