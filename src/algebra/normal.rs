//! The normal form of an expression and the zero test.
//!
//! [`to_poly`] expands an [`Expr`] into a [`Poly`]: products are multiplied out, `sin` and `cos` of
//! rational combinations of angle symbols (plus a constant and a rational multiple of π) are expanded
//! into products of `sin`, `cos` of single base angles, and `sin²` is replaced by `1 − cos²`. What
//! falls outside that class (the negative power of a sum, `sin` of a non-linear argument) becomes an
//! opaque atom whose inside is itself in normal form, so the result is still exact.
//!
//! Base angles: every symbol `x` gets one base angle `x/L` for the whole expression, `L` the least
//! common multiple of the denominators of the multiples of `x` in its angles, so all of them are
//! integer multiples of it: in `sin²(q1/2) + cos(q1/3)` the base is `q1/6`, and `sin(q1/2)` is
//! `sin(3 · q1/6)`. Without fractions `L = 1` and the base is `x` itself. An integer multiple `n` of a
//! base angle is written with the Chebyshev polynomials, `cos(n y) = T_n(cos y)` and
//! `sin(n y) = sin y · U_{n−1}(cos y)`, term by term at the cost of the answer.
//!
//! The contract: for expressions polynomial in symbols, `q̇`, `q̈` and `sin`/`cos` of rational
//! combinations of symbols (plus rational multiples of π), [`is_zero`]`(a − b)` holds exactly when `a`
//! and `b` are equal as functions. The normal form is unique among expressions whose angles give each
//! symbol the same base (within one derivation, every expression of `θ = q1/2` uses `q1/2`).
//!
//! Sizes: [`try_to_poly`] refuses with an [`AlgebraError`] what passes the
//! [size limits](super::limits) (`sin(q1)^99999999`, `sin(99999 q1)`); [`to_poly`], for derived
//! expressions that cannot pass them, keeps such a part as an opaque atom instead (still exact, and
//! never taken for zero).

use super::atom;
use super::error::AlgebraError;
use super::expr::{Expr, Func, Kind};
use super::limits::{check_bits, check_terms, describe};
use super::number::Rational;
use super::poly::{Mono, Poly};
use super::symbol::Symbol;
use num_integer::Integer;
use num_traits::ToPrimitive;
use std::collections::BTreeMap;

/// The polynomial normal form of `e`; a part beyond the size limits stays an opaque atom (see
/// [`try_to_poly`] to be told instead).
pub fn to_poly(e: &Expr) -> Poly {
    Converter::new(e, false)
        .poly(e)
        .expect("the lenient conversion does not fail")
}

/// The polynomial normal form of `e`, or the error of its first part beyond the
/// [size limits](super::limits).
pub fn try_to_poly(e: &Expr) -> Result<Poly, AlgebraError> {
    Converter::new(e, true).poly(e)
}

/// The normal form of `e`, as a canonical expression (expanded, `sin²` reduced).
pub fn normal_form(e: &Expr) -> Expr {
    to_poly(e).to_expr()
}

/// [`normal_form`], refusing what passes the size limits.
pub fn try_normal_form(e: &Expr) -> Result<Expr, AlgebraError> {
    Ok(try_to_poly(e)?.to_expr())
}

/// The zero test: whether `e` is identically zero (exact within the contract of this module).
pub fn is_zero(e: &Expr) -> bool {
    to_poly(e).is_zero()
}

/// Whether `a` and `b` are equal as functions: the zero test on `a − b`, one expression, so that
/// both sides are written over the same base angles.
pub fn equal(a: &Expr, b: &Expr) -> bool {
    is_zero(&(a - b))
}

/// The base angle of each symbol in one expression: `x` → `L` for the base `x/L`; 0 when no `u64`
/// holds the least common multiple (the symbol's angles then stay opaque).
type Bases = BTreeMap<Symbol, u64>;

/// Records the denominators of the multiples of each symbol in the angles of `e`.
fn collect_bases(e: &Expr, bases: &mut Bases) {
    match e.kind() {
        Kind::Num(_) | Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) => {}
        Kind::Add(_, ts) => ts.iter().for_each(|(t, _)| collect_bases(t, bases)),
        Kind::Mul(_, fs) => fs.iter().for_each(|(b, _)| collect_bases(b, bases)),
        Kind::Fun(_, a) => {
            for (t, k) in a.terms() {
                if let Some(x) = t.as_symbol() {
                    let base = bases.entry(x.clone()).or_insert(1);
                    *base = match k.denom().to_u64() {
                        Some(d) if *base != 0 => {
                            let l = Integer::lcm(&u128::from(*base), &u128::from(d));
                            u64::try_from(l).unwrap_or(0)
                        }
                        _ => 0,
                    };
                }
            }
            collect_bases(a, bases);
        }
    }
}

/// One conversion: the expression's base angles, and whether a part beyond the size limits is an
/// error (`strict`) or an opaque atom.
struct Converter {
    bases: Bases,
    strict: bool,
}

impl Converter {
    fn new(e: &Expr, strict: bool) -> Converter {
        let mut bases = Bases::new();
        collect_bases(e, &mut bases);
        Converter { bases, strict }
    }

    /// `node` as an opaque atom where it passes a limit, or the error in strict mode.
    fn beyond(&self, node: &Expr, err: AlgebraError) -> Result<Poly, AlgebraError> {
        if self.strict {
            Err(err)
        } else {
            Ok(Poly::atom(atom::other(node)))
        }
    }

    fn poly(&self, e: &Expr) -> Result<Poly, AlgebraError> {
        Ok(match e.kind() {
            Kind::Num(r) => Poly::constant(r.clone()),
            Kind::Sym(s) => Poly::symbol(s),
            Kind::Pi => Poly::atom(atom::pi()),
            Kind::Sqrt(k) => Poly::atom(atom::sqrt(k)),
            Kind::Add(c, ts) => {
                let parts: Vec<Poly> = ts
                    .iter()
                    .map(|(t, k)| Ok(self.poly(t)?.scale(k)))
                    .collect::<Result<_, AlgebraError>>()?;
                Poly::sum(&parts).add(&Poly::constant(c.clone()))
            }
            Kind::Mul(c, fs) => {
                let mut acc = Poly::constant(c.clone());
                for (b, k) in fs {
                    let p = if *k > 0 {
                        let k = u32::try_from(*k).unwrap_or(u32::MAX);
                        match self.poly(b)?.try_pow(k) {
                            Ok(p) => p,
                            Err(err) => {
                                let node = b.pow(i64::from(k)).unwrap_or_else(|_| b.clone());
                                self.beyond(&node, err)?
                            }
                        }
                    } else {
                        self.inverse_power(b, u32::try_from(-*k).unwrap_or(u32::MAX))?
                    };
                    acc = acc.mul(&p);
                }
                acc
            }
            Kind::Fun(f, a) => self.trig(*f, a)?,
        })
    }

    /// `b^(−k)`: exact for a single term, otherwise an opaque atom `(b / lc)^(−k)` with the sum made
    /// monic by its canonical leading coefficient, so `1/(a − b)` and `−1/(b − a)` agree.
    fn inverse_power(&self, b: &Expr, k: u32) -> Result<Poly, AlgebraError> {
        let p = self.poly(b)?;
        if p.is_zero() {
            // Canonical construction never divides by a structural zero; an expression equal to zero
            // as a function (1/(sin² + cos² − 1)) has no value: keep it opaque rather than invent one.
            let opaque = b.pow(-i64::from(k)).unwrap_or_else(|_| Expr::zero());
            return Ok(Poly::atom(atom::other(&opaque)));
        }
        if let [(m, c)] = p.terms() {
            let mut exponents = Vec::with_capacity(m.factors().len());
            for &(id, e) in m.factors() {
                match i32::try_from(-i64::from(e) * i64::from(k)) {
                    Ok(x) => exponents.push((id, x)),
                    Err(_) => {
                        let err = AlgebraError::TooLarge(format!(
                            "the exponent of `({})^-{k}` is beyond {}",
                            describe(b),
                            i32::MAX
                        ));
                        return self.beyond(&b.pow(-1).unwrap_or_else(|_| b.clone()), err);
                    }
                }
            }
            let coeff = match c.pow(-i64::from(k)) {
                Some(c) if super::limits::bits(&c) <= super::limits::MAX_NUMBER_BITS => c,
                _ => {
                    let bits = u128::from(super::limits::growing_bits(c)) * u128::from(k);
                    let err = check_bits(|| format!("({})^-{k}", describe(b)), bits)
                        .err()
                        .unwrap_or(AlgebraError::DivisionByZero);
                    return self.beyond(&b.pow(-1).unwrap_or_else(|_| b.clone()), err);
                }
            };
            return Ok(Poly::term(Mono::from_sorted(exponents), coeff));
        }
        let canonical = p.to_expr();
        let lead = canonical
            .terms()
            .first()
            .map(|(_, c)| c.clone())
            .unwrap_or_else(Rational::one);
        let monic = p.scale(&lead.recip().expect("non-zero leading coefficient"));
        let id = atom::other(&monic.to_expr());
        let Some(coeff) = lead
            .pow(-i64::from(k))
            .filter(|c| super::limits::bits(c) <= super::limits::MAX_NUMBER_BITS)
        else {
            let bits = u128::from(super::limits::growing_bits(&lead)) * u128::from(k);
            let err = check_bits(|| format!("({})^-{k}", describe(b)), bits)
                .err()
                .unwrap_or(AlgebraError::DivisionByZero);
            return self.beyond(&b.pow(-1).unwrap_or_else(|_| b.clone()), err);
        };
        let k = i32::try_from(k).unwrap_or(i32::MAX);
        Ok(Poly::term(Mono::atom(id, -k), coeff))
    }

    /// `f(arg)`: expanded over the base angles when the argument is linear, opaque otherwise.
    fn trig(&self, f: Func, arg: &Expr) -> Result<Poly, AlgebraError> {
        let p = self.poly(arg)?;
        let Some(lin) = self.linear_form(&p) else {
            // Outside the contract: keep it whole, with its argument in normal form.
            let e = Expr::fun(f, &p.to_expr());
            return match e.kind() {
                Kind::Fun(..) => Ok(Poly::atom(atom::other(&e))),
                _ => self.poly(&e),
            };
        };
        let node = || Expr::fun(f, arg);
        // The answer's size, before any work: each multiple n of a base angle gives about n/2 + 1
        // terms with numbers of about n bits, and the symbols' expansions multiply.
        let terms = lin.terms.iter().fold(2u128, |acc, (_, _, n)| {
            acc.saturating_mul(u128::from(n.unsigned_abs()) + 2)
        });
        let bits: u128 = lin
            .terms
            .iter()
            .map(|(_, _, n)| u128::from(n.unsigned_abs()) + 2)
            .sum();
        if let Err(err) = check_terms(|| describe(&node()), terms)
            .and_then(|()| check_bits(|| describe(&node()), bits))
        {
            return self.beyond(&node(), err);
        }
        let (mut s, mut c) = constant_angle(&lin.constant);
        for (x, over, n) in &lin.terms {
            let (sn, cn) = multiple_angle(x, *over, *n);
            let next_s = s.mul(&cn).add(&c.mul(&sn));
            let next_c = c.mul(&cn).sub(&s.mul(&sn));
            s = next_s;
            c = next_c;
        }
        Ok(match f {
            Func::Sin => s,
            Func::Cos => c,
        })
    }

    /// The argument `Σ nᵢ (xᵢ/Lᵢ) + K` over the base angles `xᵢ/Lᵢ`, `nᵢ` integers and `K` a constant
    /// (a rational plus a rational multiple of π), if it has that form.
    fn linear_form(&self, p: &Poly) -> Option<Linear> {
        let mut terms = Vec::new();
        let mut constant = Vec::new();
        for (m, c) in p.terms() {
            match m.factors() {
                [] => constant.push(Expr::num(c.clone())),
                [(id, 1)] if atom::class(*id) == atom::Class::Pi => {
                    constant.push(&Expr::pi() * &Expr::num(c.clone()))
                }
                [(id, 1)]
                    if matches!(atom::class(*id), atom::Class::Param | atom::Class::Coord) =>
                {
                    let x = atom::symbol_of(*id)?;
                    // A base not recorded (an argument that became linear only when expanded) or
                    // one no u64 holds: outside, and opaque.
                    let over = *self.bases.get(&x).filter(|&&l| l != 0)?;
                    let n = c * &Rational::from(num_bigint::BigInt::from(over));
                    terms.push((x, over, n.to_i64()?));
                }
                _ => return None,
            }
        }
        // Canonical order of the angle symbols, so the expansion is built the same way every run.
        terms.sort();
        Some(Linear {
            terms,
            constant: Expr::sum(constant),
        })
    }
}

/// An argument `Σ nᵢ (xᵢ/Lᵢ) + K`: `(xᵢ, Lᵢ, nᵢ)`, and the constant `K`.
struct Linear {
    terms: Vec<(Symbol, u64, i64)>,
    constant: Expr,
}

/// `(sin K, cos K)` for a constant angle `K = c + r π`: `sin c`, `cos c` are a related atom pair
/// (for `c != 0`), `sin r π`, `cos r π` exact values or opaque atoms.
fn constant_angle(k: &Expr) -> (Poly, Poly) {
    let mut c = Rational::zero();
    let mut rest = Vec::new();
    for (t, coeff) in k.terms() {
        if t.is_one() {
            c = coeff;
        } else {
            rest.push(t.scale(&coeff));
        }
    }
    let pi_part = Expr::sum(rest);
    let (sr, cr) = match pi_part
        .as_rational()
        .cloned()
        .or_else(|| pi_multiple(&pi_part))
    {
        Some(r) => pi_pair(&r),
        None => (Poly::zero(), Poly::one()),
    };
    if c.is_zero() {
        return (sr, cr);
    }
    let sign = if c.is_negative() {
        Rational::int(-1)
    } else {
        Rational::one()
    };
    let c = Expr::num(c.abs());
    let sc = Poly::atom(atom::sin_const(&c)).scale(&sign);
    let cc = Poly::atom(atom::cos_const(&c));
    (sc.mul(&cr).add(&cc.mul(&sr)), cc.mul(&cr).sub(&sc.mul(&sr)))
}

/// `r` for an expression `r π`.
fn pi_multiple(e: &Expr) -> Option<Rational> {
    match e.kind() {
        Kind::Pi => Some(Rational::one()),
        Kind::Mul(c, fs) if fs.len() == 1 && fs[0].1 == 1 && matches!(fs[0].0.kind(), Kind::Pi) => {
            Some(c.clone())
        }
        _ => None,
    }
}

/// `(sin r π, cos r π)`: exact values where the table has them, otherwise `±sin b π`, `±cos b π` of the
/// base angle `b` in `(0, 1/4)` reached by the quadrant and complement identities, as a related atom
/// pair (so `sin²(π/5) + cos²(π/5)` is 1 and `cos(3π/10)` is `sin(π/5)`).
fn pi_pair(r: &Rational) -> (Poly, Poly) {
    let angle = &Expr::pi() * &Expr::num(r.clone());
    let (s, c) = (Expr::sin(&angle), Expr::cos(&angle));
    let is_value = |e: &Expr| e.symbols().is_empty() && !has_fun(e);
    if is_value(&s) && is_value(&c) {
        return (to_poly(&s), to_poly(&c));
    }
    // r mod 2 in [0, 2), then the quadrant k and the rest t in [0, 1/2).
    let half = Rational::new(1, 2).expect("non-zero");
    let two = Rational::int(2);
    let turns = num_integer::Integer::div_floor(&r.numer(), &(r.denom() * 2));
    let r0 = r - &(&two * &Rational::from(turns));
    let quadrants = num_integer::Integer::div_floor(&(&r0 * &two).numer(), &(&r0 * &two).denom());
    let k = num_traits::ToPrimitive::to_i64(&quadrants).unwrap_or(0);
    let t = &r0 - &(&half * &Rational::int(k));
    let quarter = Rational::new(1, 4).expect("non-zero");
    let (b, swap) = if t > quarter {
        (&half - &t, true)
    } else {
        (t, false)
    };
    let base = &Expr::pi() * &Expr::num(b);
    let (sb, cb) = (
        Poly::atom(atom::sin_const(&base)),
        Poly::atom(atom::cos_const(&base)),
    );
    let (st, ct) = if swap { (cb, sb) } else { (sb, cb) };
    match k {
        0 => (st, ct),
        1 => (ct, st.neg()),
        2 => (st.neg(), ct.neg()),
        _ => (ct.neg(), st),
    }
}

fn has_fun(e: &Expr) -> bool {
    match e.kind() {
        Kind::Fun(..) => true,
        Kind::Add(_, ts) => ts.iter().any(|(t, _)| has_fun(t)),
        Kind::Mul(_, fs) => fs.iter().any(|(b, _)| has_fun(b)),
        _ => false,
    }
}

/// `(sin n y, cos n y)` for the base angle `y = x/over`, as polynomials in `sin y`, `cos y`:
/// `cos n y = T_n(cos y) = Σ_k a_k cos^(n−2k) y` with `a_0 = 2^(n−1)`,
/// `a_(k+1) = −a_k (n−2k)(n−2k−1) / (4 (k+1)(n−k−1))`, and `sin n y = sin y U_(n−1)(cos y)` with
/// `U_m = Σ_k b_k cos^(m−2k) y`, `b_0 = 2^m`, `b_(k+1) = −b_k (m−2k)(m−2k−1) / (4 (k+1)(m−k))`: one
/// term at a time, no intermediate products.
fn multiple_angle(x: &Symbol, over: u64, n: i64) -> (Poly, Poly) {
    let (sin_id, cos_id) = (atom::sin_over(x, over), atom::cos_over(x, over));
    let m = n.unsigned_abs();
    if m == 0 {
        return (Poly::zero(), Poly::one());
    }
    let power_of_cos = |k: u64| Mono::atom(cos_id, i32::try_from(k).expect("within the limits"));
    let two_to = |k: u64| Rational::int(2).pow(k as i64).expect("non-zero");
    let chebyshev = |degree: u64, first: Rational, denominator_shift: u64| {
        // The terms a_k c^(degree − 2k); denominator_shift is 1 for T (n − k − 1), 0 for U (m − k).
        let mut out = Vec::new();
        let mut a = first;
        for k in 0..=degree / 2 {
            out.push((power_of_cos(degree - 2 * k), a.clone()));
            if k < degree / 2 {
                let num = -((degree - 2 * k) as i128 * (degree - 2 * k - 1) as i128);
                let den = 4 * (k + 1) as i128 * (degree - k - denominator_shift) as i128;
                a = &a * &Rational::from_bigints(num.into(), den.into()).expect("non-zero");
            }
        }
        out
    };
    let cos_terms = chebyshev(m, two_to(m - 1), 1);
    let u_terms = chebyshev(m - 1, two_to(m - 1), 0);
    let sin_terms = u_terms.into_iter().map(|(mono, a)| {
        let mut f = mono.factors().to_vec();
        f.push((sin_id, 1));
        f.sort();
        (Mono::from_sorted(f), a)
    });
    let mut s = Poly::from_terms(sin_terms);
    if n < 0 {
        s = s.neg();
    }
    (s, Poly::from_terms(cos_terms))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(i: u32) -> Expr {
        Expr::q(i)
    }

    #[test]
    fn pythagoras() {
        let e = Expr::sin(&q(1)).pow(2).unwrap() + Expr::cos(&q(1)).pow(2).unwrap();
        assert!(normal_form(&e).is_one());
    }

    #[test]
    fn angle_addition() {
        let lhs = Expr::cos(&(q(2) + q(3)));
        let rhs = Expr::cos(&q(2)) * Expr::cos(&q(3)) - Expr::sin(&q(2)) * Expr::sin(&q(3));
        assert!(equal(&lhs, &rhs));
        let double = Expr::sin(&(Expr::int(2) * q(1)));
        let product = Expr::int(2) * Expr::sin(&q(1)) * Expr::cos(&q(1));
        assert!(equal(&double, &product));
    }

    #[test]
    fn not_equal_is_not_zero() {
        assert!(!is_zero(&(Expr::sin(&q(1)) - Expr::cos(&q(1)))));
        assert!(!is_zero(&(Expr::sin(&q(1)).pow(2).unwrap() - Expr::one())));
    }

    #[test]
    fn constant_angles_obey_pythagoras() {
        let one = Expr::one();
        let e = Expr::sin(&one).pow(2).unwrap() + Expr::cos(&-one.clone()).pow(2).unwrap();
        assert!(normal_form(&e).is_one());
        let shifted = Expr::sin(&(q(1) + Expr::frac(2, 3).unwrap()));
        let expanded = Expr::sin(&q(1)) * Expr::cos(&Expr::frac(2, 3).unwrap())
            + Expr::cos(&q(1)) * Expr::sin(&Expr::frac(2, 3).unwrap());
        assert!(equal(&shifted, &expanded));
    }

    #[test]
    fn multiples_of_pi_without_table_values() {
        let pi = |n, d| Expr::pi() * Expr::frac(n, d).unwrap();
        let e = Expr::sin(&pi(1, 5)).pow(2).unwrap() + Expr::cos(&pi(1, 5)).pow(2).unwrap();
        assert!(normal_form(&e).is_one());
        assert!(equal(&Expr::cos(&pi(3, 10)), &Expr::sin(&pi(1, 5))));
        assert!(equal(&Expr::sin(&pi(-7, 5)), &Expr::sin(&pi(3, 5))));
        let a = Expr::sin(&(q(1) + pi(1, 5))).pow(2).unwrap();
        let b = Expr::one() - Expr::cos(&(q(1) + pi(1, 5))).pow(2).unwrap();
        assert!(equal(&a, &b));
    }

    #[test]
    fn inverse_of_sum_is_sign_normalised() {
        let a = Expr::symbol("a");
        let b = Expr::symbol("b");
        let x = Expr::one().div(&(&a - &b)).unwrap();
        let y = Expr::one().div(&(&b - &a)).unwrap();
        assert!(is_zero(&(x + y)));
    }

    #[test]
    fn surds_and_pi_shifts() {
        let s2 = Expr::sqrt(&Expr::int(2)).unwrap();
        let e = Expr::sin(&(q(1) + Expr::pi() * Expr::frac(1, 4).unwrap()));
        let want = (Expr::sin(&q(1)) + Expr::cos(&q(1))) * s2 * Expr::frac(1, 2).unwrap();
        assert!(equal(&e, &want));
    }
}
