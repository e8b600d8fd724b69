//! `simplify`: the normal form, then the display rewrites of `tidy`.
//!
//! Equal mathematics gives equal output: the normal form is unique within the zero-test contract, and
//! the display rewrites are deterministic functions of it.

use super::expr::Expr;
use super::tidy::tidy;

/// The simplified form of `e` for display: `sin(q1)^2 + cos(q1)^2` is `1`, `1/3 + 1/6` is `1/2`.
pub fn simplify(e: &Expr) -> Expr {
    tidy(e)
}
