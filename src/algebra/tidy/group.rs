//! Partial grouping: which terms of a sum share a factor in the textbook's display.
//!
//! [`super::factor`] only pulls out what *every* term shares. Textbooks also group *some* terms, and
//! by one of two habits (Spong et al., §7.4.2):
//! - gravity terms by their trig monomial: `(m1 lc1 + m2 l1) g cos q1 + m2 lc2 g cos(q1 + q2)`;
//! - inertia terms by their leading parameter, the mass (masses sort first among parameters):
//!   `m1 lc1² + m2 (l1² + lc2² + 2 l1 lc2 cos q2) + I1 + I2`.
//!
//! A [`Grouping`] names the habit; [`group`] splits a sum into groups and factors each.

use super::collect::{collect, KeyClass};
use super::factor::factor_list;
use super::memo::Memo;
use super::ranked::RankedSum;
use super::rates::group_rates;
use super::share::share_cofactors;
use crate::algebra::expr::{Expr, Kind};
use crate::algebra::number::Rational;
use crate::algebra::symbol::Symbol;
use std::collections::BTreeMap;

/// How to group the terms of a sum before factoring each group.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Grouping {
    /// By trig monomial: `m1 g cos q1 + m2 g cos q1` is `(m1 + m2) g cos q1`.
    Trig,
    /// By leading parameter (with its power): `m2 l1² + m2 lc2² + I2` is `m2 (l1² + lc2²) + I2`.
    Leading,
}

/// `e`'s terms grouped under `grouping`, each group with its common factor pulled out
/// ([`super::factor::factor_common`]), added back up. Equal to `e` as a function.
///
/// `m1 g cos(q1) + m2 g cos(q1) + m2 g sin(q2)` by [`Grouping::Trig`] is
/// `(m1 + m2) g cos(q1) + m2 g sin(q2)`.
pub fn group(e: &Expr, grouping: Grouping) -> Expr {
    group_ranked(e, None, grouping)
}

/// [`group`] of a sum whose ranked terms the contraction left (`ranks`, when it ended in ranks):
/// the grouping by leading parameter goes on from them instead of ranking the sum again.
pub(super) fn group_ranked(e: &Expr, ranks: Option<&RankedSum>, grouping: Grouping) -> Expr {
    DISPLAYED.get_or(&(e.clone(), grouping), |(e, grouping)| {
        grouped(e, ranks, *grouping)
    })
}

/// The sums [`group`] has grouped, with their results: a sheet groups some sums more than once (an
/// equation's side in the Euler–Lagrange section and in both Newton–Euler sections).
pub(super) static DISPLAYED: Memo<(Expr, Grouping), Expr> = Memo::new();

/// [`group`], computed: by leading parameter on the sum's ranked terms when its bases are plain
/// ([`super::leading`], the same result, checked against the expressions' in debug builds), else on
/// the expressions.
fn grouped(e: &Expr, ranks: Option<&RankedSum>, grouping: Grouping) -> Expr {
    if grouping == Grouping::Leading {
        if let Some(items) = super::leading::leading_groups(e, ranks) {
            let ranked = share_cofactors(&Expr::sum(items));
            debug_assert_eq!(
                ranked,
                grouped_on_expressions(e, grouping),
                "grouped on ranks as on expressions: {e:?}"
            );
            return ranked;
        }
    }
    grouped_on_expressions(e, grouping)
}

/// [`group`] on the expressions: the terms taken apart, grouped, factored and built again.
pub(super) fn grouped_on_expressions(e: &Expr, grouping: Grouping) -> Expr {
    let groups = match grouping {
        Grouping::Trig => collect(e, KeyClass::Trig),
        Grouping::Leading => by_leading_param(e),
    };
    let sum = Expr::sum(groups.into_iter().map(|(key, coeff)| {
        let factors = factor_list(&coeff);
        match grouping {
            Grouping::Trig => Expr::product(factors.into_iter().chain([key])),
            // The vectors of Newton–Euler: their rates as the book writes them.
            Grouping::Leading => Expr::product(factors.iter().map(group_rates).chain([key])),
        }
    }));
    match grouping {
        Grouping::Trig => sum,
        // A force every link beyond a joint carries, once: `−(m3 + m4) (…)`.
        Grouping::Leading => share_cofactors(&sum),
    }
}

/// The terms of `e` grouped by their leading parameter: the first parameter factor in canonical order,
/// with its power. Terms without a parameter share the key `1`. Like [`collect`]'s result.
fn by_leading_param(e: &Expr) -> Vec<(Expr, Expr)> {
    let mut groups: BTreeMap<Expr, Vec<(Expr, Rational)>> = BTreeMap::new();
    for (t, c) in e.terms() {
        let mut factors = t.factors();
        let lead = factors
            .iter()
            .position(|(b, _)| matches!(b.kind(), Kind::Sym(Symbol::Param(_))));
        let key = match lead {
            Some(i) => {
                let (b, k) = factors.remove(i);
                power(&b, k)
            }
            None => Expr::one(),
        };
        // What is left of a term is its factors as they stand when they are plain (the normal
        // form's symbols and functions): kept as (monomial, coefficient) and summed as such.
        let parts = groups.entry(key).or_default();
        if factors.is_empty() {
            parts.push((Expr::one(), c));
        } else if factors.iter().all(|(b, _)| b.is_plain_base()) {
            parts.push((Expr::monomial_of_sorted_bases(factors), c));
        } else {
            let rest = factors.into_iter().map(|(b, k)| power(&b, k));
            parts.extend(Expr::product(std::iter::once(Expr::num(c)).chain(rest)).terms());
        }
    }
    groups
        .into_iter()
        .map(|(key, parts)| {
            let mut constant = Rational::zero();
            let mut terms = Vec::with_capacity(parts.len());
            for (t, c) in parts {
                if t.is_one() {
                    constant += &c;
                } else {
                    terms.push((t, c));
                }
            }
            (key, Expr::sum_of_terms(constant, terms))
        })
        .collect()
}

fn power(b: &Expr, k: i64) -> Expr {
    b.pow(k).expect("bases of a canonical product are non-zero")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::equal;

    fn s(name: &str) -> Expr {
        Expr::symbol(name)
    }
    fn sq(e: &Expr) -> Expr {
        e.pow(2).unwrap()
    }

    /// `group(input, grouping)` is `expected` structurally, and equal to `input` as a function.
    fn check(input: Expr, grouping: Grouping, expected: Expr) {
        let got = group(&input, grouping);
        assert_eq!(got, expected, "group({input:?}, {grouping:?})");
        assert!(equal(&input, &got), "value changed: {input:?} -> {got:?}");
    }

    #[test]
    fn rules() {
        let (g, m1, m2, l1, lc1, lc2) = (s("g"), s("m1"), s("m2"), s("l1"), s("lc1"), s("lc2"));
        let (i1, i2) = (s("I1"), s("I2"));
        let (c1, s2) = (Expr::cos(&Expr::q(1)), Expr::sin(&Expr::q(2)));
        let c2 = Expr::cos(&Expr::q(2));
        // Trig: the doc example.
        check(
            Expr::sum([&m1 * &g * &c1, &m2 * &g * &c1, &m2 * &g * &s2]),
            Grouping::Trig,
            Expr::sum([
                Expr::product([&m1 + &m2, g.clone(), c1.clone()]),
                &m2 * &g * &s2,
            ]),
        );
        // Leading: Spong's d11 from its expanded form.
        let d11 = Expr::sum([
            &m1 * sq(&lc1),
            &m2 * sq(&l1),
            &m2 * sq(&lc2),
            Expr::int(2) * &m2 * &l1 * &lc2 * &c2,
            i1.clone(),
            i2.clone(),
        ]);
        let spong = Expr::sum([
            &m1 * sq(&lc1),
            Expr::product([
                m2.clone(),
                Expr::sum([sq(&l1), sq(&lc2), Expr::int(2) * &l1 * &lc2 * &c2]),
            ]),
            i1.clone(),
            i2.clone(),
        ]);
        check(d11, Grouping::Leading, spong);
        // Leading: the doc example; a term without parameters stays apart.
        check(
            Expr::sum([&m2 * sq(&l1), &m2 * sq(&lc2), i2.clone(), c1.clone()]),
            Grouping::Leading,
            Expr::sum([
                Expr::product([m2.clone(), sq(&l1) + sq(&lc2)]),
                i2.clone(),
                c1.clone(),
            ]),
        );
        // A parameter that leads one term but not another is only taken from the first.
        check(
            Expr::sum([&m1 * &l1, &l1 * &lc1]),
            Grouping::Leading,
            Expr::sum([&m1 * &l1, &l1 * &lc1]),
        );
        // The leading power is part of the key: m2² and m2 are apart.
        check(
            Expr::sum([sq(&m2) * &l1, &m2 * &lc1]),
            Grouping::Leading,
            Expr::sum([sq(&m2) * &l1, &m2 * &lc1]),
        );
    }
}
