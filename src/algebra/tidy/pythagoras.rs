//! Pythagoras read backwards: `c R − c R cos² x` is `c R sin² x`.
//!
//! The normal form removes every `sin² x` (it writes `1 − cos² x`), so an inertia such as
//! `I_x sin² q2 + I_y cos² q2` comes out as `I_x − I_x cos² q2 + I_y cos² q2`. This rule merges the pair
//! of terms that differ by the factor `−cos² x` back into one: `I_x sin² q2 + I_y cos² q2` again.
//! One pass merges disjoint pairs, visited in canonical order; the angle `x` must be one the normal
//! form expands ([`super::contract::is_angle`]), so the result is equal to the input as a function.
//!
//! Rule, with one example: `a − a cos² q2` is `a sin² q2` (and `cos² q1 − 1` is `−sin² q1`).

use super::contract::{is_angle, rebuild, Term};
use crate::algebra::expr::{Expr, Func, Kind};
use std::collections::BTreeMap;

/// One pass of `c R − c R cos² x → c R sin² x` over the terms of `e`; `None` if no pair matches.
pub fn pythagoras(e: &Expr) -> Option<Expr> {
    // Only a term with a squared cosine of an angle starts a pair: without one (most sums once
    // their angles are contracted), the sum is not taken apart.
    let squared_cosine = |(b, k): &(Expr, i64)| {
        *k >= 2 && matches!(b.kind(), Kind::Fun(Func::Cos, x) if is_angle(x))
    };
    let Kind::Add(_, ts) = e.kind() else {
        return None; // one term has no partner
    };
    if !ts
        .iter()
        .any(|(t, _)| matches!(t.kind(), Kind::Mul(_, fs) if fs.iter().any(squared_cosine)))
    {
        return None;
    }
    let terms = Term::split(e);
    let by_monomial: BTreeMap<Expr, usize> = terms
        .iter()
        .enumerate()
        .map(|(i, t)| (t.monomial_without(&[]), i))
        .collect();
    let mut used = vec![false; terms.len()];
    let mut merged = Vec::new();
    for (j, t) in terms.iter().enumerate() {
        for (f, (b, k)) in t.factors.iter().enumerate() {
            let Kind::Fun(Func::Cos, x) = b.kind() else {
                continue;
            };
            if *k < 2 || !is_angle(x) || used[j] {
                continue;
            }
            let rest = t.monomial_without(&[(f, 2)]);
            let Some(&i) = by_monomial.get(&rest) else {
                continue;
            };
            if i == j || used[i] || terms[i].coeff != -&t.coeff {
                continue;
            }
            let sin2 = Expr::sin(x).pow(2).expect("sin x is not zero");
            merged.push(Expr::product([
                Expr::num(terms[i].coeff.clone()),
                rest,
                sin2,
            ]));
            used[i] = true;
            used[j] = true;
        }
    }
    rebuild(&terms, &used, merged)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::equal;

    /// `pythagoras(input)` is `expected` (`None`: no change), equal to `input` as a function.
    fn check(input: Expr, expected: Option<Expr>) {
        let got = pythagoras(&input);
        assert_eq!(got, expected, "pythagoras({input:?})");
        if let Some(got) = got {
            assert!(equal(&input, &got), "value changed: {input:?} -> {got:?}");
        }
    }

    #[test]
    fn rules() {
        let (a, b) = (Expr::symbol("a"), Expr::symbol("b"));
        let (q1, q2) = (Expr::q(1), Expr::q(2));
        let c2 = |x: &Expr| Expr::cos(x).pow(2).unwrap();
        let s2 = |x: &Expr| Expr::sin(x).pow(2).unwrap();
        let cos3 = Expr::cos(&q1).pow(3).unwrap();
        let rows = [
            (&a - &a * c2(&q2), Some(&a * s2(&q2))),
            (c2(&q1) - Expr::one(), Some(-s2(&q1))),
            // The inertia example: I_x − I_x cos² + I_y cos².
            (
                &a - &a * c2(&q2) + &b * c2(&q2),
                Some(&a * s2(&q2) + &b * c2(&q2)),
            ),
            // Higher powers keep the rest: cos q − cos³ q = cos q sin² q.
            (Expr::cos(&q1) - &cos3, Some(Expr::cos(&q1) * s2(&q1))),
            // No partner, or a partner with the wrong coefficient, or an angle outside the class.
            (&a * c2(&q2), None),
            (&a - Expr::int(2) * &a * c2(&q2), None),
            (
                Expr::one() - c2(&(Expr::pi() * Expr::frac(1, 5).unwrap())),
                None,
            ),
        ];
        for (input, expected) in rows {
            check(input, expected);
        }
    }
}
