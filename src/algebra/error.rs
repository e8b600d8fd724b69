//! Errors of the algebra core: the few operations that have no value.

use thiserror::Error;

/// Why an algebraic operation has no result.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum AlgebraError {
    /// A division by an expression that is identically zero (also `0^-k`, `tan(pi/2)`).
    #[error("division by zero")]
    DivisionByZero,
    /// `sqrt` applies to rational numbers only.
    #[error("sqrt takes a rational number here, not `{0}`")]
    SqrtOfNonRational(String),
    /// `sqrt` of a negative number has no real value.
    #[error("sqrt of the negative number {0} has no real value")]
    SqrtOfNegative(String),
    /// An exponent that is not an integer.
    #[error("only integer powers are supported, not `{0}`")]
    NonIntegerPower(String),
    /// A number too large to handle (such as an exponent beyond 2^31).
    #[error("number too large: {0}")]
    TooLarge(String),
}
