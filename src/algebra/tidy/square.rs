//! Squares of angle sums read back: `cos²(A ± B)` out of its expansion.
//!
//! The normal form writes `cos²(q2 + q3)` as `2 cos² q2 cos² q3 − 2 cos q2 cos q3 sin q2 sin q3 + 1 −
//! cos² q2 − cos² q3`; the angle-sum rule alone would pair its first two terms into
//! `2 cos(q2 + q3) cos q2 cos q3` and leave the rest, so an inertia `I_y cos²(q2 + q3) + I_x
//! sin²(q2 + q3)` printed as two sums of three terms. This rule finds the two terms that only a square
//! has, `2k R cos² A cos² B` and `∓2k R cos A cos B sin A sin B`, and writes `k R cos²(A ± B)` in their
//! place, moving the rest of the expansion, `k R (1 − cos² A − cos² B)`, onto the other terms (where it
//! usually cancels: `cos²(q2 + q3) + sin²(q2 + q3)` is 1, and `a − a cos²(q2 + q3)` goes on to the
//! Pythagoras rule, `a sin²(q2 + q3)`). Disjoint pairs merge in one pass, visited in canonical order;
//! the angles must be ones the normal form expands ([`super::contract::is_angle`]), so the result is
//! equal to the input as a function.
//!
//! Rule, with one example: `2 cos² q2 cos² q3 − 2 cos q2 cos q3 sin q2 sin q3 + 1 − cos² q2 − cos² q3`
//! is `cos²(q2 + q3)`; with `+ 2 cos q1 cos q2 sin q1 sin q2`, `cos²(q1 − q2)`.

use super::contract::{is_angle, Term};
use crate::algebra::expr::{Expr, Func, Kind};
use crate::algebra::number::Rational;
use std::collections::BTreeMap;

/// One pass of `2k R cos² A cos² B ∓ 2k R cos A cos B sin A sin B → k R cos²(A ± B) + k R (cos² A +
/// cos² B − 1)` over the terms of `e`; `None` if no pair matches.
pub fn square_sum(e: &Expr) -> Option<Expr> {
    // Only a term with two squared cosines can start a pair: without one, the sum is not taken
    // apart (nor a single term, which has no partner).
    let squared_cosines = |fs: &[(Expr, i64)]| {
        fs.iter()
            .filter(|(b, k)| matches!(b.kind(), Kind::Fun(Func::Cos, x) if *k >= 2 && is_angle(x)))
            .count()
    };
    let Kind::Add(_, ts) = e.kind() else {
        return None;
    };
    if !ts
        .iter()
        .any(|(t, _)| matches!(t.kind(), Kind::Mul(_, fs) if squared_cosines(fs) >= 2))
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
    let mut added: Vec<Expr> = Vec::new();
    for (j, t) in terms.iter().enumerate() {
        // The squared cosines of angles, in canonical order.
        let squares: Vec<(usize, &Expr)> = t
            .factors
            .iter()
            .enumerate()
            .filter_map(|(f, (b, k))| match b.kind() {
                Kind::Fun(Func::Cos, x) if *k >= 2 && is_angle(x) => Some((f, x)),
                _ => None,
            })
            .collect();
        for (x, &(fa, a)) in squares.iter().enumerate() {
            for &(fb, b) in &squares[x + 1..] {
                if used[j] {
                    break;
                }
                let rest = t.monomial_without(&[(fa, 2), (fb, 2)]);
                let (sa, sb) = (Expr::sin(a), Expr::sin(b));
                if rest.factors().iter().any(|(f, _)| *f == sa || *f == sb) {
                    continue; // R sin A would be a square of sin A, which the normal form has not
                }
                let partner = Expr::product([
                    rest.clone(),
                    Expr::cos(a),
                    Expr::cos(b),
                    sa.clone(),
                    sb.clone(),
                ]);
                let Some(&i) = by_monomial.get(&partner) else {
                    continue;
                };
                if used[i] || i == j {
                    continue;
                }
                let plus = if terms[i].coeff == -&t.coeff {
                    true
                } else if terms[i].coeff == t.coeff {
                    false
                } else {
                    continue;
                };
                let k = &t.coeff * &Rational::new(1, 2).expect("non-zero");
                let kr = rest.scale(&k);
                let angle = if plus { a + b } else { a - b };
                let square = |x: &Expr| x.pow(2).expect("cos is not zero");
                added.push(&kr * &square(&Expr::cos(&angle)));
                added.push(&kr * &square(&Expr::cos(a)));
                added.push(&kr * &square(&Expr::cos(b)));
                added.push(-&kr);
                used[i] = true;
                used[j] = true;
            }
        }
    }
    if added.is_empty() {
        return None;
    }
    let kept = terms
        .iter()
        .zip(&used)
        .filter(|(_, u)| !**u)
        .map(|(t, _)| t.expr());
    Some(Expr::sum(kept.chain(added)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::{equal, normal_form};

    /// `square_sum(normal form of input)` is `expected` (`None`: no change), equal to `input`.
    fn check(input: Expr, expected: Option<Expr>) {
        let got = square_sum(&normal_form(&input));
        assert_eq!(got, expected, "square_sum({input:?})");
        if let Some(got) = got {
            assert!(equal(&input, &got), "value changed: {input:?} -> {got:?}");
        }
    }

    #[test]
    fn rules() {
        let (a, b) = (Expr::symbol("a"), Expr::symbol("b"));
        let (q1, q2, q3) = (Expr::q(1), Expr::q(2), Expr::q(3));
        let c2 = |x: &Expr| Expr::cos(x).pow(2).unwrap();
        let s2 = |x: &Expr| Expr::sin(x).pow(2).unwrap();
        let q23 = &q2 + &q3;
        let rows = [
            (c2(&q23), Some(c2(&q23))),
            (&a * c2(&q23), Some(&a * c2(&q23))),
            (c2(&(&q1 - &q2)), Some(c2(&(&q1 - &q2)))),
            // sin² comes back as a − a cos², which the Pythagoras rule finishes.
            (&a * s2(&q23), Some(&a - &a * c2(&q23))),
            // Other factors ride along.
            (
                &b * Expr::qd(1) * c2(&q23),
                Some(&b * Expr::qd(1) * c2(&q23)),
            ),
            // No square of a sum: products of single angles stay.
            (&a * c2(&q2) * c2(&q3), None),
            (
                Expr::cos(&q2) * Expr::cos(&q3) - Expr::sin(&q2) * Expr::sin(&q3),
                None,
            ),
        ];
        for (input, expected) in rows {
            check(input, expected);
        }
    }
}
