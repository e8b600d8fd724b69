//! Exact rational numbers: the coefficients of every expression.
//!
//! A [`Rational`] is a fraction in lowest terms with a positive denominator. Small values live in two
//! `i64`s (the fast path: almost every coefficient of a robot model is small); anything that would
//! overflow moves to a `BigRational`, so no computation ever overflows or rounds. The representation is
//! private and canonical: a value that fits the small form is always stored in it, so derived equality
//! and hashing are value equality.

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::fmt;

/// An exact rational number in lowest terms.
#[derive(Clone, PartialEq, Eq)]
pub struct Rational(Repr);

#[derive(Clone, PartialEq, Eq)]
enum Repr {
    /// numerator, denominator (> 0), coprime.
    Small(i64, i64),
    /// Only values that do not fit `Small` (boxed, so a coefficient stays three words).
    Big(Box<BigRational>),
}

/// Greatest common divisor of two `u128`s: the `u64` path when both fit, else the binary loop in
/// 128 bits (no 128-bit division, which is a library call).
#[inline]
fn gcd_u128(a: u128, b: u128) -> u128 {
    match (u64::try_from(a), u64::try_from(b)) {
        (Ok(x), Ok(y)) => gcd_u64(x, y) as u128,
        // One step of Euclid's algorithm brings the wide one below the other (a division by a
        // 64-bit divisor, where the binary loop would take a step for each bit of the difference).
        (Err(_), Ok(y)) if y != 0 => gcd_u64(y, (a % b) as u64) as u128,
        (Ok(x), Err(_)) if x != 0 => gcd_u64(x, (b % a) as u64) as u128,
        _ => binary_gcd(a, b),
    }
}

/// `x / g` for a divisor `g` of `x`, in 64 bits when both fit (128-bit division is a library call).
#[inline]
fn div_exact(x: i128, g: u128) -> i128 {
    match (i64::try_from(x), i64::try_from(g)) {
        (Ok(x), Ok(g)) => (x / g) as i128,
        _ => x / g as i128,
    }
}

impl Rational {
    /// The integer `n`.
    pub fn int(n: i64) -> Rational {
        Rational(Repr::Small(n, 1))
    }

    /// Zero.
    pub fn zero() -> Rational {
        Rational::int(0)
    }

    /// One.
    pub fn one() -> Rational {
        Rational::int(1)
    }

    /// `num/den`, reduced. Returns `None` when `den` is zero.
    pub fn new(num: i64, den: i64) -> Option<Rational> {
        if den == 0 {
            return None;
        }
        Some(Rational::from_i128(num as i128, den as i128))
    }

    fn from_i128(num: i128, den: i128) -> Rational {
        debug_assert!(den != 0);
        let g = gcd_u128(num.unsigned_abs(), den.unsigned_abs()).max(1);
        let (mut n, mut d) = if g == 1 {
            (num, den)
        } else {
            (div_exact(num, g), div_exact(den, g))
        };
        if d < 0 {
            n = -n;
            d = -d;
        }
        Rational::from_reduced_i128(n, d)
    }

    /// `num/den` already in lowest terms with `den > 0`: the small form when both fit.
    #[inline]
    fn from_reduced_i128(num: i128, den: i128) -> Rational {
        debug_assert!(den > 0);
        match (i64::try_from(num), i64::try_from(den)) {
            (Ok(n), Ok(d)) => Rational(Repr::Small(n, d)),
            _ => Rational(Repr::Big(Box::new(BigRational::new_raw(
                BigInt::from(num),
                BigInt::from(den),
            )))),
        }
    }

    /// From a big rational, normalising to the small form when it fits.
    pub fn from_big(r: BigRational) -> Rational {
        if let (Some(n), Some(d)) = (r.numer().to_i64(), r.denom().to_i64()) {
            return Rational(Repr::Small(n, d));
        }
        Rational(Repr::Big(Box::new(r)))
    }

    /// From big integers `num/den`; `None` when `den` is zero.
    pub fn from_bigints(num: BigInt, den: BigInt) -> Option<Rational> {
        if den.is_zero() {
            return None;
        }
        Some(Rational::from_big(BigRational::new(num, den)))
    }

    /// The value as a `BigRational`.
    pub fn to_big(&self) -> BigRational {
        match &self.0 {
            Repr::Small(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Repr::Big(r) => (**r).clone(),
        }
    }

    /// The numerator (sign included).
    pub fn numer(&self) -> BigInt {
        match &self.0 {
            Repr::Small(n, _) => BigInt::from(*n),
            Repr::Big(r) => r.numer().clone(),
        }
    }

    /// The denominator (always positive).
    pub fn denom(&self) -> BigInt {
        match &self.0 {
            Repr::Small(_, d) => BigInt::from(*d),
            Repr::Big(r) => r.denom().clone(),
        }
    }

    /// The numerator and denominator when both fit in `i64`.
    pub fn as_small(&self) -> Option<(i64, i64)> {
        match self.0 {
            Repr::Small(n, d) => Some((n, d)),
            Repr::Big(_) => None,
        }
    }

    /// `2 · self`, without a gcd: a fraction in lowest terms doubled halves an even denominator, or
    /// doubles the numerator over an odd one (which then shares no factor 2 with it).
    pub fn double(&self) -> Rational {
        match self.0 {
            Repr::Small(n, d) if d % 2 == 0 => Rational(Repr::Small(n, d / 2)),
            Repr::Small(n, d) => match n.checked_mul(2) {
                Some(n) => Rational(Repr::Small(n, d)),
                None => Rational::from_reduced_i128(2 * n as i128, d as i128),
            },
            Repr::Big(_) => self * &Rational::int(2),
        }
    }

    /// `self / 2`, without a gcd: a fraction in lowest terms halved halves an even numerator, or
    /// doubles the denominator under an odd one (which then shares no factor 2 with it).
    pub fn half(&self) -> Rational {
        match self.0 {
            Repr::Small(n, d) if n % 2 == 0 => Rational(Repr::Small(n / 2, d)),
            Repr::Small(n, d) => match d.checked_mul(2) {
                Some(d) => Rational(Repr::Small(n, d)),
                None => Rational::from_reduced_i128(n as i128, 2 * d as i128),
            },
            Repr::Big(_) => self * &Rational::new(1, 2).expect("a denominator of 2"),
        }
    }

    /// Whether this is zero.
    pub fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Small(0, _))
    }

    /// Whether this is one.
    pub fn is_one(&self) -> bool {
        matches!(self.0, Repr::Small(1, 1))
    }

    /// Whether this is minus one.
    pub fn is_minus_one(&self) -> bool {
        matches!(self.0, Repr::Small(-1, 1))
    }

    /// Whether this is an integer.
    pub fn is_integer(&self) -> bool {
        match &self.0 {
            Repr::Small(_, d) => *d == 1,
            Repr::Big(r) => r.is_integer(),
        }
    }

    /// The value as an `i64` when it is an integer that fits.
    pub fn to_i64(&self) -> Option<i64> {
        match self.0 {
            Repr::Small(n, 1) => Some(n),
            _ => None,
        }
    }

    /// Whether this is negative.
    pub fn is_negative(&self) -> bool {
        match &self.0 {
            Repr::Small(n, _) => *n < 0,
            Repr::Big(r) => r.is_negative(),
        }
    }

    /// The absolute value.
    pub fn abs(&self) -> Rational {
        if self.is_negative() {
            -self
        } else {
            self.clone()
        }
    }

    /// The nearest `f64`.
    pub fn to_f64(&self) -> f64 {
        match &self.0 {
            Repr::Small(n, d) => *n as f64 / *d as f64,
            Repr::Big(r) => {
                // Scale so that both parts fit comfortably in f64 range.
                let n = r.numer().to_f64().unwrap_or(f64::NAN);
                let d = r.denom().to_f64().unwrap_or(f64::NAN);
                if n.is_finite() && d.is_finite() {
                    n / d
                } else {
                    let bits = r.numer().bits().max(r.denom().bits()) as i64 - 1000;
                    let shift = bits.max(0) as usize;
                    let n = (r.numer() >> shift).to_f64().unwrap_or(0.0);
                    let d = (r.denom() >> shift).to_f64().unwrap_or(f64::INFINITY);
                    n / d
                }
            }
        }
    }

    /// The reciprocal; `None` for zero.
    pub fn recip(&self) -> Option<Rational> {
        if self.is_zero() {
            return None;
        }
        Some(match &self.0 {
            Repr::Small(n, d) => Rational::from_i128(*d as i128, *n as i128),
            Repr::Big(r) => Rational::from_big(r.recip()),
        })
    }

    /// `self^e` for an integer exponent; `None` for `0^e` with `e < 0`.
    pub fn pow(&self, e: i64) -> Option<Rational> {
        if e < 0 {
            return self.recip()?.pow(-e);
        }
        let mut base = self.clone();
        let mut acc = Rational::one();
        let mut e = e as u64;
        while e > 0 {
            if e & 1 == 1 {
                acc = &acc * &base;
            }
            e >>= 1;
            if e > 0 {
                base = &base * &base;
            }
        }
        Some(acc)
    }

    /// The exact square root, if this rational is the square of one (`9/4` gives `3/2`); `None` for a
    /// negative value or a non-square (numerator and denominator are coprime, so both must be
    /// squares).
    pub fn sqrt_exact(&self) -> Option<Rational> {
        if self.is_negative() {
            return None;
        }
        if let Repr::Small(n, d) = self.0 {
            // In 64 bits: the roots of coprime squares are coprime, so the result is reduced.
            return Some(Rational::from_reduced_i128(
                i128::from(sqrt_u64(n as u64)?),
                i128::from(sqrt_u64(d as u64)?),
            ));
        }
        let root = |n: BigInt| {
            let s = num_integer::Roots::sqrt(&n);
            (&s * &s == n).then_some(s)
        };
        Rational::from_bigints(root(self.numer())?, root(self.denom())?)
    }

    /// Greatest common divisor of two rationals: gcd of numerators over lcm of denominators (positive).
    pub fn gcd(&self, other: &Rational) -> Rational {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &other.0) {
            // Numerators' gcd over the denominators' lcm, in 128 bits: `b/g · d` < 2¹²⁶, and the
            // quotient is coprime to that lcm (each prime of it divides a denominator, so not both
            // numerators), so only the small-or-big choice is left.
            let n = gcd_u64(a.unsigned_abs(), c.unsigned_abs());
            if n == 0 {
                return Rational::zero();
            }
            let (b, d) = (*b as u64, *d as u64);
            let lcm = u128::from(b / gcd_u64(b, d)) * u128::from(d);
            return Rational::from_reduced_i128(n as i128, lcm as i128);
        }
        let n = self.numer().gcd(&other.numer());
        let d = self.denom().lcm(&other.denom());
        if n.is_zero() {
            return Rational::zero();
        }
        Rational::from_big(BigRational::new(n, d))
    }

    /// Exact value of a decimal literal such as `0.4318` or `1.2e-3`; `None` if it is not one.
    pub fn parse_decimal(text: &str) -> Option<Rational> {
        let (mantissa, exponent) = match text.find(['e', 'E']) {
            Some(i) => (&text[..i], text[i + 1..].parse::<i64>().ok()?),
            None => (text, 0),
        };
        let (int_part, frac_part) = match mantissa.find('.') {
            Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
            None => (mantissa, ""),
        };
        if int_part.is_empty() && frac_part.is_empty() {
            return None;
        }
        if !int_part
            .bytes()
            .chain(frac_part.bytes())
            .all(|b| b.is_ascii_digit())
        {
            return None;
        }
        let scale = exponent.checked_sub(frac_part.len() as i64)?;
        // The decimals of a scene (`0.0825`, `-1.5707963`, `3e-3`) fit a machine word: no big
        // integers then.
        if int_part.len() + frac_part.len() <= 18 && scale.unsigned_abs() <= 18 {
            let num = int_part
                .bytes()
                .chain(frac_part.bytes())
                .fold(0i64, |n, b| n * 10 + i64::from(b - b'0'));
            let power = 10i64.pow(scale.unsigned_abs() as u32);
            return Some(if scale >= 0 {
                Rational::from_i128(i128::from(num) * i128::from(power), 1)
            } else {
                Rational::from_i128(i128::from(num), i128::from(power))
            });
        }
        let digits = format!("{int_part}{frac_part}");
        let num: BigInt = digits.parse().ok()?;
        if scale.unsigned_abs() > 100_000 {
            return None;
        }
        let ten = BigInt::from(10);
        let value = if scale >= 0 {
            BigRational::from_integer(num * num_traits::pow(ten, scale as usize))
        } else {
            BigRational::new(num, num_traits::pow(ten, (-scale) as usize))
        };
        Some(Rational::from_big(value))
    }
}

impl std::hash::Hash for Rational {
    /// Hashes numerator and denominator directly (the form is canonical, so this is value hashing;
    /// `BigRational`'s own hash recurses through a continued fraction and can exhaust the stack).
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        match &self.0 {
            Repr::Small(n, d) => {
                state.write_u8(0);
                state.write_i64(*n);
                state.write_i64(*d);
            }
            Repr::Big(r) => {
                state.write_u8(1);
                r.numer().hash(state);
                r.denom().hash(state);
            }
        }
    }
}

impl Default for Rational {
    fn default() -> Self {
        Rational::zero()
    }
}

impl From<i64> for Rational {
    fn from(n: i64) -> Self {
        Rational::int(n)
    }
}

impl From<BigInt> for Rational {
    fn from(n: BigInt) -> Self {
        Rational::from_big(BigRational::from_integer(n))
    }
}

impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        match (&self.0, &other.0) {
            (Repr::Small(a, b), Repr::Small(c, d)) => {
                ((*a as i128) * (*d as i128)).cmp(&((*c as i128) * (*b as i128)))
            }
            _ => self.to_big().cmp(&other.to_big()),
        }
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Greatest common divisor of two `u64`s.
#[inline]
/// The square root of `n` when `n` is a perfect square.
fn sqrt_u64(n: u64) -> Option<u64> {
    // The float's root is within one of the integer root (a 53-bit mantissa); corrected by
    // exact integer steps.
    let mut s = (n as f64).sqrt() as u64;
    while s.checked_mul(s).is_none_or(|sq| sq > n) {
        s -= 1;
    }
    while (s + 1).checked_mul(s + 1).is_some_and(|sq| sq <= n) {
        s += 1;
    }
    (s * s == n).then_some(s)
}

fn gcd_u64(a: u64, b: u64) -> u64 {
    if a == 1 || b == 1 {
        // Integers and unit numerators are most coefficients; the loop would take a step a bit.
        return 1;
    }
    // The binary loop takes a step for each bit by which the longer is longer than the other (a
    // decimal coefficient's `/3125000000000000` times ½: some fifty steps). Past a byte of
    // difference, one step of Euclid's algorithm (one division) first brings it below the other.
    if (a | b) >> 16 != 0 {
        let (small, large) = if a <= b { (a, b) } else { (b, a) };
        if small != 0 && large.leading_zeros() + 8 < small.leading_zeros() {
            return binary_gcd(small, large % small);
        }
    }
    binary_gcd(a, b)
}

/// Greatest common divisor by the binary algorithm (shifts and subtractions, no division).
#[inline]
fn binary_gcd<T: num_traits::PrimInt>(mut a: T, mut b: T) -> T {
    if a.is_zero() {
        return b;
    }
    if b.is_zero() {
        return a;
    }
    let shift = (a | b).trailing_zeros() as usize;
    a = a >> a.trailing_zeros() as usize;
    loop {
        b = b >> b.trailing_zeros() as usize;
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b = b - a;
        if b.is_zero() {
            return a << shift;
        }
    }
}

/// `a/b · c/d` for reduced small fractions: cross-cancel in 64 bits, then multiply. The cancelled
/// product is in lowest terms, so a product past 64 bits needs no 128-bit gcd.
#[inline]
fn mul_small(a: i64, b: i64, c: i64, d: i64) -> Option<Rational> {
    if a == 0 || c == 0 {
        return Some(Rational::zero());
    }
    // A factor 1 (a monomial's coefficient, as a rule): the other, already reduced.
    if c == 1 && d == 1 {
        return Some(Rational(Repr::Small(a, b)));
    }
    if a == 1 && b == 1 {
        return Some(Rational(Repr::Small(c, d)));
    }
    if b == 1 && d == 1 {
        if let Some(n) = a.checked_mul(c) {
            return Some(Rational(Repr::Small(n, 1)));
        }
        return Some(Rational::from_reduced_i128(a as i128 * c as i128, 1));
    }
    let g1 = gcd_u64(a.unsigned_abs(), d as u64) as i64;
    let g2 = gcd_u64(c.unsigned_abs(), b as u64) as i64;
    let (a, c, b, d) = (a / g1, c / g2, b / g2, d / g1);
    match (a.checked_mul(c), b.checked_mul(d)) {
        (Some(n), Some(den)) => Some(Rational(Repr::Small(n, den))),
        _ => Some(Rational::from_reduced_i128(
            a as i128 * c as i128,
            b as i128 * d as i128,
        )),
    }
}

/// `a/b + c/d` for reduced small fractions (Henrici): with `g = gcd(b, d)`, the sum is
/// `t / (b/g · d)` for `t = a·(d/g) + c·(b/g)`, and only `gcd(t, g)` can cancel. Sums past 64 bits
/// stay exact in 128.
#[inline]
fn add_small(a: i64, b: i64, c: i64, d: i64) -> Option<Rational> {
    if b == d {
        let n = a as i128 + c as i128;
        if n == 0 {
            return Some(Rational::zero());
        }
        if b == 1 {
            return Some(Rational::from_reduced_i128(n, 1));
        }
        let g = gcd_u128(n.unsigned_abs(), b as u128);
        return Some(Rational::from_reduced_i128(
            div_exact(n, g),
            (b as u128 / g) as i128,
        ));
    }
    let g = gcd_u64(b as u64, d as u64);
    let (bg, dg) = (b as i128 / g as i128, d as i128 / g as i128);
    let t = a as i128 * dg + c as i128 * bg;
    if t == 0 {
        return Some(Rational::zero());
    }
    if g == 1 {
        return Some(Rational::from_reduced_i128(t, b as i128 * d as i128));
    }
    let r = match u64::try_from(t.unsigned_abs()) {
        Ok(t) => t % g,
        Err(_) => (t.unsigned_abs() % g as u128) as u64,
    };
    let g2 = gcd_u64(r, g);
    Some(Rational::from_reduced_i128(
        div_exact(t, g2 as u128),
        bg * (d as i128 / g2 as i128),
    ))
}

macro_rules! binop {
    ($trait:ident, $method:ident, $fast:expr, $small:expr, $big:expr) => {
        impl std::ops::$trait<&Rational> for &Rational {
            type Output = Rational;
            fn $method(self, rhs: &Rational) -> Rational {
                if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &rhs.0) {
                    let fast: fn(i64, i64, i64, i64) -> Option<Rational> = $fast;
                    if let Some(r) = fast(*a, *b, *c, *d) {
                        return r;
                    }
                    let f: fn(i128, i128, i128, i128) -> Option<(i128, i128)> = $small;
                    if let Some((n, d)) = f(*a as i128, *b as i128, *c as i128, *d as i128) {
                        return Rational::from_i128(n, d);
                    }
                }
                let g: fn(BigRational, BigRational) -> BigRational = $big;
                Rational::from_big(g(self.to_big(), rhs.to_big()))
            }
        }
        impl std::ops::$trait<Rational> for Rational {
            type Output = Rational;
            fn $method(self, rhs: Rational) -> Rational {
                std::ops::$trait::$method(&self, &rhs)
            }
        }
    };
}

binop!(
    Add,
    add,
    add_small,
    |a, b, c, d| Some((
        a.checked_mul(d)?.checked_add(c.checked_mul(b)?)?,
        b.checked_mul(d)?
    )),
    |x, y| x + y
);
binop!(
    Sub,
    sub,
    |a, b, c, d| add_small(a, b, c.checked_neg()?, d),
    |a, b, c, d| Some((
        a.checked_mul(d)?.checked_sub(c.checked_mul(b)?)?,
        b.checked_mul(d)?
    )),
    |x, y| x - y
);
binop!(
    Mul,
    mul,
    mul_small,
    |a, b, c, d| Some((a.checked_mul(c)?, b.checked_mul(d)?)),
    |x, y| x * y
);

impl std::ops::Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        match &self.0 {
            Repr::Small(n, d) => match n.checked_neg() {
                Some(m) => Rational(Repr::Small(m, *d)),
                None => Rational::from_i128(-(*n as i128), *d as i128),
            },
            Repr::Big(r) => Rational::from_big(-(**r).clone()),
        }
    }
}

impl std::ops::Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        -&self
    }
}

impl std::ops::AddAssign<&Rational> for Rational {
    fn add_assign(&mut self, rhs: &Rational) {
        *self = &*self + rhs;
    }
}

impl fmt::Display for Rational {
    /// `n` or `n/d`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Small(n, 1) => write!(f, "{n}"),
            Repr::Small(n, d) => write!(f, "{n}/{d}"),
            Repr::Big(r) if r.is_integer() => write!(f, "{}", r.numer()),
            Repr::Big(r) => write!(f, "{}/{}", r.numer(), r.denom()),
        }
    }
}

impl fmt::Debug for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

/// The largest `k` with `k^2 | n` and the square-free rest: `n = k^2 * rest`. `n` must be positive.
pub fn split_square(n: &BigInt) -> (BigInt, BigInt) {
    debug_assert!(n.is_positive());
    let mut k = BigInt::one();
    let mut rest = n.clone();
    // Trial division is enough for the radicands a robot model meets (2, 3, 6, ...). Beyond a bound the
    // remainder is kept as is: still exact, merely not fully reduced.
    let mut p = BigInt::from(2);
    let bound = BigInt::from(100_000);
    while &p * &p <= rest && p < bound {
        let sq = &p * &p;
        while (&rest % &sq).is_zero() {
            rest /= &sq;
            k *= &p;
        }
        p += 1;
    }
    // What is left has no square factor below the bound; it may still be a perfect square.
    let root = num_integer::Roots::sqrt(&rest);
    if &root * &root == rest {
        return (k * root, BigInt::one());
    }
    (k, rest)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Doubling and halving without a gcd give the products by 2 and ½, in lowest terms and in the
    /// same representation: zero, units, even and odd numerators and denominators, both signs,
    /// the ends of 64 bits (where the result no longer fits) and a big fraction.
    #[test]
    fn doubling_and_halving_are_the_products_by_two_and_a_half() {
        let (two, half) = (Rational::int(2), r(1, 2));
        let big = Rational::from_bigints(BigInt::from(i64::MAX) * 3, BigInt::from(7)).unwrap();
        let mut values = vec![Rational::zero(), Rational::one(), big.clone(), -&big];
        for n in [1, 2, 3, 6, 9, 1 << 40, i64::MAX, i64::MAX - 1, i64::MIN + 1] {
            for d in [1, 2, 4, 5, 12, 3 << 30, i64::MAX, i64::MAX - 1] {
                if let Some(q) = Rational::new(n, d) {
                    values.push(-&q);
                    values.push(q);
                }
            }
        }
        for q in &values {
            assert_eq!(q.double(), q * &two, "2 · {q}");
            assert_eq!(q.half(), q * &half, "{q} / 2");
        }
    }

    fn r(n: i64, d: i64) -> Rational {
        Rational::new(n, d).unwrap()
    }

    #[test]
    fn arithmetic_is_exact_and_reduced() {
        assert_eq!(&r(1, 3) + &r(1, 6), r(1, 2));
        assert_eq!(&r(17, 192) + &r(1, 4), r(65, 192));
        assert_eq!(&r(2, 4) * &r(2, 1), Rational::one());
        assert_eq!(r(3, -6), r(-1, 2));
    }

    #[test]
    fn exact_square_roots_only_of_squares() {
        assert_eq!(r(9, 4).sqrt_exact(), Some(r(3, 2)));
        assert_eq!(Rational::zero().sqrt_exact(), Some(Rational::zero()));
        assert_eq!(r(25, 1).sqrt_exact(), Some(r(5, 1)));
        assert_eq!(r(2, 1).sqrt_exact(), None);
        assert_eq!(r(9, 8).sqrt_exact(), None);
        assert_eq!(r(-4, 1).sqrt_exact(), None);
        let big =
            Rational::from_bigints(BigInt::from(3).pow(80u32), BigInt::from(7).pow(40u32)).unwrap();
        let root = Rational::from_bigints(BigInt::from(3).pow(40u32), BigInt::from(7).pow(20u32));
        assert_eq!(big.sqrt_exact(), root);
        // The 64-bit path against the big integers' roots, about squares and at the ends.
        for n in (0..2000u64).chain([u64::from(u32::MAX) * u64::from(u32::MAX), i64::MAX as u64]) {
            let general = num_integer::Roots::sqrt(&BigInt::from(n));
            let want = (&general * &general == BigInt::from(n))
                .then(|| u64::try_from(general).expect("a root of a u64"));
            assert_eq!(sqrt_u64(n), want, "{n}");
        }
        for (n, d) in [
            (4, 9),
            (49, 64),
            (3, 4),
            (i64::MAX, 1),
            (1, 3037000499 * 3037000499),
        ] {
            let x = r(n, d);
            let general = Rational::from_bigints(
                num_integer::Roots::sqrt(&x.numer()),
                num_integer::Roots::sqrt(&x.denom()),
            )
            .filter(|y| y * y == x);
            assert_eq!(x.sqrt_exact(), general, "{n}/{d}");
        }
    }

    #[test]
    fn small_fast_paths_agree_with_the_general_path() {
        let values = [
            r(0, 1),
            r(1, 1),
            r(-1, 1),
            r(1, 2),
            r(-3, 4),
            r(5, 6),
            r(7, 12),
            r(-12, 35),
            r(i64::MAX, 1),
            r(i64::MIN, 1),
            r(1, i64::MAX),
            r(-1, i64::MAX),
        ];
        for x in &values {
            for y in &values {
                let (xb, yb) = (x.to_big(), y.to_big());
                assert_eq!((x + y).to_big(), &xb + &yb, "{x} + {y}");
                assert_eq!((x - y).to_big(), &xb - &yb, "{x} - {y}");
                assert_eq!((x * y).to_big(), &xb * &yb, "{x} * {y}");
                assert_eq!(x * y, Rational::from_big(&xb * &yb), "{x} * {y} canonical");
                assert_eq!(x + y, Rational::from_big(&xb + &yb), "{x} + {y} canonical");
            }
            assert_eq!((-x).to_big(), -x.to_big());
        }
    }

    /// Numerators and denominators that reach every path: small, near 2^63, and products of powers
    /// of 2, 3 and 10 (decimal parameters share large factors, so their sums cancel).
    fn part() -> impl proptest::strategy::Strategy<Value = i64> {
        use proptest::prelude::*;
        prop_oneof![
            -50i64..50,
            any::<i64>(),
            (0u32..62, 0u32..39, 0u32..18).prop_map(|(a, b, c)| {
                2i64.checked_pow(a)
                    .and_then(|x| x.checked_mul(3i64.checked_pow(b)?))
                    .and_then(|x| x.checked_mul(10i64.checked_pow(c)?))
                    .unwrap_or(7)
            }),
            (i64::MAX - 100..=i64::MAX),
        ]
    }

    proptest::proptest! {
        #[test]
        fn arithmetic_agrees_with_big_rationals(
            a in part(), b in part(), c in part(), d in part(), negate in proptest::bool::ANY
        ) {
            let positive = |n: i64| n.unsigned_abs().clamp(1, i64::MAX as u64) as i64;
            let (b, d) = (positive(b), positive(d));
            let a = if negate { a.saturating_neg() } else { a };
            let (x, y) = (r(a, b), r(c, d));
            let (xb, yb) = (x.to_big(), y.to_big());
            let gcd = Rational::from_big(BigRational::new(
                Integer::gcd(xb.numer(), yb.numer()),
                Integer::lcm(xb.denom(), yb.denom()),
            ));
            proptest::prop_assert_eq!(x.gcd(&y), gcd, "gcd({}, {})", x, y);
            for (got, want, op) in [(&x + &y, &xb + &yb, "+"), (&x - &y, &xb - &yb, "-"), (&x * &y, &xb * &yb, "*")] {
                proptest::prop_assert_eq!(got.to_big(), want.clone(), "{} {} {}", x, op, y);
                // Canonical: a value that fits the small form is stored in it.
                proptest::prop_assert_eq!(got, Rational::from_big(want), "{} {} {} canonical", x, op, y);
            }
        }

        #[test]
        fn gcd_of_128_and_64_bits(
            g in proptest::num::u32::ANY, x in proptest::num::u64::ANY, y in 0u64..1000, k in 0u32..32
        ) {
            // A common factor `g` (up to 63 bits with `k` more twos) times cofactors of any size.
            let g = (g as u128) << k;
            for (a, b) in [(g * x as u128, g * y as u128), (x as u128, y as u128), (g, 0)] {
                let want = num_integer::Integer::gcd(&a, &b);
                proptest::prop_assert_eq!(gcd_u128(a, b), want);
                proptest::prop_assert_eq!(gcd_u128(b, a), want);
            }
            // 64 bits, of any lengths: a small one and a long one take Euclid's step first.
            let (a, b) = (x >> (k + k), y << k);
            let want = num_integer::Integer::gcd(&a, &b);
            proptest::prop_assert_eq!(gcd_u64(a, b), want);
            proptest::prop_assert_eq!(gcd_u64(b, a), want);
        }
    }

    #[test]
    fn huge_fractions_hash_without_recursion() {
        use std::hash::{Hash, Hasher};
        let big = r(3, 7).pow(20_000).unwrap();
        let mut h = std::collections::hash_map::DefaultHasher::new();
        big.hash(&mut h);
        let _ = h.finish();
    }

    #[test]
    fn overflow_moves_to_big_and_back() {
        let big = Rational::int(i64::MAX);
        let sq = &big * &big;
        assert!(sq.as_small().is_none());
        let back = &sq * &big.recip().unwrap();
        assert_eq!(back, big);
        assert!(back.as_small().is_some());
    }

    #[test]
    fn decimals_are_exact() {
        assert_eq!(Rational::parse_decimal("0.4318"), Some(r(2159, 5000)));
        assert_eq!(Rational::parse_decimal("1.2e-3"), Some(r(3, 2500)));
        assert_eq!(Rational::parse_decimal("90"), Some(Rational::int(90)));
        assert_eq!(Rational::parse_decimal("1e2"), Some(Rational::int(100)));
        assert_eq!(Rational::parse_decimal("."), None);
    }

    /// Short decimals take machine words, long ones big integers: both give the value that big
    /// integers give, at the boundary (18 digits, a scale of ±18) and past it.
    #[test]
    fn short_and_long_decimals_are_the_same_values() {
        fn by_big_integers(text: &str) -> Rational {
            let (mantissa, exponent) = match text.find(['e', 'E']) {
                Some(i) => (&text[..i], text[i + 1..].parse::<i64>().unwrap()),
                None => (text, 0),
            };
            let (int_part, frac_part) = mantissa.split_once('.').unwrap_or((mantissa, ""));
            let num: BigInt = format!("{int_part}{frac_part}").parse().unwrap();
            let scale = exponent - frac_part.len() as i64;
            let ten = BigInt::from(10);
            Rational::from_big(if scale >= 0 {
                BigRational::from_integer(num * num_traits::pow(ten, scale as usize))
            } else {
                BigRational::new(num, num_traits::pow(ten, (-scale) as usize))
            })
        }
        let mut checked = 0;
        for mantissa in [
            "0",
            "000",
            "7",
            "0.0825",
            "1.5707963",
            "0.000000000000000001",
            "123456789.123456789",
            "999999999999999999",
            "9999999999999999999",
            "12345678901234567890.5",
            ".5",
            "5.",
        ] {
            for exponent in [
                "", "e0", "e3", "e-3", "E17", "e-18", "e18", "e-19", "e19", "e-40",
            ] {
                let text = format!("{mantissa}{exponent}");
                assert_eq!(
                    Rational::parse_decimal(&text),
                    Some(by_big_integers(&text)),
                    "{text}"
                );
                checked += 1;
            }
        }
        assert_eq!(checked, 120);
    }

    #[test]
    fn powers_and_square_parts() {
        assert_eq!(r(2, 3).pow(-2), Some(r(9, 4)));
        assert_eq!(Rational::zero().pow(-1), None);
        assert_eq!(
            split_square(&BigInt::from(12)),
            (BigInt::from(2), BigInt::from(3))
        );
        assert_eq!(
            split_square(&BigInt::from(2)),
            (BigInt::from(1), BigInt::from(2))
        );
    }
}
