//! Terms that differ only in their masses and lengths share their common part:
//! `m3 (a1² + 2 a1 a2 c2 + a2²) + m4 (a1² + 2 a1 a2 c2 + a2²)` is
//! `(m3 + m4) (a1² + 2 a1 a2 c2 + a2²)`, and `−m3 (g − a2 q̈3) − m4 (g − a2 q̈3)` is
//! `−(m3 + m4) (g − a2 q̈3)`.
//!
//! The grouping by leading parameter ([`super::Grouping::Leading`]) gives each mass its own group, so a
//! force that every link beyond a joint carries (the SCARA arm's `f_2`) reads once per mass. Here each
//! term is split as `P R`: `P` its coefficient with its parameters and coordinates (a prismatic joint's
//! `q3` is a length like `d4`, and a sum of those, `lc3 − q3`, is one too) and `R` the rest; terms
//! whose `R` is the same *and holds a sum* (a parenthesised factor, which a reader would otherwise read
//! twice) of at least [`SHARED_SYMBOLS`] symbols become `(Σ P) R`. A rest without a sum, or a short
//! one, stays apart, so the PPP arm's `m2 q̈2 + m3 q̈2` and `−m2 (g + q̈1) − m3 (g + q̈1)` are written
//! as its worked solution writes them. The result is equal to the input as a function.

use super::factor::factor_list;
use crate::algebra::expr::{Expr, Kind};
use crate::algebra::number::Rational;
use crate::algebra::symbol::Symbol;

/// A parameter or a coordinate (a prismatic joint's `q3` is a length like `d4`), or a sum of products
/// of them (`l_{c3} − q_3`).
pub fn is_length(b: &Expr) -> bool {
    let plain = |e: &Expr| {
        matches!(
            e.kind(),
            Kind::Sym(Symbol::Param(_)) | Kind::Sym(Symbol::Coord { order: 0, .. })
        )
    };
    match b.kind() {
        Kind::Add(_, ts) => ts
            .iter()
            .all(|(t, _)| plain(t) || t.factors().iter().all(|(f, _)| plain(f))),
        _ => plain(b),
    }
}

/// A term's factors `(base, exponent)`, in canonical order.
type Factors = Vec<(Expr, i64)>;

/// The term `t` as `(P, R)`, each as its factors: its length factors (`P` with the term's
/// coefficient), and the rest. A canonical product's factors are sorted, merged and its sums
/// primitive, so `R`'s expression ([`product`]) is the same exactly when its factors are: the
/// expressions are built only for the terms that share a rest.
fn split(t: &Expr) -> (Factors, Factors) {
    t.factors().into_iter().partition(|(b, _)| is_length(b))
}

/// The product of `c` (if any) and of the factors.
fn product(c: Option<&Rational>, factors: Factors) -> Expr {
    Expr::product(
        c.map(|c| Expr::num(c.clone())).into_iter().chain(
            factors
                .into_iter()
                .map(|(b, k)| b.pow(k).expect("bases of a canonical product are non-zero")),
        ),
    )
}

/// The fewest symbols a shared rest has: a shorter one (`g + q̈1`, `(q̇1 + q̇2)²`) reads as the book
/// writes it, once per mass (the PPP arm's `−m2 (g + q̈1) − m3 (g + q̈1)`, as in its worked solution).
pub const SHARED_SYMBOLS: usize = 3;

/// Whether the rest `r` (its factors) holds a sum (to a power or not) and at least
/// [`SHARED_SYMBOLS`] symbols: a factor a reader would otherwise read twice.
fn worth_sharing(r: &[(Expr, i64)]) -> bool {
    r.iter().any(|(b, _)| matches!(b.kind(), Kind::Add(..)))
        && r.iter().map(|(b, _)| symbols(b)).sum::<usize>() >= SHARED_SYMBOLS
}

/// Whether the product `t` has a sum among its factors.
fn has_a_sum_factor(t: &Expr) -> bool {
    match t.kind() {
        Kind::Mul(_, fs) => fs.iter().any(|(b, _)| matches!(b.kind(), Kind::Add(..))),
        _ => false,
    }
}

/// The symbols of `e`, each occurrence counted.
fn symbols(e: &Expr) -> usize {
    match e.kind() {
        Kind::Sym(_) => 1,
        Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) => 0,
        Kind::Fun(_, a) => symbols(a),
        Kind::Add(_, ts) => ts.iter().map(|(t, _)| symbols(t)).sum(),
        Kind::Mul(_, fs) => fs.iter().map(|(b, _)| symbols(b)).sum(),
    }
}

/// A term of a group: its `P`'s factors, and the term as (monomial, coefficient).
type Member = (Factors, (Expr, Rational));

/// `e` with the terms that share a rest holding a sum written once: `(Σ P) R`. `e` itself when no two
/// terms do.
pub fn share_cofactors(e: &Expr) -> Expr {
    let Kind::Add(_, ts) = e.kind() else {
        return e.clone();
    };
    // Most sums have at most one term with a sum factor: passed over without being taken apart.
    if ts
        .iter()
        .filter(|(t, _)| has_a_sum_factor(t))
        .take(2)
        .count()
        < 2
    {
        return e.clone();
    }
    // The terms that take no part (no sum worth sharing) go back as they stand, as (monomial,
    // coefficient); the others by their rest R, in the order they come.
    let mut constant = Rational::zero();
    let mut kept: Vec<(Expr, Rational)> = Vec::with_capacity(ts.len());
    let mut groups: Vec<(Factors, Vec<Member>)> = Vec::new();
    for (t, c) in e.terms() {
        if t.is_one() {
            constant += &c;
            continue;
        }
        let split = has_a_sum_factor(&t).then(|| split(&t));
        match split {
            Some((p, r)) if worth_sharing(&r) => {
                match groups.iter_mut().find(|(key, _)| *key == r) {
                    Some((_, members)) => members.push((p, (t, c))),
                    None => groups.push((r, vec![(p, (t, c))])),
                }
            }
            _ => kept.push((t, c)),
        }
    }
    if groups.iter().all(|(_, members)| members.len() < 2) {
        return e.clone();
    }
    for (r, members) in groups {
        if members.len() == 1 {
            kept.extend(members.into_iter().map(|(_, term)| term));
            continue;
        }
        let shared = Expr::sum(members.into_iter().map(|(p, (_, c))| product(Some(&c), p)));
        let merged = Expr::product(factor_list(&shared).into_iter().chain([product(None, r)]));
        for (t, c) in merged.terms() {
            if t.is_one() {
                constant += &c;
            } else {
                kept.push((t, c));
            }
        }
    }
    Expr::sum_of_terms(constant, kept)
}

#[cfg(test)]
mod tests {
    use super::super::testing::{check_rule, example_components};
    use super::*;
    use crate::algebra::normal::equal;
    use crate::parse::parse_expr;

    fn check(input: &str, expected: &str) {
        check_rule(share_cofactors, input, expected);
    }

    #[test]
    fn terms_that_differ_in_their_masses_share_the_rest() {
        check(
            "-m3*(g - a*qdd3) - m4*(g - a*qdd3)",
            "-(m3 + m4)*(g - a*qdd3)",
        );
        check(
            "(qd1 + qd2)^2*sin(q2)*I2yz + (qd1 + qd2)^2*sin(q2)*I3yz + I1xz*qdd1",
            "(qd1 + qd2)^2*sin(q2)*(I2yz + I3yz) + I1xz*qdd1",
        );
        // Lengths, and a prismatic joint's coordinate, go with the masses.
        check(
            "-m3*(lc3 - q3)*(a*qdd1 + s*qd1^2) + m4*(d4 - lc4 + q3)*(a*qdd1 + s*qd1^2)",
            "-(m3*(lc3 - q3) - m4*(d4 - lc4 + q3))*(a*qdd1 + s*qd1^2)",
        );
        // Rests that differ, or a rest without a sum (the PPP arm's forces), stay apart.
        check("m2*qdd2 + m3*qdd2", "m2*qdd2 + m3*qdd2");
        check(
            "-m2*(g + qdd1) - m3*(g + qdd1)",
            "-m2*(g + qdd1) - m3*(g + qdd1)",
        );
        check(
            "(qd1 + qd2)^2*I2yz + (qd1 + qd2)^2*I3yz",
            "(qd1 + qd2)^2*I2yz + (qd1 + qd2)^2*I3yz",
        );
        check(
            "-m2*g - m2*qdd1 - m3*g - m3*qdd1",
            "-m2*g - m2*qdd1 - m3*g - m3*qdd1",
        );
        check(
            "m3*(g - qdd3) + m4*(g + qdd3)",
            "m3*(g - qdd3) + m4*(g + qdd3)",
        );
        // A mass times a sum of lengths is an inertia, not a shared rest.
        check(
            "m1*lc1^2 + m2*(l1^2 + lc2^2)",
            "m1*lc1^2 + m2*(l1^2 + lc2^2)",
        );
    }

    /// On the Newton–Euler vectors of the examples in both frames, the display form with shared
    /// rests equals the vector and is a fixpoint of the sharing, and some components share one (the
    /// SCARA arm's forces, `−(m3 + m4) (…)`).
    #[test]
    fn the_example_vectors_keep_their_value() {
        let mut shared = 0;
        let names = ["elbow", "rpp", "scara", "elbow_payload", "ppp"];
        for c in example_components(&names).iter().filter(|c| c.len() <= 200) {
            let e = c.to_expr();
            let shown = super::super::tidy_poly_by(c, super::super::Grouping::Leading);
            assert!(equal(&e, &shown), "{e:?} -> {shown:?}");
            assert_eq!(share_cofactors(&shown), shown, "not a fixpoint: {shown:?}");
            let text = crate::print::to_string(&shown, crate::print::Style::Ascii);
            shared += usize::from(text.contains("(m3+m4)"));
        }
        assert!(shared > 0, "no component shares a rest");
    }

    #[test]
    fn lengths() {
        for (text, yes) in [
            ("m3", true),
            ("q3", true),
            ("lc3 - q3", true),
            ("a1*a2 + d4", true),
            ("qd1", false),
            ("cos(q1)", false),
            ("qd1 + a", false),
        ] {
            assert_eq!(is_length(&parse_expr(text).unwrap()), yes, "{text}");
        }
    }
}
