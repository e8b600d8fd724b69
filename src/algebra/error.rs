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
    /// A result whose numbers would pass [`MAX_NUMBER_BITS`](super::limits::MAX_NUMBER_BITS).
    #[error("`{what}` would hold a number of about {bits} bits, more than the limit of {} bits (about 600 digits)", super::limits::MAX_NUMBER_BITS)]
    NumberTooLarge {
        /// The operation, as the parser reads it.
        what: String,
        /// The estimated size of its largest number, in bits.
        bits: String,
    },
    /// An expansion that would produce more than [`MAX_TERMS`](super::limits::MAX_TERMS) terms.
    #[error(
        "`{what}` would expand into about {terms} terms, more than the limit of {}",
        super::limits::MAX_TERMS
    )]
    TooManyTerms {
        /// The operation, as the parser reads it.
        what: String,
        /// The estimated number of terms.
        terms: String,
    },
}
