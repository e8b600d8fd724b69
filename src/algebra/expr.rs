//! The canonical expression: immutable, shared, and in normal form from the moment it is built.
//!
//! An [`Expr`] is an `Arc` to a node whose [`Kind`] can be read but never built directly: every value
//! comes from the normalising constructors in this module (`Expr::num`, `+`, `*`, [`Expr::pow`],
//! [`Expr::sin`], ...). The canonical rules, each with one example (each is a row of the tests below):
//!
//! 1. Numbers are exact rationals in lowest terms: `2/4` is `1/2`.
//! 2. Sums are flat and collect like terms: `x + (y + x)` is `2 x + y`; `x - x` is `0`.
//! 3. A sum is a rational constant plus terms with non-zero rational coefficients; a term is never a
//!    number, a sum or a product with a coefficient: `2 (x y) + 3` stores term `x y` with coefficient 2.
//! 4. Products are flat and collect powers of equal bases: `x * (x * y)` is `x^2 y`; `x / x` is `1`.
//! 5. A product is a non-zero rational coefficient times bases with non-zero integer exponents; a
//!    number times a single sum distributes: `2 (x + y)` is `2 x + 2 y`.
//! 6. A one-term sum or one-factor product collapses: `x + 0` and `1 x^1` are `x`.
//! 7. Square roots are of square-free integers, at most one per product: `sqrt(12)` is `2 sqrt(3)`,
//!    `sqrt(2) sqrt(6)` is `2 sqrt(3)`, `1/sqrt(2)` is `sqrt(2)/2`.
//! 8. `sin` and `cos` take the sign and the multiples of π/2 out of their argument (see `trig_values`):
//!    `sin(-x)` is `-sin(x)`, `cos(x + pi/2)` is `-sin(x)`, `cos(pi/3)` is `1/2`.
//!
//! Terms and factors are kept sorted by [`Expr::cmp`], a total order on structure and names (never on
//! hashes or creation order), so equal mathematics built in any order prints the same text.
//!
//! Structural equality is decidable here and cheap; equality *as functions* (`sin^2 + cos^2 = 1`) is the
//! job of the normal form in `normal`.

use super::error::AlgebraError;
use super::number::{split_square, Rational};
use super::symbol::Symbol;
use super::trig_values;
use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive};
use std::cmp::Ordering;
use std::hash::{Hash, Hasher};
use std::sync::Arc;

/// A canonical expression. Cheap to clone (reference counted), immutable.
#[derive(Clone)]
pub struct Expr(Arc<Node>);

struct Node {
    /// The node's hash in the low 58 bits, and in the top 6 its place among bases before its
    /// structure is looked at ([`order_key`], below 64), both computed once in [`Expr::make`]:
    /// comparing two parameters otherwise classes both names every time. (In one word, the node
    /// stays 64 bytes.)
    hash: u64,
    kind: Kind,
}

/// Where a node's [`order_key`] sits in its `hash` word.
const KEY_SHIFT: u32 = 58;

/// The elementary functions.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Func {
    /// Sine.
    Sin,
    /// Cosine.
    Cos,
    /// The sign function (`sgn x` = −1, 0 or 1), for Coulomb friction `f_c sgn(q̇)`: an opaque atom of
    /// the normal form (never expanded), with derivative zero where it is defined.
    Sgn,
}

impl Func {
    /// The function's name, `sin` or `cos`.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Sgn => "sgn",
        }
    }
}

/// The shape of a canonical expression, for reading (pattern matching) only.
#[derive(Clone, PartialEq, Eq, Hash)]
pub enum Kind {
    /// An exact rational number.
    Num(Rational),
    /// A symbol: a parameter or a coordinate.
    Sym(Symbol),
    /// The constant π.
    Pi,
    /// `sqrt(k)` of a square-free integer `k >= 2`.
    Sqrt(BigInt),
    /// `constant + Σ coefficient · term`, terms sorted and distinct.
    Add(Rational, Vec<(Expr, Rational)>),
    /// `coefficient · Π base^exponent`, bases sorted and distinct.
    Mul(Rational, Vec<(Expr, i64)>),
    /// `sin(arg)` or `cos(arg)`.
    Fun(Func, Expr),
}

impl Expr {
    fn make(kind: Kind) -> Expr {
        // Every node is hashed once, here; the children's hashes are words already, so the fast
        // multiply-rotate hash serves (the hash only speeds up equality and hash maps, never orders).
        let mut h = super::fast_hash::FxHasher::default();
        kind.hash(&mut h);
        let key = u64::from(order_key(&kind));
        Expr(Arc::new(Node {
            hash: (h.finish() >> (64 - KEY_SHIFT)) | (key << KEY_SHIFT),
            kind,
        }))
    }

    /// The node's shape.
    pub fn kind(&self) -> &Kind {
        &self.0.kind
    }

    /// An exact number.
    pub fn num(r: Rational) -> Expr {
        Expr::make(Kind::Num(r))
    }

    /// An integer.
    pub fn int(n: i64) -> Expr {
        Expr::num(Rational::int(n))
    }

    /// `n/d`; `None` when `d` is zero.
    pub fn frac(n: i64, d: i64) -> Option<Expr> {
        Rational::new(n, d).map(Expr::num)
    }

    /// Zero.
    pub fn zero() -> Expr {
        Expr::int(0)
    }

    /// One.
    pub fn one() -> Expr {
        Expr::int(1)
    }

    /// A symbol.
    pub fn sym(s: Symbol) -> Expr {
        Expr::make(Kind::Sym(s))
    }

    /// The symbol named `name` (coordinate names such as `q1`, `qd1`, `qdd1` give coordinates).
    pub fn symbol(name: &str) -> Expr {
        Expr::sym(Symbol::new(name))
    }

    /// `q_i`.
    pub fn q(i: u32) -> Expr {
        Expr::sym(Symbol::q(i))
    }

    /// `q̇_i`.
    pub fn qd(i: u32) -> Expr {
        Expr::sym(Symbol::qd(i))
    }

    /// `q̈_i`.
    pub fn qdd(i: u32) -> Expr {
        Expr::sym(Symbol::qdd(i))
    }

    /// The constant π.
    pub fn pi() -> Expr {
        Expr::make(Kind::Pi)
    }

    /// `sqrt(r)` of a rational `r >= 0`, as `c sqrt(k)` with `k` square-free.
    pub fn sqrt_rational(r: &Rational) -> Result<Expr, AlgebraError> {
        if r.is_negative() {
            return Err(AlgebraError::SqrtOfNegative(r.to_string()));
        }
        if r.is_zero() {
            return Ok(Expr::zero());
        }
        // sqrt(n/d) = sqrt(n d) / d
        let d = r.denom();
        let nd = r.numer() * &d;
        let (k, rest) = split_square(&nd);
        let coeff = Rational::from_bigints(k, d).expect("positive denominator");
        let root = if rest.is_one() {
            Expr::one()
        } else {
            Expr::make(Kind::Sqrt(rest))
        };
        Ok(Expr::num(coeff) * root)
    }

    /// `sqrt(e)` where `e` must evaluate to a rational number.
    pub fn sqrt(e: &Expr) -> Result<Expr, AlgebraError> {
        match e.kind() {
            Kind::Num(r) => Expr::sqrt_rational(r),
            _ => {
                // sqrt(c sqrt(k))^2 ... only rationals are supported.
                Err(AlgebraError::SqrtOfNonRational(e.to_string()))
            }
        }
    }

    /// `sin(e)`, with exact values at rational multiples of π and the sign taken out.
    pub fn sin(e: &Expr) -> Expr {
        trig_values::canonical_fun(Func::Sin, e)
    }

    /// `cos(e)`, with exact values at rational multiples of π and the sign taken out.
    pub fn cos(e: &Expr) -> Expr {
        trig_values::canonical_fun(Func::Cos, e)
    }

    /// `tan(e) = sin(e)/cos(e)`; an error where `cos(e)` is identically zero.
    pub fn tan(e: &Expr) -> Result<Expr, AlgebraError> {
        Expr::sin(e).div(&Expr::cos(e))
    }

    /// `sgn(e)`: the sign of a number; `sgn(−x) = −sgn(x)` taken out, so equal signs print equally.
    pub fn sgn(e: &Expr) -> Expr {
        if let Kind::Num(r) = e.kind() {
            return Expr::int(if r.is_zero() {
                0
            } else if r.is_negative() {
                -1
            } else {
                1
            });
        }
        if e.reads_negative() {
            return -Expr::sgn(&-e);
        }
        Expr::make(Kind::Fun(Func::Sgn, e.clone()))
    }

    /// `f(e)` for a function.
    pub fn fun(f: Func, e: &Expr) -> Expr {
        match f {
            Func::Sin => Expr::sin(e),
            Func::Cos => Expr::cos(e),
            Func::Sgn => Expr::sgn(e),
        }
    }

    /// A raw function node. Only `trig_values` calls this, after normalising the argument.
    pub(crate) fn fun_unchecked(f: Func, arg: Expr) -> Expr {
        Expr::make(Kind::Fun(f, arg))
    }

    /// `self^e` for an integer exponent; an error for `0^e` with `e < 0`, and for a result beyond the
    /// [size limits](super::limits): a number of more than `MAX_NUMBER_BITS` bits (`2^99999999`) or an
    /// exponent beyond `MAX_EXPONENT`, refused before anything is computed.
    pub fn pow(&self, e: i64) -> Result<Expr, AlgebraError> {
        if e == 0 {
            return Ok(Expr::one());
        }
        if e == 1 {
            return Ok(self.clone());
        }
        self.check_power(e)?;
        match self.kind() {
            Kind::Num(r) => r.pow(e).map(Expr::num).ok_or(AlgebraError::DivisionByZero),
            Kind::Mul(c, fs) => {
                let coeff = c.pow(e).ok_or(AlgebraError::DivisionByZero)?;
                let mut factors = Vec::with_capacity(fs.len() + 1);
                factors.push(Expr::num(coeff));
                for (b, k) in fs {
                    // Within MAX_EXPONENT, checked above.
                    factors.push(Expr::power_unchecked(b.clone(), k * e));
                }
                Ok(Expr::product(factors))
            }
            _ => {
                if self.is_zero() && e < 0 {
                    return Err(AlgebraError::DivisionByZero);
                }
                Ok(Expr::product([Expr::power_unchecked(self.clone(), e)]))
            }
        }
    }

    /// Refuses `self^e` when its numbers or exponents would pass the size limits.
    fn check_power(&self, e: i64) -> Result<(), AlgebraError> {
        use super::limits::{check_bits, growing_bits, MAX_EXPONENT};
        let root = |k: &BigInt| u128::from(k.bits()) / 2 + 1;
        let (per_unit, largest_exponent) = match self.kind() {
            Kind::Num(r) => (u128::from(growing_bits(r)), 1),
            Kind::Sqrt(k) => (root(k), 1),
            Kind::Mul(c, fs) => {
                let roots: u128 = fs
                    .iter()
                    .map(|(b, _)| match b.kind() {
                        Kind::Sqrt(k) => root(k),
                        _ => 0,
                    })
                    .sum();
                let k = fs.iter().map(|(_, k)| k.unsigned_abs()).max().unwrap_or(1);
                (u128::from(growing_bits(c)) + roots, k)
            }
            Kind::Add(..) => (u128::from(growing_bits(&primitive_base(self).1)), 1),
            Kind::Sym(_) | Kind::Pi | Kind::Fun(..) => (0, 1),
        };
        let what = || super::limits::power_text(self, e);
        let exponent = u128::from(largest_exponent) * u128::from(e.unsigned_abs());
        if exponent > u128::from(MAX_EXPONENT) {
            return Err(AlgebraError::TooLarge(format!(
                "the exponent {exponent} of `{}` is beyond {MAX_EXPONENT}",
                what()
            )));
        }
        check_bits(what, per_unit.saturating_mul(u128::from(e.unsigned_abs())))
    }

    /// `self / other`; an error when `other` is structurally zero.
    pub fn div(&self, other: &Expr) -> Result<Expr, AlgebraError> {
        if other.is_zero() {
            return Err(AlgebraError::DivisionByZero);
        }
        Ok(self * &other.pow(-1)?)
    }

    /// A one-factor product `base^e` that is not yet normalised (`e != 0`); feed it to `product`.
    fn power_unchecked(base: Expr, e: i64) -> Expr {
        debug_assert!(e != 0);
        Expr::make(Kind::Mul(Rational::one(), vec![(base, e)]))
    }

    /// Whether this is a plain base: a symbol, a function or π. The factors of a canonical product
    /// of plain bases, less some of them, are a product as they stand
    /// ([`Expr::monomial_of_sorted_bases`]); other bases (numbers, surds, sums) may need merging.
    pub(crate) fn is_plain_base(&self) -> bool {
        matches!(self.kind(), Kind::Sym(_) | Kind::Fun(..) | Kind::Pi)
    }

    /// The monomial `Π bᵢ^kᵢ` (coefficient 1) of bases that are already canonical, pairwise
    /// distinct, neither numbers, square roots nor sums, in the total order, with non-zero exponents:
    /// what [`Expr::product`] makes of them, without its merging. For a polynomial's terms
    /// ([`crate::algebra::Poly::to_expr`]).
    pub(crate) fn monomial_of_sorted_bases(factors: Vec<(Expr, i64)>) -> Expr {
        debug_assert!(factors.windows(2).all(|w| w[0].0 < w[1].0));
        debug_assert!(factors.iter().all(|(b, k)| *k != 0
            && !matches!(
                b.kind(),
                Kind::Num(_) | Kind::Sqrt(_) | Kind::Add(..) | Kind::Mul(..)
            )));
        match factors.len() {
            0 => Expr::one(),
            1 if factors[0].1 == 1 => factors.into_iter().next().expect("one factor").0,
            _ => Expr::make(Kind::Mul(Rational::one(), factors)),
        }
    }

    /// `c · self · base^1` for a monomial `self` of plain bases ([`Expr::is_plain_base`]) with
    /// coefficient 1 (the number 1, one base, or a product) and a plain `base`: what
    /// [`Expr::product`] makes of them, with `base` put in its place among the factors (or its
    /// exponent raised) instead of every factor sorted again. `None` if `self` is not such a
    /// monomial. For the terms the display rules merge ([`crate::algebra::tidy::contract`]).
    pub(crate) fn monomial_times_base(&self, base: &Expr, c: &Rational) -> Option<Expr> {
        debug_assert!(base.is_plain_base() && !c.is_zero());
        let mut factors: Vec<(Expr, i64)> = match self.kind() {
            Kind::Mul(k, fs) if k.is_one() && fs.iter().all(|(b, _)| b.is_plain_base()) => {
                fs.clone()
            }
            Kind::Num(r) if r.is_one() => Vec::new(),
            _ if self.is_plain_base() => vec![(self.clone(), 1)],
            _ => return None,
        };
        match factors.binary_search_by(|(b, _)| b.cmp(base)) {
            Ok(i) if factors[i].1 == -1 => {
                factors.remove(i);
            }
            Ok(i) => factors[i].1 += 1,
            Err(i) => factors.insert(i, (base.clone(), 1)),
        }
        Some(match factors.len() {
            0 => Expr::num(c.clone()),
            1 if factors[0].1 == 1 && c.is_one() => factors.pop().expect("one factor").0,
            _ => Expr::make(Kind::Mul(c.clone(), factors)),
        })
    }

    /// The sum `constant + Σ cᵢ tᵢ` of distinct terms `tᵢ` (products with coefficient 1, none the
    /// number 1) with non-zero coefficients, in the total order: what [`Expr::sum`] makes of them
    /// once it has merged them (its last step), and what [`crate::algebra::Poly::to_expr`] gives for
    /// its monomials ([`Expr::monomial_of_sorted_bases`]).
    pub(crate) fn sum_of_sorted_monomials(
        constant: Rational,
        terms: Vec<(Expr, Rational)>,
    ) -> Expr {
        debug_assert!(terms.windows(2).all(|w| w[0].0 < w[1].0));
        debug_assert!(terms.iter().all(|(t, c)| !c.is_zero() && !t.is_one()));
        match (constant.is_zero(), terms.len()) {
            (_, 0) => Expr::num(constant),
            (true, 1) => {
                let (t, c) = terms.into_iter().next().expect("one term");
                t.scale(&c)
            }
            _ => Expr::make(Kind::Add(constant, terms)),
        }
    }

    /// The canonical sum of the given expressions.
    pub fn sum<I: IntoIterator<Item = Expr>>(items: I) -> Expr {
        let mut constant = Rational::zero();
        // Every (term, coefficient), then sorted by term and merged: the same as adding them one by
        // one into an ordered map, at a fraction of the cost.
        let items = items.into_iter();
        let mut all: Vec<(Expr, Rational)> = Vec::with_capacity(items.size_hint().0);
        for item in items {
            match item.kind() {
                Kind::Num(r) => constant += r,
                Kind::Add(c, ts) => {
                    constant += c;
                    all.extend(ts.iter().cloned());
                }
                Kind::Mul(c, _) if !c.is_one() => {
                    let (c, t) = item.split_coeff();
                    all.push((t, c));
                }
                _ => all.push((item.clone(), Rational::one())),
            }
        }
        Expr::sum_of_terms(constant, all)
    }

    /// `constant + Σ cᵢ tᵢ` for terms `tᵢ` as [`Expr::terms`] gives them (coefficient 1, not a
    /// number), in any order and possibly repeated: [`Expr::sum`] without splitting each term's
    /// coefficient off again.
    pub(crate) fn sum_of_terms(constant: Rational, mut all: Vec<(Expr, Rational)>) -> Expr {
        all.sort_by(|a, b| a.0.cmp(&b.0));
        let mut terms: Vec<(Expr, Rational)> = Vec::with_capacity(all.len());
        for term in all {
            push_sorted_term(&mut terms, term);
        }
        if terms.last().is_some_and(|(_, sum)| sum.is_zero()) {
            terms.pop();
        }
        Expr::sum_of_sorted_monomials(constant, terms)
    }

    /// The canonical product of the given expressions.
    pub fn product<I: IntoIterator<Item = Expr>>(items: I) -> Expr {
        let mut coeff = Rational::one();
        // Every (base, exponent), then sorted by base and merged (as an ordered map would, cheaper).
        // Multiplications by 1 are skipped, and only a sum can carry content out of a base.
        let items = items.into_iter();
        let mut all: Vec<(Expr, i64)> = Vec::with_capacity(items.size_hint().0.max(4));
        let times = |coeff: &mut Rational, r: &Rational| {
            if !r.is_one() {
                *coeff = &*coeff * r;
            }
        };
        for item in items {
            match item.kind() {
                Kind::Num(r) => times(&mut coeff, r),
                Kind::Mul(c, fs) => {
                    times(&mut coeff, c);
                    for (b, k) in fs {
                        if let Kind::Add(..) = b.kind() {
                            let (b, content) = primitive_base(b);
                            if !content.is_one() {
                                coeff = &coeff * &content.pow(*k).expect("non-zero content");
                            }
                            all.push((b, *k));
                        } else {
                            all.push((b.clone(), *k));
                        }
                    }
                }
                Kind::Add(..) => {
                    let (b, content) = primitive_base(&item);
                    times(&mut coeff, &content);
                    all.push((b, 1));
                }
                _ => all.push((item, 1)),
            }
            if coeff.is_zero() {
                return Expr::zero();
            }
        }
        all.sort_by(|a, b| a.0.cmp(&b.0));
        // Merged in place: equal bases add their exponents.
        let mut bases: Vec<(Expr, i64)> = Vec::with_capacity(all.len());
        for (b, k) in all {
            match bases.last_mut() {
                Some((last, e)) if (*last).cmp(&b) == std::cmp::Ordering::Equal => *e += k,
                _ => bases.push((b, k)),
            }
        }
        // Square roots: sqrt(k)^e = k^floor(e/2) sqrt(k)^(e mod 2); the odd ones multiply into one
        // radicand. Zero exponents drop out.
        let mut radicand: Option<BigInt> = None;
        let mut factors = bases;
        factors.retain(|(b, e)| {
            if *e == 0 {
                return false;
            }
            if let Kind::Sqrt(k) = b.kind() {
                let half = e.div_euclid(2);
                let odd = e.rem_euclid(2);
                if half != 0 {
                    coeff = &coeff * &Rational::from(k.clone()).pow(half).expect("k >= 2");
                }
                if odd == 1 {
                    *radicand.get_or_insert_with(BigInt::one) *= k;
                }
                return false;
            }
            true
        });
        if let Some(radicand) = radicand.filter(|r| !r.is_one()) {
            let (s, rest) = split_square(&radicand);
            coeff = &coeff * &Rational::from(s);
            if !rest.is_one() {
                let root = Expr::make(Kind::Sqrt(rest));
                let at = factors.partition_point(|(b, _)| b < &root);
                factors.insert(at, (root, 1));
            }
        }
        if factors.is_empty() {
            return Expr::num(coeff);
        }
        if factors.len() == 1 && factors[0].1 == 1 {
            let base = factors.pop().expect("one factor").0;
            if coeff.is_one() {
                return base;
            }
            if let Kind::Add(..) = base.kind() {
                return base.scale(&coeff);
            }
            factors.push((base, 1));
        }
        Expr::make(Kind::Mul(coeff, factors))
    }

    /// `c · self`, distributing over a sum.
    pub fn scale(&self, c: &Rational) -> Expr {
        if c.is_zero() {
            return Expr::zero();
        }
        if c.is_one() {
            return self.clone();
        }
        match self.kind() {
            Kind::Num(r) => Expr::num(r * c),
            Kind::Add(k, ts) => Expr::make(Kind::Add(
                k * c,
                ts.iter().map(|(t, r)| (t.clone(), r * c)).collect(),
            )),
            Kind::Mul(k, fs) => {
                let k = k * c;
                if k.is_one() && fs.len() == 1 && fs[0].1 == 1 {
                    fs[0].0.clone()
                } else {
                    Expr::make(Kind::Mul(k, fs.clone()))
                }
            }
            _ => Expr::make(Kind::Mul(c.clone(), vec![(self.clone(), 1)])),
        }
    }

    /// Splits off the rational coefficient: `3 x y` gives `(3, x y)`, `x` gives `(1, x)`, `5` gives `(5, 1)`.
    pub fn split_coeff(&self) -> (Rational, Expr) {
        match self.kind() {
            Kind::Num(r) => (r.clone(), Expr::one()),
            Kind::Mul(c, fs) => {
                let rest = if fs.len() == 1 && fs[0].1 == 1 {
                    fs[0].0.clone()
                } else {
                    Expr::make(Kind::Mul(Rational::one(), fs.clone()))
                };
                (c.clone(), rest)
            }
            _ => (Rational::one(), self.clone()),
        }
    }

    /// The factors `(base, exponent)` of a product; a non-product is one factor `(self, 1)`; a number none.
    pub fn factors(&self) -> Vec<(Expr, i64)> {
        match self.kind() {
            Kind::Num(_) => vec![],
            Kind::Mul(_, fs) => fs.clone(),
            _ => vec![(self.clone(), 1)],
        }
    }

    /// The terms `(term, coefficient)` of a sum, with the constant (if non-zero) as the term `1`.
    pub fn terms(&self) -> Vec<(Expr, Rational)> {
        match self.kind() {
            Kind::Add(c, ts) => {
                let mut out = ts.clone();
                if !c.is_zero() {
                    out.push((Expr::one(), c.clone()));
                }
                out
            }
            Kind::Num(r) if r.is_zero() => vec![],
            _ => {
                let (c, t) = self.split_coeff();
                vec![(t, c)]
            }
        }
    }

    /// The rational value, if this is a number.
    pub fn as_rational(&self) -> Option<&Rational> {
        match self.kind() {
            Kind::Num(r) => Some(r),
            _ => None,
        }
    }

    /// The symbol, if this is one.
    pub fn as_symbol(&self) -> Option<&Symbol> {
        match self.kind() {
            Kind::Sym(s) => Some(s),
            _ => None,
        }
    }

    /// Whether this is the number zero (structurally; see `normal::is_zero` for the zero test).
    pub fn is_zero(&self) -> bool {
        matches!(self.kind(), Kind::Num(r) if r.is_zero())
    }

    /// Whether this is the number one.
    pub fn is_one(&self) -> bool {
        matches!(self.kind(), Kind::Num(r) if r.is_one())
    }

    /// Whether the expression "reads negative": a negative number, or a product or sum whose leading
    /// coefficient is negative. `x - y` does not, `y - x` (= `-x + y`) does. Used to pick one of `e`, `-e`.
    pub fn reads_negative(&self) -> bool {
        match self.kind() {
            Kind::Num(r) => r.is_negative(),
            Kind::Mul(c, _) => c.is_negative(),
            Kind::Add(c, ts) => ts.first().map_or(c.is_negative(), |(_, k)| k.is_negative()),
            _ => false,
        }
    }

    /// Every symbol in the expression, sorted.
    pub fn symbols(&self) -> std::collections::BTreeSet<Symbol> {
        let mut out = std::collections::BTreeSet::new();
        self.collect_symbols(&mut out);
        out
    }

    fn collect_symbols(&self, out: &mut std::collections::BTreeSet<Symbol>) {
        match self.kind() {
            Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) => {}
            Kind::Sym(s) => {
                out.insert(s.clone());
            }
            Kind::Add(_, ts) => ts.iter().for_each(|(t, _)| t.collect_symbols(out)),
            Kind::Mul(_, fs) => fs.iter().for_each(|(b, _)| b.collect_symbols(out)),
            Kind::Fun(_, a) => a.collect_symbols(out),
        }
    }

    /// Whether `s` occurs in the expression.
    pub fn contains(&self, s: &Symbol) -> bool {
        match self.kind() {
            Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) => false,
            Kind::Sym(t) => t == s,
            Kind::Add(_, ts) => ts.iter().any(|(t, _)| t.contains(s)),
            Kind::Mul(_, fs) => fs.iter().any(|(b, _)| b.contains(s)),
            Kind::Fun(_, a) => a.contains(s),
        }
    }

    /// A small integer exponent's value or an error naming it.
    pub fn integer_exponent(&self) -> Result<i64, AlgebraError> {
        match self.kind() {
            Kind::Num(r) if r.is_integer() => r
                .to_i64()
                .filter(|e| e.abs() <= i32::MAX as i64)
                .ok_or_else(|| AlgebraError::TooLarge(r.to_string())),
            _ => Err(AlgebraError::NonIntegerPower(self.to_string())),
        }
    }

    /// The number of nodes, a measure of size.
    pub fn node_count(&self) -> usize {
        1 + match self.kind() {
            Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) | Kind::Sym(_) => 0,
            Kind::Add(_, ts) => ts.iter().map(|(t, _)| t.node_count()).sum(),
            Kind::Mul(_, fs) => fs.iter().map(|(b, _)| b.node_count()).sum(),
            Kind::Fun(_, a) => a.node_count(),
        }
    }

    /// Whether `sqrt(k)` with this radicand; for the printers.
    pub fn radicand_u64(k: &BigInt) -> Option<u64> {
        k.to_u64()
    }
}

/// A sum used as a base is primitive and reads positive: its coefficients have no common rational
/// factor and its leading one is positive, so `(2 b − 2 a)^k` is stored as `(−2)^k (a − b)^k`. Returns
/// the base and the factor taken out.
fn primitive_base(b: &Expr) -> (Expr, Rational) {
    match b.kind() {
        Kind::Add(c, ts) => {
            let mut content = ts.iter().fold(c.abs(), |g, (_, k)| g.gcd(k));
            if b.reads_negative() {
                content = -content;
            }
            if content.is_one() || content.is_zero() {
                return (b.clone(), Rational::one());
            }
            let inv = content.recip().expect("non-zero content");
            (b.scale(&inv), content)
        }
        _ => (b.clone(), Rational::one()),
    }
}

// ---------------------------------------------------------------------------------------------------
// The total order.

/// Rank of an expression used as a factor; it fixes the order in which factors print:
/// numbers, square roots, π, masses, parenthesised sums, other parameters, coordinates, functions,
/// q̇, q̈ — so `m2 (lc2^2 + l1 lc2 cos(q2))` and `(m1+m2+m3) g` read as in Spong.
fn base_rank(kind: &Kind) -> u8 {
    match kind {
        Kind::Num(_) => 0,
        Kind::Sqrt(_) => 1,
        Kind::Pi => 2,
        Kind::Sym(Symbol::Param(n)) if param_class(n) == 0 => 3,
        Kind::Add(..) => 4,
        Kind::Sym(Symbol::Param(_)) => 5,
        Kind::Sym(Symbol::Coord { order: 0, .. }) => 6,
        Kind::Fun(..) => 7,
        Kind::Sym(Symbol::Coord { order: 1, .. }) => 8,
        Kind::Sym(Symbol::Coord { .. }) => 9,
        Kind::Mul(..) => 10,
    }
}

/// A base's [`base_rank`], and for a parameter its [`param_class`] after it (below 64): bases of
/// different keys compare as their keys; two parameters of one key compare by name alone.
fn order_key(kind: &Kind) -> u8 {
    let class = match kind {
        Kind::Sym(Symbol::Param(n)) => param_class(n),
        _ => 0,
    };
    base_rank(kind) * 4 + class
}

/// The house order of parameter names: masses (`m…`) first, gravity `g` last, the rest naturally.
fn param_class(name: &str) -> u8 {
    if name == "g" {
        2
    } else if name.starts_with('m') && name[1..].chars().all(|c| c.is_ascii_digit() || c == '_') {
        0
    } else {
        1
    }
}

fn cmp_base(a: &Expr, b: &Expr) -> Ordering {
    // Equal bases are the common case (the factor lists of a sum's terms start alike): told by the
    // node's hash and shape, without ranking them (a parameter's rank classes its name).
    if a == b {
        return Ordering::Equal;
    }
    let (ka, kb) = (a.0.hash >> KEY_SHIFT, b.0.hash >> KEY_SHIFT);
    if ka != kb {
        return ka.cmp(&kb);
    }
    match (a.kind(), b.kind()) {
        (Kind::Num(x), Kind::Num(y)) => x.cmp(y),
        (Kind::Sqrt(x), Kind::Sqrt(y)) => x.cmp(y),
        (Kind::Pi, Kind::Pi) => Ordering::Equal,
        // One key: one class.
        (Kind::Sym(Symbol::Param(x)), Kind::Sym(Symbol::Param(y))) => {
            super::symbol::natural_cmp(x, y)
        }
        (Kind::Sym(x), Kind::Sym(y)) => x.cmp(y),
        (Kind::Fun(f, x), Kind::Fun(g, y)) => x.cmp(y).then(f.cmp(g)),
        (Kind::Add(c, xs), Kind::Add(d, ys)) => {
            cmp_seq(xs, ys, |(s, k), (t, l)| s.cmp(t).then_with(|| k.cmp(l))).then_with(|| c.cmp(d))
        }
        (Kind::Mul(c, xs), Kind::Mul(d, ys)) => cmp_factors(xs, ys).then_with(|| c.cmp(d)),
        _ => unreachable!("equal ranks have equal kinds"),
    }
}

/// Appends the term `(t, c)` to terms sorted so far (`t` not before the last): added to the last if
/// it is the same monomial, else put after it, the last dropped first if its coefficient came to
/// zero. A last term of coefficient zero is left for the caller to drop.
#[inline]
pub(crate) fn push_sorted_term(terms: &mut Vec<(Expr, Rational)>, (t, c): (Expr, Rational)) {
    match terms.last_mut() {
        Some((last, sum)) if (*last).cmp(&t) == Ordering::Equal => *sum += &c,
        _ => {
            if terms.last().is_some_and(|(_, sum)| sum.is_zero()) {
                terms.pop();
            }
            terms.push((t, c));
        }
    }
}

fn cmp_seq<T>(xs: &[T], ys: &[T], f: impl Fn(&T, &T) -> Ordering) -> Ordering {
    for (x, y) in xs.iter().zip(ys) {
        let o = f(x, y);
        if o != Ordering::Equal {
            return o;
        }
    }
    xs.len().cmp(&ys.len())
}

/// Factor lists compare base by base; for an equal base the higher power comes first.
fn cmp_factors(xs: &[(Expr, i64)], ys: &[(Expr, i64)]) -> Ordering {
    cmp_seq(xs, ys, |(a, i), (b, j)| {
        cmp_base(a, b).then_with(|| j.cmp(i))
    })
}

/// [`cmp_factors`] of `xs` and the one factor `b¹` (a base compared with a product), without
/// building that list.
fn cmp_factors_base(xs: &[(Expr, i64)], b: &Expr) -> Ordering {
    match xs.first() {
        None => Ordering::Less,
        Some((a, i)) => cmp_base(a, b)
            .then_with(|| 1.cmp(i))
            .then_with(|| xs.len().cmp(&1)),
    }
}

impl Ord for Expr {
    /// The canonical total order: numbers first; everything else as a product `c · Π b^e` compared by
    /// its factor list (bases by rank, then by name or structure), then by coefficient.
    fn cmp(&self, other: &Self) -> Ordering {
        if Arc::ptr_eq(&self.0, &other.0) {
            return Ordering::Equal;
        }
        match (self.kind(), other.kind()) {
            (Kind::Num(x), Kind::Num(y)) => x.cmp(y),
            (Kind::Num(_), _) => Ordering::Less,
            (_, Kind::Num(_)) => Ordering::Greater,
            (Kind::Mul(c, xs), Kind::Mul(d, ys)) => cmp_factors(xs, ys).then_with(|| c.cmp(d)),
            (Kind::Mul(c, xs), _) => {
                cmp_factors_base(xs, other).then_with(|| c.cmp(&Rational::one()))
            }
            (_, Kind::Mul(d, ys)) => cmp_factors_base(ys, self)
                .reverse()
                .then_with(|| Rational::one().cmp(d)),
            _ => cmp_base(self, other),
        }
    }
}

impl PartialOrd for Expr {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl PartialEq for Expr {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
            || (self.0.hash == other.0.hash && self.0.kind == other.0.kind)
    }
}

impl Eq for Expr {}

impl Hash for Expr {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(self.0.hash);
    }
}

// ---------------------------------------------------------------------------------------------------
// Operators.

impl std::ops::Add<&Expr> for &Expr {
    type Output = Expr;
    fn add(self, rhs: &Expr) -> Expr {
        Expr::sum([self.clone(), rhs.clone()])
    }
}

impl std::ops::Sub<&Expr> for &Expr {
    type Output = Expr;
    fn sub(self, rhs: &Expr) -> Expr {
        Expr::sum([self.clone(), -rhs])
    }
}

impl std::ops::Mul<&Expr> for &Expr {
    type Output = Expr;
    fn mul(self, rhs: &Expr) -> Expr {
        Expr::product([self.clone(), rhs.clone()])
    }
}

impl std::ops::Neg for &Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        self.scale(&Rational::int(-1))
    }
}

macro_rules! owned_ops {
    ($($trait:ident $method:ident),*) => {$(
        impl std::ops::$trait<Expr> for Expr {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr { std::ops::$trait::$method(&self, &rhs) }
        }
        impl std::ops::$trait<&Expr> for Expr {
            type Output = Expr;
            fn $method(self, rhs: &Expr) -> Expr { std::ops::$trait::$method(&self, rhs) }
        }
        impl std::ops::$trait<Expr> for &Expr {
            type Output = Expr;
            fn $method(self, rhs: Expr) -> Expr { std::ops::$trait::$method(self, &rhs) }
        }
    )*};
}
owned_ops!(Add add, Sub sub, Mul mul);

impl std::ops::Neg for Expr {
    type Output = Expr;
    fn neg(self) -> Expr {
        -&self
    }
}

impl From<i64> for Expr {
    fn from(n: i64) -> Self {
        Expr::int(n)
    }
}

impl From<Rational> for Expr {
    fn from(r: Rational) -> Self {
        Expr::num(r)
    }
}

impl From<Symbol> for Expr {
    fn from(s: Symbol) -> Self {
        Expr::sym(s)
    }
}

impl std::fmt::Debug for Expr {
    /// A plain, unambiguous form for debugging (not the house style; see `print`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.kind() {
            Kind::Num(r) => write!(f, "{r}"),
            Kind::Sym(s) => write!(f, "{s:?}"),
            Kind::Pi => write!(f, "pi"),
            Kind::Sqrt(k) => write!(f, "sqrt({k})"),
            Kind::Add(c, ts) => {
                write!(f, "(")?;
                for (i, (t, k)) in ts.iter().enumerate() {
                    if i > 0 {
                        write!(f, " + ")?;
                    }
                    write!(f, "{k}*{t:?}")?;
                }
                if !c.is_zero() {
                    write!(f, " + {c}")?;
                }
                write!(f, ")")
            }
            Kind::Mul(c, fs) => {
                write!(f, "{c}")?;
                for (b, e) in fs {
                    write!(f, "*{b:?}^{e}")?;
                }
                Ok(())
            }
            Kind::Fun(g, a) => write!(f, "{}({a:?})", g.name()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn x() -> Expr {
        Expr::symbol("x")
    }
    fn y() -> Expr {
        Expr::symbol("y")
    }

    /// `monomial_times_base` is what `product` makes of the same factors: a new base in the middle,
    /// at either end, a raised exponent, an exponent raised to zero, no other factor, a coefficient
    /// of one and not; and it declines what is not a monomial of plain bases.
    #[test]
    fn monomial_times_base_is_the_product() {
        let (c1, s2) = (Expr::cos(&Expr::q(1)), Expr::sin(&Expr::q(2)));
        let (m, a, z) = (Expr::symbol("m2"), Expr::symbol("a1"), Expr::symbol("zz"));
        let monomials = [
            Expr::one(),
            m.clone(),
            &m * &a,
            &m * &a * &z * &s2,
            &m * &c1,
            c1.pow(2).unwrap() * &a,
            c1.pow(-1).unwrap() * &m,
        ];
        for r in &monomials {
            for base in [&c1, &s2, &m, &z] {
                for c in [
                    Rational::one(),
                    Rational::int(-2),
                    Rational::new(3, 4).unwrap(),
                ] {
                    let want = Expr::product([Expr::num(c.clone()), r.clone(), base.clone()]);
                    assert_eq!(
                        r.monomial_times_base(base, &c),
                        Some(want),
                        "{r:?} {base:?}"
                    );
                }
            }
        }
        let two_m = Expr::int(2) * &m;
        for r in [
            two_m,
            &m + &a,
            Expr::int(3),
            Expr::sqrt(&Expr::int(2)).unwrap(),
        ] {
            assert_eq!(r.monomial_times_base(&c1, &Rational::one()), None, "{r:?}");
        }
    }

    /// One row per canonical rule in the module documentation.
    #[test]
    fn canonical_rules() {
        let half = Expr::frac(1, 2).unwrap();
        // 1
        assert_eq!(Expr::frac(2, 4).unwrap(), half);
        // 2
        assert_eq!(&x() + &(&y() + &x()), &Expr::int(2) * &x() + y());
        assert!((&x() - &x()).is_zero());
        // 3
        let s = &(&Expr::int(2) * &(&x() * &y())) + &Expr::int(3);
        match s.kind() {
            Kind::Add(c, ts) => {
                assert_eq!(c, &Rational::int(3));
                assert_eq!(ts, &vec![(&x() * &y(), Rational::int(2))]);
            }
            _ => panic!("not a sum"),
        }
        // 4
        assert_eq!(&x() * &(&x() * &y()), &x().pow(2).unwrap() * &y());
        assert!(x().div(&x()).unwrap().is_one());
        // 5
        assert_eq!(
            &Expr::int(2) * &(&x() + &y()),
            &(&Expr::int(2) * &x()) + &(&Expr::int(2) * &y())
        );
        // 6
        assert_eq!(&x() + &Expr::zero(), x());
        assert_eq!(Expr::product([x().pow(1).unwrap(), Expr::one()]), x());
        // 7
        let sqrt = |n| Expr::sqrt(&Expr::int(n)).unwrap();
        assert_eq!(sqrt(12), &Expr::int(2) * &sqrt(3));
        assert_eq!(&sqrt(2) * &sqrt(6), &Expr::int(2) * &sqrt(3));
        assert_eq!(Expr::one().div(&sqrt(2)).unwrap(), &sqrt(2) * &half);
        // 8
        assert_eq!(Expr::sin(&-x()), -Expr::sin(&x()));
        let pi2 = &Expr::pi() * &half;
        assert_eq!(Expr::cos(&(&x() + &pi2)), -Expr::sin(&x()));
        assert_eq!(Expr::cos(&(&Expr::pi() * &Expr::frac(1, 3).unwrap())), half);
    }

    /// The order key fits the hash word's top bits, and parameters order by class, then name:
    /// masses first, `g` last, numbers in names by value.
    #[test]
    fn the_order_key_fits_its_bits_and_orders_parameters_by_class() {
        assert_eq!(std::mem::size_of::<Node>(), 64, "a node is one cache line");
        let names = [
            "m2", "m10", "m_1", "I1", "a2", "lc10", "lc2", "g", "Xi3", "mu",
        ];
        for n in names {
            assert!(u32::from(order_key(Expr::symbol(n).kind())) < 1 << (64 - KEY_SHIFT));
        }
        let mut bases: Vec<Expr> = names.iter().map(|n| Expr::symbol(n)).collect();
        bases.push(Expr::q(1));
        bases.push(Expr::cos(&Expr::q(1)));
        bases.push(Expr::symbol("a1") + Expr::symbol("a2"));
        for b in &bases {
            assert!(u32::from(order_key(b.kind())) < 1 << (64 - KEY_SHIFT));
        }
        let mut sorted: Vec<Expr> = bases.clone();
        sorted.sort_by(cmp_base);
        let text: Vec<String> = sorted.iter().map(|e| e.to_string()).collect();
        // Masses (m…; a digit sorts before `_`), the sum, other parameters naturally, g, then q1
        // and cos q1.
        assert_eq!(
            text,
            [
                "m2", "m10", "m_1", "a1 + a2", "I1", "Xi3", "a2", "lc2", "lc10", "mu", "g", "q1",
                "cos(q1)"
            ]
        );
    }

    #[test]
    fn order_is_independent_of_construction_order() {
        let names = ["m3", "m1", "lc2", "g", "q1", "qd2", "I1"];
        let forward = Expr::sum(names.iter().map(|n| Expr::symbol(n)));
        let backward = Expr::sum(names.iter().rev().map(|n| Expr::symbol(n)));
        assert_eq!(forward, backward);
        let p1 = Expr::product(names.iter().map(|n| Expr::symbol(n)));
        let p2 = Expr::product(names.iter().rev().map(|n| Expr::symbol(n)));
        assert_eq!(p1, p2);
        assert_eq!(p1.cmp(&p2), Ordering::Equal);
    }

    #[test]
    fn sums_as_bases_are_primitive() {
        let (m, q) = (Expr::symbol("m1"), Expr::q(1));
        let a = (&(Expr::int(2) * &m) + &Expr::int(2)) * &q;
        let b = Expr::product([Expr::int(2), &m + &Expr::one(), q.clone()]);
        assert_eq!(a, b);
        let half = (&(&m * &Expr::frac(1, 2).unwrap()) + &Expr::one())
            .pow(-1)
            .unwrap();
        assert_eq!(half, (&m + &Expr::int(2)).pow(-1).unwrap() * Expr::int(2));
    }

    #[test]
    fn sums_as_bases_read_positive() {
        let (a, b) = (x(), y());
        assert_eq!((&b - &a).pow(2).unwrap(), (&a - &b).pow(2).unwrap());
        assert_eq!((&b - &a).pow(3).unwrap(), -(&a - &b).pow(3).unwrap());
        assert_eq!((&b - &a) * (&a - &b).pow(-1).unwrap(), Expr::int(-1));
    }

    /// Errors name expressions as the parser reads them, not in the debug form.
    #[test]
    fn errors_name_expressions_readably() {
        let two_pi = Expr::int(2) * Expr::pi();
        assert_eq!(
            Expr::sqrt(&two_pi).unwrap_err().to_string(),
            "sqrt takes a rational number here, not `2*pi`"
        );
        let half_x = Expr::symbol("x") + Expr::frac(1, 2).unwrap();
        assert_eq!(
            half_x.integer_exponent().unwrap_err().to_string(),
            "only integer powers are supported, not `x + 1/2`"
        );
    }

    #[test]
    fn errors_instead_of_panics() {
        assert_eq!(Expr::zero().pow(-1), Err(AlgebraError::DivisionByZero));
        assert_eq!(x().div(&Expr::zero()), Err(AlgebraError::DivisionByZero));
        assert!(Expr::sqrt(&Expr::int(-2)).is_err());
        assert!(Expr::sqrt(&x()).is_err());
        let pi2 = &Expr::pi() * &Expr::frac(1, 2).unwrap();
        assert_eq!(Expr::tan(&pi2), Err(AlgebraError::DivisionByZero));
    }
}
