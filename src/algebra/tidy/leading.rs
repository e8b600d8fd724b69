//! The grouping by leading parameter ([`super::Grouping::Leading`]) on a sum's ranked terms.
//!
//! [`super::group`] splits a sum by the first parameter of each term (with its power), pulls the
//! common factor out of each group's coefficient ([`super::factor::factor_list`]) and groups the
//! rates left in it ([`super::rates::group_rates`]). On the expressions, each of these steps takes
//! every term apart again and builds its pieces as expressions. Here the sum's terms are factor
//! lists over its distinct bases ranked in the canonical order ([`super::ranked::rank_sum`]): the
//! groups, their content, their common monomial and their terms divided by it are found on ranks,
//! and each group's remaining sum is built once, as the expression [`super::factor::factor_list`]
//! would give. The rates and the final products are the expressions' own ([`super::group`]), so
//! the result is the one of the passes on expressions, which the tests and the debug builds check.
//!
//! Only sums whose bases are all plain (symbols, π, sines and cosines of sums of symbols) go this
//! way: those are what the Newton–Euler vectors of a sheet hold once contracted.

use super::factor;
use super::ranked::{rank_sum, RankedSum};
use super::rates::group_rates_ranked;
use crate::algebra::expr::{Expr, Kind};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::number::Rational;
use crate::algebra::poly::{cmp_ranked, Ranked};
use crate::algebra::symbol::Symbol;
use std::borrow::Borrow;

/// A term over ranked bases: its factors `(rank, exponent)` by rank, and its coefficient.
type Term = (Vec<(u32, i32)>, Rational);

/// A group's terms without their key, and its constant (a term that was its key alone).
type Group = (Vec<Term>, Rational);

/// The terms of the sum `e` grouped by leading parameter, each group's coefficient factored with
/// its rates grouped, times the group's key: the expressions whose sum [`super::group`] gives for
/// [`super::Grouping::Leading`] before sharing cofactors. `ranks`, when given, are `e`'s ranked
/// terms (as the contraction left them); otherwise `e` is ranked here. `None` when `e` is not a
/// sum or a base is not plain.
pub(super) fn leading_groups(e: &Expr, ranks: Option<&RankedSum>) -> Option<Vec<Expr>> {
    if !matches!(e.kind(), Kind::Add(..)) {
        return None;
    }
    match ranks {
        Some(s) => groups_of(&s.bases, &s.terms, &s.constant),
        None => {
            let r = rank_sum(e)?;
            groups_of(&r.bases, &r.terms, &r.constant)
        }
    }
}

/// [`leading_groups`] of the sum `constant + Σ terms` over `bases`, its terms in the canonical order.
pub(super) fn groups_of<C: Borrow<Rational>>(
    bases: &[Expr],
    terms: &[(Vec<(u32, i32)>, C)],
    constant: &Rational,
) -> Option<Vec<Expr>> {
    if !bases.iter().all(plain) {
        return None;
    }
    let is_param: Vec<bool> = bases
        .iter()
        .map(|b| matches!(b.kind(), Kind::Sym(Symbol::Param(_))))
        .collect();
    // By leading factor (rank, exponent), or none.
    let mut groups: FxHashMap<Option<(u32, i32)>, Group> = FxHashMap::default();
    for (factors, c) in terms {
        let c: &Rational = c.borrow();
        let lead = factors.iter().position(|&(r, _)| is_param[r as usize]);
        let (key, rest) = match lead {
            Some(i) => {
                let mut rest = factors.clone();
                (Some(rest.remove(i)), rest)
            }
            None => (None, factors.clone()),
        };
        let (terms, constant) = groups
            .entry(key)
            .or_insert_with(|| (Vec::new(), Rational::zero()));
        if rest.is_empty() {
            *constant += c;
        } else {
            terms.push((rest, c.clone()));
        }
    }
    if !constant.is_zero() {
        let (_, sum) = groups
            .entry(None)
            .or_insert_with(|| (Vec::new(), Rational::zero()));
        *sum += constant;
    }
    let items = groups
        .into_iter()
        .map(|(key, (mut terms, constant))| {
            let key = key.map_or_else(Expr::one, |(r, k)| {
                bases[r as usize]
                    .pow(i64::from(k))
                    .expect("a base of a canonical product is non-zero")
            });
            // The rests in the canonical order of their monomials, as the group's sum holds them.
            terms.sort_by(|x, y| cmp_ranked(&x.0, &y.0));
            Expr::product(factored(bases, &terms, &constant).into_iter().chain([key]))
        })
        .collect();
    Some(items)
}

/// The factors [`groups_of`] makes of the one group of a sum whose terms all hold its key, given
/// the group's terms with the key divided out: the sum `constant + Σ terms` over `bases` (its terms
/// in the canonical order of their monomials). `None` when a base is not plain, `Some(None)` for
/// the zero sum (a group whose terms cancel makes nothing).
pub(super) fn key_divided<C: Borrow<Rational>>(
    bases: &[Expr],
    terms: &[(Vec<(u32, i32)>, C)],
    constant: &Rational,
) -> Option<Option<Vec<Expr>>> {
    if !bases.iter().all(plain) {
        return None;
    }
    if terms.is_empty() && constant.is_zero() {
        return Some(None);
    }
    debug_assert!(terms
        .windows(2)
        .all(|w| cmp_ranked(&w[0].0, &w[1].0).is_lt()));
    Some(Some(factored(bases, terms, constant)))
}

/// A base [`super::factor::factor_list`] leaves as it is and [`Ranked::monomial_over`] builds
/// as it stands: a symbol, π, a sine or cosine of a sum of symbols (not a surd).
fn plain(b: &Expr) -> bool {
    factor::plain(b) && b.is_plain_base()
}

/// The factors of `Σ terms + constant` (the terms sorted, none of them constant; a term or a
/// non-zero constant at least), their rates grouped (the first a number: the content, with the
/// sign): what `factor_list` of the canonical sum gives, each
/// factor through `group_rates`. The content and the common monomial come out of a sum of two
/// terms or more; a single term is its own factors.
fn factored<C: Borrow<Rational>>(
    bases: &[Expr],
    terms: &[(Vec<(u32, i32)>, C)],
    constant: &Rational,
) -> Vec<Expr> {
    match (terms, constant.is_zero()) {
        ([], _) => return vec![Expr::num(constant.clone())],
        ([(factors, c)], true) => {
            return vec![
                Expr::num(c.borrow().clone()),
                Ranked::monomial_over(bases, factors),
            ];
        }
        _ => {}
    }
    // The content: the gcd of every coefficient, the constant's too.
    let content = terms
        .iter()
        .fold(constant.clone(), |acc, (_, c)| acc.gcd(c.borrow()));
    // The common monomial: each base of the first term, to the power every term holds it with
    // (the smallest if all positive, the one nearest zero if all negative); a constant holds none.
    let first = &terms[0].0;
    let monomial: Vec<(u32, i32)> = if constant.is_zero() {
        first
            .iter()
            .filter_map(|&(r, k)| {
                let common = terms[1..].iter().try_fold(k, |acc, (fs, _)| {
                    let e = fs
                        .binary_search_by_key(&r, |&(s, _)| s)
                        .map_or(0, |i| fs[i].1);
                    match (acc.signum(), e.signum()) {
                        (1, 1) => Some(acc.min(e)),
                        (-1, -1) => Some(acc.max(e)),
                        _ => None,
                    }
                })?;
                Some((r, common))
            })
            .collect()
    } else {
        Vec::new()
    };
    // The terms divided by the monomial (which keeps them apart), in the canonical order again.
    let mut divided: Vec<Term> = terms
        .iter()
        .map(|(fs, c)| {
            // Sized for every factor up front: a term has more factors than a vector grown from
            // empty holds at first, and the copy each growth makes showed in a sheet's profile.
            let mut rest: Vec<(u32, i32)> = Vec::with_capacity(fs.len());
            rest.extend(fs.iter().filter_map(|&(r, k)| {
                let m = monomial
                    .binary_search_by_key(&r, |&(s, _)| s)
                    .map_or(0, |i| monomial[i].1);
                (k != m).then_some((r, k - m))
            }));
            (rest, c.borrow().clone())
        })
        .collect();
    divided.sort_by(|x, y| cmp_ranked(&x.0, &y.0));
    // Divided by the content, negated too when the sum would read negative (its first term with a
    // factor: one always is, since at most one term equals the monomial and a constant leaves it
    // empty): then the content takes the sign.
    let negative = divided
        .iter()
        .find(|(fs, _)| !fs.is_empty())
        .is_some_and(|(_, c)| c.is_negative());
    let (content, scale) = {
        let scale = content.recip().expect("a non-zero content");
        if negative {
            (-content, -scale)
        } else {
            (content, scale)
        }
    };
    let mut inner_constant = constant * &scale;
    let mut pairs: Vec<(Expr, Rational)> = Vec::with_capacity(divided.len());
    // Each term's factors, for the grouping of rates on ranks.
    let mut ranked: Vec<Vec<(u32, i32)>> = Vec::with_capacity(divided.len());
    for (fs, c) in divided {
        let c = &c * &scale;
        if fs.is_empty() {
            inner_constant += &c;
        } else {
            pairs.push((Ranked::monomial_over(bases, &fs), c));
            ranked.push(fs);
        }
    }
    let inner = Expr::sum_of_sorted_monomials(inner_constant, pairs);
    let mut out = Vec::with_capacity(3);
    out.push(Expr::num(content));
    if !monomial.is_empty() {
        out.push(Ranked::monomial_over(bases, &monomial));
    }
    out.push(group_rates_ranked(&inner, bases, &ranked));
    out
}

#[cfg(test)]
mod tests {
    use super::super::contract::contract_normal;
    use super::super::group::grouped_on_expressions;
    use super::super::share::share_cofactors;
    use super::super::testing::example_components;
    use super::super::Grouping;
    use super::*;
    use crate::parse::parse_expr;

    /// The grouping on ranks is the grouping on expressions: on the Newton–Euler vectors of the
    /// example scenes in both frames, contracted as a sheet shows them, and on sums made to meet
    /// the edge cases (a constant, a key alone, a negative first term, a common monomial, negative
    /// powers, non-plain bases left to the expressions).
    #[test]
    fn the_ranked_grouping_is_the_grouping_on_expressions() {
        let mut sums: Vec<Expr> = example_components(&["elbow", "rpp", "scara", "stanford"])
            .iter()
            .filter(|p| p.len() >= 2)
            .map(|p| contract_normal(&p.to_expr()))
            .collect();
        for text in [
            "m1*g + m2*g + 3",
            "m2 + m2*l1*qdd1 + m2*lc2*qdd1 - 4",
            "-m2*l1*qd1^2 - m2*l1*qd1*qd2 + I2*qdd2",
            "m2*x^3*a + m2*x^2*b + m2^2*x",
            "m2/x + m2*y/x - 1/x",
            "2*m3*qdd1*sin(q1 + q2) + 2*m3*qdd2*sin(q1 + q2) - 4*m3*a2*cos(q2)",
            "sqrt(2)*m1*a + sqrt(2)*m1*b",
            "m1*sin(2*q1 + q2) + m1*cos(q1)",
        ] {
            sums.push(parse_expr(text).unwrap());
        }
        let mut ranked = 0;
        for e in &sums {
            let want = grouped_on_expressions(e, Grouping::Leading);
            if let Some(items) = leading_groups(e, None) {
                ranked += 1;
                assert_eq!(share_cofactors(&Expr::sum(items)), want, "{e:?}");
            }
        }
        assert!(
            ranked > 200,
            "only {ranked} of {} sums on ranks",
            sums.len()
        );
    }
}
