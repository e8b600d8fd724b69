//! The normal form of an expression and the zero test.
//!
//! [`to_poly`] expands an [`Expr`] into a [`Poly`]: products are multiplied out, `sin` and `cos` of
//! integer combinations of angle symbols (plus a constant and a rational multiple of π) are expanded
//! into products of `sin x`, `cos x` of single symbols, and `sin² x` is replaced by `1 − cos² x`.
//! What falls outside that class (the negative power of a sum, `sin` of a non-linear argument) becomes
//! an opaque atom whose inside is itself in normal form, so the result is still exact.
//!
//! The contract: for expressions polynomial in symbols, `q̇`, `q̈` and `sin`/`cos` of integer
//! combinations of symbols (plus rational multiples of π), [`is_zero`]`(a − b)` holds exactly when `a`
//! and `b` are equal as functions.

use super::atom;
use super::expr::{Expr, Func, Kind};
use super::number::Rational;
use super::poly::{Mono, Poly};
use super::symbol::Symbol;

/// The polynomial normal form of `e`.
pub fn to_poly(e: &Expr) -> Poly {
    match e.kind() {
        Kind::Num(r) => Poly::constant(r.clone()),
        Kind::Sym(s) => Poly::symbol(s),
        Kind::Pi => Poly::atom(atom::pi()),
        Kind::Sqrt(k) => Poly::atom(atom::sqrt(k)),
        Kind::Add(c, ts) => {
            let parts: Vec<Poly> = ts.iter().map(|(t, k)| to_poly(t).scale(k)).collect();
            Poly::sum(&parts).add(&Poly::constant(c.clone()))
        }
        Kind::Mul(c, fs) => {
            let mut acc = Poly::constant(c.clone());
            for (b, k) in fs {
                let p = if *k > 0 {
                    to_poly(b).pow(*k as u32)
                } else {
                    inverse_power(b, (-*k) as u32)
                };
                acc = acc.mul(&p);
            }
            acc
        }
        Kind::Fun(f, a) => trig(*f, a),
    }
}

/// The normal form of `e`, as a canonical expression (expanded, `sin²` reduced).
pub fn normal_form(e: &Expr) -> Expr {
    to_poly(e).to_expr()
}

/// The zero test: whether `e` is identically zero (exact within the contract of this module).
pub fn is_zero(e: &Expr) -> bool {
    to_poly(e).is_zero()
}

/// Whether `a` and `b` are equal as functions (the zero test on `a − b`).
pub fn equal(a: &Expr, b: &Expr) -> bool {
    to_poly(a).sub(&to_poly(b)).is_zero()
}

/// `b^(−k)`: exact for a single term, otherwise an opaque atom `(b / lc)^(−k)` with the sum made
/// monic by its canonical leading coefficient, so `1/(a − b)` and `−1/(b − a)` agree.
fn inverse_power(b: &Expr, k: u32) -> Poly {
    let p = to_poly(b);
    if p.is_zero() {
        // Canonical construction never divides by a structural zero; an expression equal to zero as a
        // function (1/(sin² + cos² − 1)) has no value: keep it opaque rather than invent one.
        let opaque = b.pow(-(k as i64)).unwrap_or_else(|_| Expr::zero());
        return Poly::atom(atom::other(&opaque));
    }
    if let [(m, c)] = p.terms() {
        let mono = Mono::from_sorted(
            m.factors()
                .iter()
                .map(|&(id, e)| (id, -e * k as i32))
                .collect(),
        );
        let coeff = c.pow(-(k as i64)).expect("non-zero coefficient");
        return Poly::term(mono, coeff);
    }
    let canonical = p.to_expr();
    let lead = canonical
        .terms()
        .first()
        .map(|(_, c)| c.clone())
        .unwrap_or_else(Rational::one);
    let monic = p.scale(&lead.recip().expect("non-zero leading coefficient"));
    let id = atom::other(&monic.to_expr());
    Poly::term(
        Mono::atom(id, -(k as i32)),
        lead.pow(-(k as i64)).expect("non-zero"),
    )
}

/// An argument `Σ nᵢ xᵢ + c + r π` with integer `nᵢ`, if the argument has that form.
struct Linear {
    terms: Vec<(Symbol, i64)>,
    constant: Expr,
}

fn linear_form(p: &Poly) -> Option<Linear> {
    let mut terms = Vec::new();
    let mut constant = Vec::new();
    for (m, c) in p.terms() {
        match m.factors() {
            [] => constant.push(Expr::num(c.clone())),
            [(id, 1)] if atom::class(*id) == atom::Class::Pi => {
                constant.push(&Expr::pi() * &Expr::num(c.clone()))
            }
            [(id, 1)] if matches!(atom::class(*id), atom::Class::Param | atom::Class::Coord) => {
                let n = c.to_i64()?;
                terms.push((atom::symbol_of(*id)?, n));
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

/// `(sin n x, cos n x)` as polynomials in `sin x`, `cos x`.
fn multiple_angle(x: &Symbol, n: i64) -> (Poly, Poly) {
    let s = Poly::atom(atom::sin(x));
    let c = Poly::atom(atom::cos(x));
    let (mut sn, mut cn) = (Poly::zero(), Poly::one());
    for _ in 0..n.unsigned_abs() {
        let next_s = sn.mul(&c).add(&cn.mul(&s));
        let next_c = cn.mul(&c).sub(&sn.mul(&s));
        sn = next_s;
        cn = next_c;
    }
    if n < 0 {
        sn = sn.neg();
    }
    (sn, cn)
}

fn trig(f: Func, arg: &Expr) -> Poly {
    let p = to_poly(arg);
    let Some(lin) = linear_form(&p) else {
        // Outside the contract: keep it whole, with its argument in normal form.
        let e = Expr::fun(f, &p.to_expr());
        return match e.kind() {
            Kind::Fun(..) => Poly::atom(atom::other(&e)),
            _ => to_poly(&e),
        };
    };
    if lin.terms.is_empty() {
        let (s, c) = constant_angle(&lin.constant);
        return match f {
            Func::Sin => s,
            Func::Cos => c,
        };
    }
    let (mut s, mut c) = constant_angle(&lin.constant);
    for (x, n) in &lin.terms {
        let (sn, cn) = multiple_angle(x, *n);
        let next_s = s.mul(&cn).add(&c.mul(&sn));
        let next_c = c.mul(&cn).sub(&s.mul(&sn));
        s = next_s;
        c = next_c;
    }
    match f {
        Func::Sin => s,
        Func::Cos => c,
    }
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
