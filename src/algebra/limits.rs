//! Size limits: one policy for every operation whose result can grow much faster than its input.
//!
//! A power `x^n`, an expansion `(a + b)^n`, a multiple angle `sin(n x)` and the reduction
//! `sin^n x = sin^(n mod 2) x (1 − cos² x)^(n div 2)` cost what their answers cost, and the answer can
//! be astronomically large for a short input (`2^99999999`, `sin(q1)^99999999`, `(a+b)^25` multiplied
//! out naively). Every such operation estimates its answer first, exactly or from above, and refuses
//! with a typed [`AlgebraError`] when the estimate passes a limit:
//!
//! - [`MAX_NUMBER_BITS`]: no number built by a power is larger than this, in bits of numerator plus
//!   denominator (about 600 decimal digits), also the parser's bound on a literal;
//! - [`MAX_TERMS`]: no expansion produces more terms than this before collecting them;
//! - [`MAX_EXPONENT`]: no exponent of a result is larger (then sums of exponents cannot overflow).
//!
//! The checked entry points are `Expr::pow`, [`Poly::try_pow`](super::Poly::try_pow),
//! [`try_to_poly`](super::normal::try_to_poly), [`simplify`](super::simplify()) and
//! [`expand`](super::expand()); `subs` and `eval_exact` go through them.

use super::error::AlgebraError;
use super::number::Rational;

/// The largest number a power may build, in bits of numerator plus denominator.
pub const MAX_NUMBER_BITS: u64 = 2048;

/// The most terms an expansion may produce before they are collected.
pub const MAX_TERMS: u128 = 1_000_000;

/// The largest exponent of a result.
pub const MAX_EXPONENT: u64 = i32::MAX as u64;

/// The bits of a rational's numerator and denominator.
pub fn bits(r: &Rational) -> u64 {
    match r.as_small() {
        Some((n, d)) => u64::from(128 - n.unsigned_abs().leading_zeros() - d.leading_zeros()),
        None => r.numer().bits() + r.denom().bits(),
    }
}

/// The bits by which the parts of `r` grow in a power: a numerator or denominator of ±1 does not.
pub fn growing_bits(r: &Rational) -> u64 {
    let part = |k: &num_bigint::BigInt| {
        if k.magnitude().bits() > 1 {
            k.bits()
        } else {
            0
        }
    };
    part(&r.numer()) + part(&r.denom())
}

/// An expression as an error names it: its parser syntax, cut short when long.
pub fn describe(e: &super::Expr) -> String {
    let text = e.to_string();
    match text.char_indices().nth(60) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text,
    }
}

/// `base^e` as an error names it, the base in parentheses unless it is a name, a call or a
/// natural number: `2^99`, `sin(q1)^9`, `(a + b)^25`.
pub fn power_text(base: &super::Expr, e: i64) -> String {
    use super::expr::Kind;
    let text = describe(base);
    match base.kind() {
        Kind::Sym(_) | Kind::Pi | Kind::Fun(..) => format!("{text}^{e}"),
        Kind::Num(r) if r.is_integer() && !r.is_negative() => format!("{text}^{e}"),
        _ => format!("({text})^{e}"),
    }
}

/// Refuses a number of about `bits` bits that `what` would build.
pub fn check_bits(what: impl FnOnce() -> String, bits: u128) -> Result<(), AlgebraError> {
    if bits > u128::from(MAX_NUMBER_BITS) {
        return Err(AlgebraError::NumberTooLarge {
            what: what(),
            bits: bits.to_string(),
        });
    }
    Ok(())
}

/// Refuses an expansion of about `terms` terms that `what` would produce.
pub fn check_terms(what: impl FnOnce() -> String, terms: u128) -> Result<(), AlgebraError> {
    if terms > MAX_TERMS {
        return Err(AlgebraError::TooManyTerms {
            what: what(),
            terms: terms.to_string(),
        });
    }
    Ok(())
}

/// `C(n + k, k)`, the number of ways to write `n` as a sum of `k + 1` non-negative parts (the terms of
/// a multinomial expansion), saturating at `u128::MAX`.
pub fn compositions(n: u64, k: u64) -> u128 {
    let (n, k) = if k > n { (k, n) } else { (n, k) };
    let mut c: u128 = 1;
    for i in 1..=u128::from(k) {
        // c · (n + i) / i stays exact: c is C(n + i − 1, i − 1), and i divides C(n + i − 1, i − 1)·(n + i).
        let Some(next) = c.checked_mul(u128::from(n) + i) else {
            return u128::MAX;
        };
        c = next / i;
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_bits() {
        assert_eq!(compositions(2, 1), 3); // (a+b)^2: 3 terms
        assert_eq!(compositions(25, 1), 26);
        assert_eq!(compositions(3, 2), 10); // (a+b+c)^3
        assert_eq!(compositions(0, 5), 1);
        assert_eq!(compositions(1, 5), 6); // (a+b+c+d+e+f)^1
        assert_eq!(compositions(5, 1), 6);
        assert_eq!(compositions(1_000_000_000, 100), u128::MAX);
        assert_eq!(bits(&Rational::int(8)), 5);
        assert_eq!(growing_bits(&Rational::new(1, 8).unwrap()), 4);
        assert_eq!(growing_bits(&Rational::int(-1)), 0);
        assert!(check_terms(|| "x".into(), MAX_TERMS + 1).is_err());
        assert!(check_bits(|| "x".into(), u128::from(MAX_NUMBER_BITS)).is_ok());
    }
}
