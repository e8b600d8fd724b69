//! Lowering: the pairs of an `expr` into a canonical [`Expr`].
//!
//! The grammar leaves an expression flat (signs, operands and operators in text order); the Pratt
//! parser below is the one place that gives the operators their precedence and associativity. Every
//! lowered value keeps its span, so an error of the algebra (`1/0`, `x^(1/2)`, `sqrt(x)`) points at
//! the text that caused it.
//!
//! Guards that keep hostile input from exhausting the stack or the memory: nesting deeper than
//! [`MAX_DEPTH`], exponents beyond `i32::MAX` and exact numbers beyond [`MAX_NUMBER_BITS`] are errors.

use super::error::{ParseError, ParseErrorKind};
use super::grammar::Rule;
use super::names::{self, Function};
use super::MAX_DEPTH;
use crate::algebra::{AlgebraError, Expr, Kind, Rational, Symbol};
use pest::iterators::{Pair, Pairs};
use pest::pratt_parser::{Assoc, Op, PrattParser};
use std::ops::Range;
use std::sync::LazyLock;

/// The largest exact number the parser builds, in bits of numerator plus denominator (about 600 decimal
/// digits), and the largest exponent of a result: the core's limits ([`crate::algebra::limits`]).
pub(crate) use crate::algebra::limits::{MAX_EXPONENT, MAX_NUMBER_BITS};

/// The highest derivative order a name `qN_dK` may state: one below the largest order a symbol holds,
/// so that the time derivative of anything read is still exact.
const MAX_READ_ORDER: u8 = u8::MAX - 1;

/// The operators' precedence, lowest first, and associativity: stated once, here.
static PRATT: LazyLock<PrattParser<Rule>> = LazyLock::new(|| {
    PrattParser::new()
        .op(Op::infix(Rule::add, Assoc::Left) | Op::infix(Rule::sub, Assoc::Left))
        .op(Op::infix(Rule::mul, Assoc::Left)
            | Op::infix(Rule::div, Assoc::Left)
            | Op::infix(Rule::implicit_mul, Assoc::Left))
        .op(Op::prefix(Rule::neg) | Op::prefix(Rule::pos))
        .op(Op::infix(Rule::pow, Assoc::Right))
});

/// A lowered piece of the expression and the bytes of the source it was written in.
struct Spanned {
    expr: Expr,
    span: Range<usize>,
}

type Lowered = Result<Spanned, ParseError>;

/// Lowers an `expr` pair, found in any input (an expression alone or a scene statement), into a
/// canonical expression. Errors are located in the pair's whole input.
pub(crate) fn lower_expr(pair: Pair<'_, Rule>) -> Result<Expr, ParseError> {
    debug_assert_eq!(pair.as_rule(), Rule::expr);
    lower_at(pair, 0).map(|s| s.expr)
}

/// Checks that parentheses in `text` nest no deeper than [`MAX_DEPTH`]; to be called before pest
/// parses `text`, since pest recurses once per level.
pub(crate) fn check_paren_depth(text: &str) -> Result<(), ParseError> {
    let mut depth = 0usize;
    for (i, c) in text.char_indices() {
        match c {
            '(' => {
                depth += 1;
                if depth > MAX_DEPTH {
                    return Err(ParseError::new(ParseErrorKind::TooDeep, text, i..i + 1));
                }
            }
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
}

/// Lowers an `expr` pair nested `depth` levels deep.
fn lower_at(pair: Pair<'_, Rule>, depth: usize) -> Lowered {
    let input = pair.get_input();
    let pairs = pair.into_inner();
    let mut operand_depths = operand_depths(pairs.clone(), depth)?.into_iter();
    PRATT
        .map_primary(|p| lower_operand(p, operand_depths.next().unwrap_or(depth + 1)))
        .map_prefix(|op, rhs| unary(op.as_rule(), op.as_span().start(), rhs?))
        .map_infix(|lhs, op, rhs| binary(input, lhs?, op.as_rule(), rhs?))
        .parse(pairs)
}

/// The nesting depth of each operand of an expression nested `depth` levels deep, or an error if
/// one is deeper than [`MAX_DEPTH`].
///
/// The Pratt parser recurses once per sign and per `^` of a chain such as `-x^-y^z`, so these count
/// as levels too: an operand is nested one level deeper than its expression plus the signs and
/// powers still open before it.
#[inline(never)]
fn operand_depths(pairs: Pairs<'_, Rule>, depth: usize) -> Result<Vec<usize>, ParseError> {
    let mut open = 0;
    let mut depths = Vec::new();
    for p in pairs {
        match p.as_rule() {
            Rule::neg | Rule::pos | Rule::pow => {
                open += 1;
                if depth + open > MAX_DEPTH {
                    let s = p.as_span();
                    return Err(ParseError::new(
                        ParseErrorKind::TooDeep,
                        p.get_input(),
                        s.start()..s.end(),
                    ));
                }
            }
            Rule::add | Rule::sub | Rule::mul | Rule::div | Rule::implicit_mul => open = 0,
            _ => depths.push(depth + open + 1),
        }
    }
    Ok(depths)
}

/// Applies a sign written at byte `start`.
#[inline(never)]
fn unary(op: Rule, start: usize, rhs: Spanned) -> Lowered {
    let span = start..rhs.span.end;
    let expr = match op {
        Rule::neg => -&rhs.expr,
        _ => rhs.expr,
    };
    Ok(Spanned { expr, span })
}

/// Applies a binary operator.
#[inline(never)]
fn binary(input: &str, lhs: Spanned, op: Rule, rhs: Spanned) -> Lowered {
    let span = lhs.span.start..rhs.span.end;
    let expr = match op {
        Rule::add => checked(input, &lhs.expr + &rhs.expr, &span)?,
        Rule::sub => checked(input, &lhs.expr - &rhs.expr, &span)?,
        Rule::div => {
            let q = lhs.expr.div(&rhs.expr);
            checked(
                input,
                q.map_err(|e| algebra_error(input, e, rhs.span.clone()))?,
                &span,
            )?
        }
        Rule::pow => power(input, &lhs, &rhs)?,
        // mul and implicit_mul
        _ => checked(input, &lhs.expr * &rhs.expr, &span)?,
    };
    Ok(Spanned { expr, span })
}

/// `base^exponent` for an exponent that is an integer.
fn power(input: &str, base: &Spanned, exponent: &Spanned) -> Result<Expr, ParseError> {
    let span = base.span.start..exponent.span.end;
    let e = exponent
        .expr
        .integer_exponent()
        .map_err(|err| algebra_error(input, err, exponent.span.clone()))?;
    // The core refuses, before computing, a power beyond the size limits (`2^2147483647`).
    let value = base
        .expr
        .pow(e)
        .map_err(|err| algebra_error(input, err, span.clone()))?;
    checked(input, value, &span)
}

use crate::algebra::limits::bits;

/// Refuses results whose top-level numbers or exponents are out of bounds; the parts below the top
/// level were checked when they were built, and only the top level combines in later operations.
/// Operands within bounds give results of at most twice the bound, which the core builds safely.
fn checked(input: &str, e: Expr, span: &Range<usize>) -> Result<Expr, ParseError> {
    let exponent_ok = |fs: &[(Expr, i64)]| fs.iter().all(|(_, k)| k.unsigned_abs() <= MAX_EXPONENT);
    let (numbers_ok, exponents_ok) = match e.kind() {
        Kind::Num(r) => (bits(r) <= MAX_NUMBER_BITS, true),
        Kind::Mul(c, fs) => (bits(c) <= MAX_NUMBER_BITS, exponent_ok(fs)),
        Kind::Add(c, ts) => (
            bits(c) <= MAX_NUMBER_BITS && ts.iter().all(|(_, k)| bits(k) <= MAX_NUMBER_BITS),
            ts.iter().all(|(t, _)| match t.kind() {
                Kind::Mul(_, fs) => exponent_ok(fs),
                _ => true,
            }),
        ),
        Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) | Kind::Fun(..) => (true, true),
    };
    if !numbers_ok {
        return Err(ParseError::new(
            ParseErrorKind::NumberTooLarge,
            input,
            span.clone(),
        ));
    }
    if !exponents_ok {
        return Err(ParseError::new(
            ParseErrorKind::ExponentTooLarge,
            input,
            span.clone(),
        ));
    }
    Ok(e)
}

/// An error of the algebra core, located at `span`.
fn algebra_error(input: &str, error: AlgebraError, span: Range<usize>) -> ParseError {
    let kind = match error {
        AlgebraError::DivisionByZero => ParseErrorKind::DivisionByZero,
        AlgebraError::NonIntegerPower(_) => ParseErrorKind::NonIntegerPower,
        AlgebraError::TooLarge(_) => ParseErrorKind::ExponentTooLarge,
        AlgebraError::NumberTooLarge { .. } => ParseErrorKind::NumberTooLarge,
        other => ParseErrorKind::Algebra(other),
    };
    ParseError::new(kind, input, span)
}

/// Lowers an operand (a number, an angle, a name, a call or a parenthesised expression) whose inner
/// expression, if any, is nested `depth` levels deep.
///
/// This function and [`call`] are on the path of the recursion through parentheses, so they keep few
/// locals: the leaves are lowered in [`leaf`].
fn lower_operand(pair: Pair<'_, Rule>, depth: usize) -> Lowered {
    match pair.as_rule() {
        Rule::call => call(pair, depth),
        Rule::paren => {
            let span = pair.as_span();
            let inner = first_expr(pair.clone())?;
            let expr = lower_at(inner, depth)?.expr;
            Ok(Spanned {
                expr,
                span: span.start()..span.end(),
            })
        }
        _ => leaf(pair),
    }
}

/// Lowers a number, an angle or a name.
#[inline(never)]
fn leaf(pair: Pair<'_, Rule>) -> Lowered {
    let input = pair.get_input();
    let s = pair.as_span();
    let span = s.start()..s.end();
    let err = |kind| Err(ParseError::new(kind, input, span.clone()));
    let expr = match pair.as_rule() {
        Rule::number => number(input, pair.as_str(), &span)?,
        Rule::degrees => {
            let digits = pair.as_str().trim_end_matches(names::DEG);
            let value = number(input, digits, &span)?;
            let per_degree = Expr::pi()
                .div(&Expr::int(180))
                .map_err(|e| algebra_error(input, e, span.clone()))?;
            &value * &per_degree
        }
        Rule::name => {
            let name = names::normalise(pair.as_str());
            if name == names::PI {
                Expr::pi()
            } else if name == names::DEG {
                return err(ParseErrorKind::MisplacedDeg);
            } else if names::function(&name).is_some() {
                return err(ParseErrorKind::FunctionWithoutArgument(name.into_owned()));
            } else if Symbol::spells_derivative(&name)
                && !matches!(
                    Symbol::coord_from_name(&name),
                    Some(Symbol::Coord {
                        order: 1..=MAX_READ_ORDER,
                        ..
                    })
                )
            {
                return err(ParseErrorKind::DerivativeOrder(name.into_owned()));
            } else {
                Expr::symbol(&name)
            }
        }
        _ => return err(ParseErrorKind::Expected(vec![super::Expected::Operand])),
    };
    Ok(Spanned { expr, span })
}

/// Lowers a `call` pair: the callee, then the argument nested `depth` levels deep.
fn call(pair: Pair<'_, Rule>, depth: usize) -> Lowered {
    let function = callee(&pair)?;
    let arg = lower_at(first_expr(pair.clone())?, depth)?;
    apply(pair, function, arg)
}

/// The function a `call` pair names, or the error for an unknown one.
#[inline(never)]
fn callee(pair: &Pair<'_, Rule>) -> Result<Function, ParseError> {
    let callee = pair
        .clone()
        .into_inner()
        .find(|p| p.as_rule() == Rule::callee);
    let Some(callee) = callee else {
        return Err(unexpected(pair));
    };
    names::function(callee.as_str()).ok_or_else(|| {
        let s = callee.as_span();
        let kind = ParseErrorKind::UnknownFunction(callee.as_str().to_string());
        ParseError::new(kind, pair.get_input(), s.start()..s.end())
    })
}

/// Applies a function to its lowered argument; `pair` is the call.
#[inline(never)]
fn apply(pair: Pair<'_, Rule>, function: Function, arg: Spanned) -> Lowered {
    let input = pair.get_input();
    let s = pair.as_span();
    let span = s.start()..s.end();
    let value = match function {
        Function::Sin => Ok(Expr::sin(&arg.expr)),
        Function::Cos => Ok(Expr::cos(&arg.expr)),
        Function::Sgn => Ok(Expr::sgn(&arg.expr)),
        Function::Tan => Expr::tan(&arg.expr),
        Function::Sqrt => Expr::sqrt(&arg.expr).map_err(|e| match e {
            // The user's own text reads better than the core's canonical form of it.
            AlgebraError::SqrtOfNonRational(_) => {
                AlgebraError::SqrtOfNonRational(input[arg.span.clone()].trim().to_string())
            }
            other => other,
        }),
    };
    let value = value.map_err(|e| algebra_error(input, e, span.clone()))?;
    Ok(Spanned {
        expr: checked(input, value, &span)?,
        span,
    })
}

/// The error for a pair the grammar does not put here (unreachable with `grammar/expr.pest`).
#[inline(never)]
fn unexpected(pair: &Pair<'_, Rule>) -> ParseError {
    let s = pair.as_span();
    ParseError::new(
        ParseErrorKind::Expected(vec![super::Expected::Operand]),
        pair.get_input(),
        s.start()..s.end(),
    )
}

/// The `expr` inside a call or a parenthesised expression.
fn first_expr(pair: Pair<'_, Rule>) -> Result<Pair<'_, Rule>, ParseError> {
    match pair
        .clone()
        .into_inner()
        .find(|p| p.as_rule() == Rule::expr)
    {
        Some(inner) => Ok(inner),
        None => Err(unexpected(&pair)),
    }
}

/// The exact value of a decimal literal, refusing ones too large to hold.
fn number(input: &str, text: &str, span: &Range<usize>) -> Result<Expr, ParseError> {
    let too_large = || ParseError::new(ParseErrorKind::NumberTooLarge, input, span.clone());
    let (mantissa, exponent) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], &text[i + 1..]),
        None => (text, ""),
    };
    let exponent_digits = exponent
        .trim_start_matches(['+', '-'])
        .trim_start_matches('0');
    // 10^k needs 3.3 k bits: bound the digits before anything is computed.
    let digit_budget = (MAX_NUMBER_BITS / 3) as usize;
    if exponent_digits.len() > 6 || mantissa.len() > digit_budget {
        return Err(too_large());
    }
    let e: usize = exponent_digits.parse().unwrap_or(0);
    if e > digit_budget {
        return Err(too_large());
    }
    let r = Rational::parse_decimal(text).ok_or_else(too_large)?;
    if bits(&r) > MAX_NUMBER_BITS {
        return Err(too_large());
    }
    Ok(Expr::num(r))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::grammar::Grammar;
    use pest::Parser;

    /// Lowers the `expr` at the start of `input`, which goes on with text that is no expression.
    fn lower_prefix(input: &str) -> Result<Expr, ParseError> {
        let pair = Grammar::parse(Rule::expr, input)
            .expect("an expression at the start")
            .next()
            .expect("one pair");
        lower_expr(pair)
    }

    #[test]
    fn an_expr_pair_inside_more_text() {
        let x = Expr::symbol("x");
        assert_eq!(lower_prefix("2 x, y").unwrap(), &Expr::int(2) * &x);
        assert_eq!(lower_prefix("x  # comment").unwrap(), x);
        let e = lower_prefix("1 + 1/0 ; more\nsecond line").unwrap_err();
        assert_eq!((e.line(), e.column()), (1, 7));
        assert_eq!(e.kind(), &ParseErrorKind::DivisionByZero);
        assert!(
            e.to_string().ends_with("  1 + 1/0 ; more\n        ^"),
            "{e}"
        );
    }
}
