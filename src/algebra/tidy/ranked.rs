//! The angle-sum pass of the trig contraction ([`super::contract`]) on a sum's ranked terms.
//!
//! A pass pairs terms `c R f(A) g(B)` by the identities of [`ANGLE_IDENTITIES`]. Here the terms
//! are factor lists over the sum's distinct bases ranked in the canonical order ([`Ranked`]):
//! candidates are bucketed by integer keys (the other factors `R` and the two angles as ranks) and
//! visited in the canonical order of `(R, A, B)` by comparing ranks ([`cmp_ranked`], the order of
//! the expressions); only merged terms and their `R` are built as expressions.
//!
//! A sheet's tidying starts from polynomials ([`super::tidy_poly_by`]), and the first pass over
//! one is the costly one (every single-angle product still there): [`contract_ranked`] takes its
//! ranked terms straight from the polynomial ([`crate::algebra::Poly::ranked`], the ranking its
//! conversion to an expression sorts by); the other rules look for their squared cosines before
//! taking a sum apart. Every later pass ranks the sum's bases ([`rank_sum`]).

use super::contract::{
    contractible, is_angle, merged_term, pass, rebuild_from, Candidate, ANGLE_IDENTITIES,
    PASS_LIMIT, TRIG_RULES,
};
use super::pythagoras::pythagoras;
use super::rule::{first_change, fixpoint};
use super::square::square_sum;
use crate::algebra::expr::{Expr, Func, Kind};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::number::Rational;
use crate::algebra::poly::{cmp_ranked, Ranked};
use std::collections::hash_map::Entry;

/// [`super::contract::contract_normal`] of the canonical sum of `ranked`, with its first pass made
/// on the ranked terms.
pub(super) fn contract_ranked(ranked: &Ranked) -> Expr {
    if !contractible_ranked(ranked) {
        return ranked.to_expr();
    }
    let e = &ranked.to_expr();
    debug_assert!(contractible(e), "contractible as ranked terms and as a sum");
    let first = square_sum(e)
        .or_else(|| angle_sum_ranked(ranked, e))
        .or_else(|| pythagoras(e));
    debug_assert_eq!(
        first,
        first_change(&TRIG_RULES, e),
        "the first pass, ranked"
    );
    match first {
        Some(next) if next != *e => fixpoint(&next, PASS_LIMIT - 1, pass),
        _ => e.clone(),
    }
}

/// [`contractible`] of the canonical sum of `ranked`: a term has two sines or cosines of angles
/// (powers counted), and there are two terms.
fn contractible_ranked(ranked: &Ranked) -> bool {
    let terms = ranked.terms.len() + usize::from(!ranked.constant.is_zero());
    terms >= 2
        && ranked.terms.iter().any(|(factors, _)| {
            let angles: i32 = factors
                .iter()
                .filter(|&&(r, _)| trig(&ranked.bases[r as usize]).is_some())
                .map(|&(_, k)| k.max(0))
                .sum();
            angles >= 2
        })
}

/// The sine or cosine of an angle ([`is_angle`]) that a base is, and the angle.
fn trig(base: &Expr) -> Option<(Func, &Expr)> {
    match base.kind() {
        Kind::Fun(f, x) if is_angle(x) => Some((*f, x)),
        _ => None,
    }
}

/// The candidates of one `(R, A, B)`: the other factors `R` by rank, the angles `A < B` by rank.
type Key = (Vec<(u32, i32)>, u32, u32);

/// The terms of the sum `e` over its distinct bases ranked in the canonical order; `None` when `e`
/// is not a sum (or, past any real expression, holds an exponent beyond `i32`).
pub(super) fn rank_sum(e: &Expr) -> Option<Ranked<'_>> {
    let Kind::Add(constant, ts) = e.kind() else {
        return None;
    };
    // Each term's factors by first-seen index, then the indices ranked.
    // A sum of the sheets names a few dozen bases at most.
    let mut index: FxHashMap<&Expr, u32> =
        FxHashMap::with_capacity_and_hasher(32, Default::default());
    let mut seen: Vec<&Expr> = Vec::with_capacity(32);
    let mut terms: Vec<(Vec<(u32, i32)>, &Rational)> = Vec::with_capacity(ts.len());
    for (t, c) in ts {
        let key = match t.kind() {
            Kind::Mul(_, fs) => {
                let mut key = Vec::with_capacity(fs.len());
                for (b, k) in fs {
                    key.push((
                        first_seen(&mut index, &mut seen, b),
                        i32::try_from(*k).ok()?,
                    ));
                }
                key
            }
            _ => vec![(first_seen(&mut index, &mut seen, t), 1)],
        };
        terms.push((key, c));
    }
    let mut order: Vec<usize> = (0..seen.len()).collect();
    order.sort_by(|&a, &b| seen[a].cmp(seen[b]));
    let mut rank = vec![0u32; seen.len()];
    for (r, &i) in order.iter().enumerate() {
        rank[i] = r as u32;
    }
    // A canonical product's factors are in the canonical order already: so are their ranks.
    for (key, _) in &mut terms {
        for f in key.iter_mut() {
            f.0 = rank[f.0 as usize];
        }
    }
    Some(Ranked {
        bases: order.iter().map(|&i| seen[i].clone()).collect(),
        terms,
        constant: constant.clone(),
    })
}

/// The index of `b` among the bases `seen` so far, which it joins if new.
fn first_seen<'a>(
    index: &mut FxHashMap<&'a Expr, u32>,
    seen: &mut Vec<&'a Expr>,
    b: &'a Expr,
) -> u32 {
    match index.entry(b) {
        Entry::Occupied(o) => *o.get(),
        Entry::Vacant(v) => {
            seen.push(b);
            *v.insert(seen.len() as u32 - 1)
        }
    }
}

/// One pass of the angle-sum identities over the terms of `e`, the canonical sum of `ranked`
/// (its terms in the same order).
pub(super) fn angle_sum_ranked(ranked: &Ranked, e: &Expr) -> Option<Expr> {
    let Kind::Add(constant, ts) = e.kind() else {
        unreachable!("a contractible expression is a sum")
    };
    debug_assert_eq!(ts.len(), ranked.terms.len(), "the sum of the ranked terms");
    // The angles, by rank in the canonical order, and each base's function and angle.
    let mut angles: Vec<&Expr> = ranked.bases.iter().filter_map(trig).map(|t| t.1).collect();
    angles.sort();
    angles.dedup();
    let funcs: Vec<Option<(Func, u32)>> = ranked
        .bases
        .iter()
        .map(|b| {
            trig(b).map(|(f, x)| {
                let a = angles.binary_search(&x).expect("collected above");
                (f, a as u32)
            })
        })
        .collect();
    // About two pairs of trig factors a term (sized once, not grown pass by pass).
    let mut buckets: FxHashMap<Key, Vec<Candidate>> =
        FxHashMap::with_capacity_and_hasher(2 * ranked.terms.len(), Default::default());
    for (index, (factors, coeff)) in ranked.terms.iter().enumerate() {
        let trig: Vec<(usize, Func, u32)> = factors
            .iter()
            .enumerate()
            .filter_map(|(i, &(r, k))| match funcs[r as usize] {
                Some((f, a)) if k > 0 => Some((i, f, a)),
                _ => None,
            })
            .collect();
        for (x, &(i, f, a)) in trig.iter().enumerate() {
            for &(j, g, b) in &trig[x + 1..] {
                if a == b {
                    continue;
                }
                let ((a, f), (b, g)) = if a < b {
                    ((a, f), (b, g))
                } else {
                    ((b, g), (a, f))
                };
                let rest: Vec<(u32, i32)> = factors
                    .iter()
                    .enumerate()
                    .filter_map(|(n, &(r, k))| {
                        let k = if n == i || n == j { k - 1 } else { k };
                        (k != 0).then_some((r, k))
                    })
                    .collect();
                buckets.entry((rest, a, b)).or_default().push(Candidate {
                    index,
                    funcs: (f, g),
                    coeff,
                });
            }
        }
    }
    // Visited in the canonical order of (R, A, B), never in hash order (the keys are distinct).
    let mut groups: Vec<(Key, Vec<Candidate>)> = buckets
        .into_iter()
        .filter(|(_, cands)| cands.len() >= 2)
        .collect();
    groups.sort_unstable_by(|(x, _), (y, _)| {
        cmp_ranked(&x.0, &y.0)
            .then(x.1.cmp(&y.1))
            .then(x.2.cmp(&y.2))
    });
    let mut used = vec![false; ts.len()];
    let mut merged = Vec::new();
    // The values `h(A ± B)` met in this pass, by identity and angles.
    let mut values: FxHashMap<(usize, u32, u32), Expr> = FxHashMap::default();
    for ((rest, a, b), cands) in &groups {
        let mut rest_expr: Option<Expr> = None;
        for (x, p) in cands.iter().enumerate() {
            for q in &cands[x + 1..] {
                if used[p.index] || used[q.index] || p.index == q.index {
                    continue;
                }
                let found = ANGLE_IDENTITIES
                    .iter()
                    .enumerate()
                    .find_map(|(k, id)| id.matching(p, q).map(|c| (k, id, c)));
                if let Some((k, id, c)) = found {
                    let h = values
                        .entry((k, *a, *b))
                        .or_insert_with(|| id.value(angles[*a as usize], angles[*b as usize]));
                    let r = rest_expr.get_or_insert_with(|| ranked.monomial(rest));
                    merged.push(merged_term(h, c, r));
                    used[p.index] = true;
                    used[q.index] = true;
                }
            }
        }
    }
    let kept = ts
        .iter()
        .zip(&used)
        .filter(|(_, u)| !**u)
        .map(|((t, c), _)| (t, c));
    rebuild_from(constant.clone(), kept, merged)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::tidy::contract::contract_normal;
    use crate::algebra::tidy::testing::{example_components, example_derivations};

    /// On the Newton–Euler vectors (both frames) and the inertia matrices of the example scenes,
    /// the contraction from ranked terms is the contraction of the expression: sums passed over,
    /// sums contracted over several passes, and sums the first pass leaves to Pythagoras.
    #[test]
    fn the_ranked_first_pass_contracts_as_the_expression_does() {
        let (mut passed, mut contracted, mut total) = (0, 0, 0);
        let names = ["elbow", "rpp", "scara", "stanford", "puma560"];
        let mut polys = example_components(&names);
        for der in example_derivations(&names) {
            polys.extend(der.mass_matrix().d.iter().flatten().cloned());
        }
        for p in polys.iter().filter(|p| (2..=200).contains(&p.len())) {
            let ranked = p.ranked().expect("symbols, sines and cosines");
            let e = p.to_expr();
            assert_eq!(ranked.to_expr(), e, "{e:?}");
            let got = contract_ranked(&ranked);
            assert_eq!(got, contract_normal(&e), "{e:?}");
            total += 1;
            passed += usize::from(!contractible_ranked(&ranked));
            contracted += usize::from(got != e);
        }
        assert!(
            passed > 50 && contracted > 100 && passed + contracted + 20 < total,
            "{passed} passed over, {contracted} contracted, of {total}"
        );
    }
}
