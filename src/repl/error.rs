//! The errors of one REPL line. Each says what went wrong in words; none ends the session.

use thiserror::Error;

/// Why a line got no answer.
#[derive(Debug, Error, PartialEq, Eq)]
pub enum ReplError {
    /// An expression or a scene that does not parse, rendered with its line, column and caret.
    #[error("{0}")]
    Parse(String),
    /// A first word that names no command.
    #[error("unknown command `{name}`{}; type `help` for the list", suggestion_text(.suggestion))]
    UnknownCommand {
        /// What was typed.
        name: String,
        /// The closest command name, if one is close.
        suggestion: Option<String>,
    },
    /// A command used with the wrong arguments: the usage line.
    #[error("usage: {0}")]
    Usage(String),
    /// An index beyond the robot's joints (or below 1).
    #[error("{query}: {}", index_text(*.low, *.dof))]
    Index {
        /// The query as typed back: `D[4,1]`, `Jv 0`.
        query: String,
        /// The robot's number of joints.
        dof: usize,
        /// The lowest index the query accepts (0 for frames, 1 otherwise).
        low: usize,
    },
    /// An index below 1 where indices count from 1 (`D[0,1]`).
    #[error("{query}: indices start at 1, as in the book (the robot's joints are 1 to {dof})")]
    IndexFromOne {
        /// The query as typed back: `D[0,1]`, `Jv 0`.
        query: String,
        /// The robot's number of joints.
        dof: usize,
    },
    /// A mathematical operation without a result (a value that is not a number, a zero denominator).
    #[error("{0}")]
    Math(String),
    /// A command the front end must carry out (reading a file).
    #[error("`{0}` is read by the REPL front end; in the library call `Session::load_scene_text`")]
    FrontEnd(String),
    /// A query whose expanded answer is too large to derive ([`Derivation::measured_fits`] with
    /// [`crate::dynamics::EXPANSION_LIMIT`], as `symdyn derive`).
    ///
    /// [`Derivation::measured_fits`]: crate::dynamics::Derivation::measured_fits
    #[error(
        "{query}: {why}, too large to expand; `symdyn derive --compact` prints every quantity as \
         named intermediates, `symdyn eval` evaluates them, and `T`, `R`, `Jv`, `Jw`, `regressor` \
         and `base` still answer here"
    )]
    TooLarge {
        /// The query as typed.
        query: String,
        /// Which entry of `D(q)` passed the limit, and the limit.
        why: crate::dynamics::TooLarge,
    },
}

fn suggestion_text(s: &Option<String>) -> String {
    match s {
        Some(s) => format!(" (did you mean `{s}`?)"),
        None => String::new(),
    }
}

fn index_text(low: usize, dof: usize) -> String {
    if low == 0 {
        format!("the robot has {dof} joints (frames 0 to {dof})")
    } else {
        format!("the robot has {dof} joints")
    }
}
