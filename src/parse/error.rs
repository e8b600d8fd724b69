//! Parse errors: what went wrong, in a user's words, and where, with the line and a caret under it.
//!
//! ```text
//! line 1, column 7: division by zero
//!   1 + x/0
//!         ^
//! ```

use super::grammar::{Expected, Rule};
use super::location::{floor_boundary, Location};
use super::names;
use super::MAX_DEPTH;
use crate::algebra::AlgebraError;
use std::collections::BTreeSet;
use std::ops::Range;
use thiserror::Error;

/// What is wrong with the text.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[non_exhaustive]
pub enum ParseErrorKind {
    /// The text stops making sense here; these would have.
    #[error("expected {}", expected_words(.0))]
    Expected(Vec<Expected>),
    /// A `(` that is never closed.
    #[error("unclosed `(`")]
    UnclosedParen,
    /// A `)` with no `(` to close.
    #[error("unmatched `)`")]
    UnmatchedParen,
    /// A call of a function that does not exist.
    #[error(
        "unknown function `{0}`; the known functions are {list}{hint}",
        list = names::function_list(),
        hint = product_hint(.0)
    )]
    UnknownFunction(String),
    /// A function name used without its argument.
    #[error(
        "`{0}` is a function: write its argument in parentheses right after it, as in `{0}(x)`"
    )]
    FunctionWithoutArgument(String),
    /// `deg` that does not follow a number.
    #[error("`deg` must follow a number directly, as in `90deg`")]
    MisplacedDeg,
    /// A division by an expression that is zero.
    #[error("division by zero")]
    DivisionByZero,
    /// An exponent that is not an integer.
    #[error("only integer powers are supported")]
    NonIntegerPower,
    /// An exponent beyond the supported range.
    #[error("exponent too large: exponents are limited to {}", i32::MAX)]
    ExponentTooLarge,
    /// A number too large to hold exactly.
    #[error("number too large: exact numbers are limited to about 600 digits")]
    NumberTooLarge,
    /// A name spelt as a derivative `qN_dK` whose order `K` is not from 1 to 254.
    #[error("`{0}` names a time derivative of a coordinate: its order, after `_d`, is a whole number from 1 to 254 (`q1_d3` is the third derivative of q1)")]
    DerivativeOrder(String),
    /// More nesting than [`MAX_DEPTH`] levels.
    #[error("expression nested too deeply (more than {MAX_DEPTH} levels of parentheses, signs and powers)")]
    TooDeep,
    /// An operation of the algebra core with no value, such as `sqrt(x)` or `sqrt(-2)`.
    #[error(transparent)]
    Algebra(AlgebraError),
}

/// For an unknown function that looks like a parameter (`m2(x)`, `lc_1(x)`: it has a digit or `_`),
/// how to write the product that was probably meant.
fn product_hint(name: &str) -> String {
    if name.contains(|c: char| c.is_ascii_digit() || c == '_') {
        format!(" (for a product, write `{name} (...)`)")
    } else {
        String::new()
    }
}

/// The expectations joined into words, such as "an operator such as `+` or `*`, or `)`".
fn expected_words(what: &[Expected]) -> String {
    let words: Vec<&str> = what.iter().map(|e| e.words()).collect();
    words.join(", or ")
}

/// A parse error: its kind, and where in the source it is. Small (one pointer), so that results
/// travel cheaply through the parser's recursion.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("{0}")]
pub struct ParseError(Box<Located>);

/// The contents of a [`ParseError`].
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("line {}, column {}: {kind}\n{}", at.line, at.column, at.excerpt)]
struct Located {
    kind: ParseErrorKind,
    at: Location,
}

impl ParseError {
    /// An error of `kind` at the byte range `span` of `source` (the whole text that was parsed, so
    /// that the line and column are counted from its start).
    pub fn new(kind: ParseErrorKind, source: &str, span: Range<usize>) -> ParseError {
        ParseError(Box::new(Located {
            kind,
            at: Location::new(source, span),
        }))
    }

    /// What is wrong.
    pub fn kind(&self) -> &ParseErrorKind {
        &self.0.kind
    }

    /// The offending text, as a byte range of the source.
    pub fn span(&self) -> Range<usize> {
        self.0.at.span.clone()
    }

    /// The line, from 1.
    pub fn line(&self) -> usize {
        self.0.at.line
    }

    /// The column, from 1, counted in characters.
    pub fn column(&self) -> usize {
        self.0.at.column
    }

    /// The error as a compiler prints it: `file:line:column: message`, then the line and the caret.
    pub fn render(&self, source_name: &str) -> String {
        self.0.at.render(source_name, &self.0.kind)
    }
}

/// The innermost `(` left open at the end of `text`, as a byte offset.
fn innermost_open(text: &str) -> Option<usize> {
    let mut open = Vec::new();
    for (i, c) in text.char_indices() {
        match c {
            '(' => open.push(i),
            ')' => {
                open.pop();
            }
            _ => {}
        }
    }
    open.pop()
}

/// Translates pest's error on the expression text `source` into a [`ParseError`].
pub(crate) fn from_pest(source: &str, error: pest::error::Error<Rule>) -> ParseError {
    let pos = match error.location {
        pest::error::InputLocation::Pos(p) => p,
        pest::error::InputLocation::Span((s, _)) => s,
    };
    let pos = floor_boundary(source, pos.min(source.len()));
    let rest = &source[pos..];
    let here = pos..pos + rest.chars().next().map_or(0, char::len_utf8);
    let positives = match error.variant {
        pest::error::ErrorVariant::ParsingError { positives, .. } => positives,
        // pest's only own errors are its call and stack limits.
        pest::error::ErrorVariant::CustomError { .. } => {
            return ParseError::new(ParseErrorKind::TooDeep, source, here)
        }
    };
    let mut expected: BTreeSet<Expected> = positives
        .into_iter()
        .filter_map(Expected::of_rule)
        .collect();
    // After an operand, pest also lists `name`: implicit multiplication looked ahead for one.
    if expected.contains(&Expected::Operator) {
        expected.remove(&Expected::Operand);
    }
    if expected.is_empty() || expected.contains(&Expected::Operand) {
        return ParseError::new(
            ParseErrorKind::Expected(vec![Expected::Operand]),
            source,
            here,
        );
    }
    let after_spaces = rest.trim_start_matches([' ', '\t']);
    let at_end = after_spaces.is_empty() || after_spaces.starts_with(['\n', '\r']);
    match innermost_open(&source[..pos]) {
        Some(open) if at_end => {
            ParseError::new(ParseErrorKind::UnclosedParen, source, open..open + 1)
        }
        Some(_) => {
            expected.remove(&Expected::End);
            expected.insert(Expected::CloseParen);
            ParseError::new(
                ParseErrorKind::Expected(expected.into_iter().collect()),
                source,
                here,
            )
        }
        None if rest.starts_with(')') => {
            ParseError::new(ParseErrorKind::UnmatchedParen, source, here)
        }
        None => ParseError::new(
            ParseErrorKind::Expected(expected.into_iter().collect()),
            source,
            here,
        ),
    }
}
