//! The errors of identification: what a robot, a data file or a fit cannot give, in words.

use crate::dynamics::model::ModelError;
use thiserror::Error;

/// Why a regressor, a set of base parameters or a fit could not be computed.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum IdentifyError {
    /// The robot itself is invalid.
    #[error("{0}")]
    Model(#[from] ModelError),
    /// A symbol that `--gravity-input` needs for the gravity vector is already a scene parameter.
    #[error("the scene already uses the name {0}, which --gravity-input needs for a component of gravity")]
    NameTaken(String),
    /// An entry of the regressor has a leaf without exact rational values at random points (a surd,
    /// the sine of a constant angle that is no multiple of π/2 in a symbolic expression).
    #[error("{0} has no exact rational value at random points, so the base parameters cannot be found by exact elimination")]
    NoRationalValue(String),
    /// The exact elimination found dependencies that the symbolic proof refuted at every attempt.
    #[error("the linear dependencies found at random points do not hold symbolically after {0} attempts")]
    Unproved(u32),
    /// A data file is malformed; the message is located (`file:line:column`).
    #[error("{0}")]
    Data(String),
    /// The fit is refused: too few samples or a badly exciting trajectory.
    #[error("{0}")]
    Fit(String),
    /// A parameter without a value where a number is needed.
    #[error("no value for {0}: give it with --set {0}=...")]
    Unbound(String),
}
