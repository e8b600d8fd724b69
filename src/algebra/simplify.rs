//! `simplify`: the normal form, then the display rewrites of `tidy`.
//!
//! Equal mathematics gives equal output: the normal form is unique within the zero-test contract
//! among expressions written over the same base angles (see `normal`: `sin(q1)` and
//! `2 sin(q1/2) cos(q1/2)` are equal, and their difference simplifies to 0, but each alone keeps its
//! own angle), and the display rewrites are deterministic functions of it.

use super::error::AlgebraError;
use super::expr::Expr;
use super::normal::try_normal_form;
use super::tidy::tidy;

/// The simplified form of `e` for display: `sin(q1)^2 + cos(q1)^2` is `1`, `1/3 + 1/6` is `1/2`.
///
/// # Errors
///
/// The expansion would pass the [size limits](super::limits): `sin(q1)^99999999` would expand into
/// fifty million terms, `(a + b)^3000` hold numbers of 3000 bits.
pub fn simplify(e: &Expr) -> Result<Expr, AlgebraError> {
    Ok(tidy(&try_normal_form(e)?))
}
