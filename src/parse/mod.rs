//! Reading expressions: text such as `2 m2 lc2^2 sin(q2)` into a canonical [`Expr`].
//!
//! The grammar is `grammar/expr.pest` (module `grammar`); `lower` turns pest's pairs into `Expr` with
//! a Pratt parser that holds the operators' precedence; `error` renders failures with a line, a column
//! and a caret. Parsing user input never panics: nesting is capped ([`MAX_DEPTH`]), numbers and
//! exponents are bounded, and every failure is a [`ParseError`].

mod error;
pub(crate) mod grammar;
pub(crate) mod lower;
mod names;

use crate::algebra::Expr;
use grammar::{Grammar, Rule};
use pest::Parser;

pub use error::{ParseError, ParseErrorKind};
pub use grammar::Expected;

/// The deepest nesting accepted: levels of parentheses (and calls), plus chains of signs and powers.
pub const MAX_DEPTH: usize = 256;

/// Parses one expression, the whole of `input`: `parse_expr("(m1 + m2) g cos(q1)")`.
///
/// Numbers are exact (`0.4318` is 2159/5000), `90deg` is π/2, Greek letters are their ASCII names
/// (`θ1` is `theta1`) and `q1`, `qd1`, `qdd1`, `q̇1`, `q̈1` are coordinates.
///
/// # Errors
///
/// A [`ParseError`] locating the first problem: text that is not an expression, an unknown function,
/// a division by zero, a power that is not an integer, a number or a nesting beyond the bounds.
pub fn parse_expr(input: &str) -> Result<Expr, ParseError> {
    lower::check_paren_depth(input)?;
    let mut pairs =
        Grammar::parse(Rule::expr_input, input).map_err(|e| error::from_pest(input, e))?;
    let expr = pairs
        .next()
        .and_then(|p| p.into_inner().find(|p| p.as_rule() == Rule::expr));
    match expr {
        Some(pair) => lower::lower_expr(pair),
        None => Err(ParseError::new(
            ParseErrorKind::Expected(vec![Expected::Operand]),
            input,
            0..0,
        )),
    }
}
