//! Reading expressions and scenes: text such as `2 m2 lc2^2 sin(q2)` into a canonical [`Expr`], and a
//! scene file into a [`Robot`](crate::dynamics::Robot) ([`parse_scene`]).
//!
//! The grammars are `grammar/expr.pest` and `grammar/scene.pest`, one parser (module `grammar`);
//! `lower` turns an expression's pairs into `Expr` with a Pratt parser that holds the operators'
//! precedence; `error` renders failures with a line, a column and a caret; `scene` reads scenes line by
//! line, reusing `lower` for every value. Parsing user input never panics: nesting is capped
//! ([`MAX_DEPTH`]), numbers and exponents are bounded, and every failure is a [`ParseError`] or a
//! [`SceneError`]. `urdf` reads URDF files into the same [`Scene`]; [`parse_robot`] reads either, told
//! apart by their content.

mod error;
pub(crate) mod grammar;
mod input;
mod location;
pub(crate) mod lower;
mod names;
pub mod scene;
pub mod urdf;

use crate::algebra::Expr;
use grammar::{Grammar, Rule};
use pest::Parser;

pub use error::{ParseError, ParseErrorKind};
pub use grammar::Expected;
pub use input::{parse_robot, InputError};
pub use scene::{
    parse_extras, parse_scene, Extras, Scene, SceneError, SceneErrorKind, SceneExpected,
    SceneWarning,
};

/// The scene the `symdyn` binary reads when given none: Spong et al., Problem 7.7, the 3-link
/// Cartesian (PPP) manipulator (`examples/ppp.scene`).
pub const BUILTIN_PPP: &str = include_str!("../../examples/ppp.scene");

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
