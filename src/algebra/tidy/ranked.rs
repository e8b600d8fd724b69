//! The angle-sum pass of the trig contraction ([`super::contract`]) on a sum's ranked terms.
//!
//! A pass pairs terms `c R f(A) g(B)` by the identities of [`ANGLE_IDENTITIES`]. Here the terms
//! are factor lists over the sum's distinct bases ranked in the canonical order ([`Ranked`]):
//! candidates are bucketed by integer keys (the other factors `R` and the two angles as ranks) and
//! visited in the canonical order of `(R, A, B)` by comparing ranks ([`cmp_ranked`], the order of
//! the expressions); only merged terms and their `R` are built as expressions.
//!
//! A sheet's tidying starts from polynomials ([`super::tidy_poly_by`]): [`contract_ranked`] takes
//! their ranked terms straight from the polynomial ([`crate::algebra::Poly::ranked`], the ranking
//! its conversion to an expression sorts by) and makes every pass of the angle-sum identities on
//! them ([`RankedSum`]), ranking in the contracted functions (`cos(A + B)`) as they come: the sum is
//! built as an expression once, at the end. The rules of squares look for squared cosines first;
//! when a term holds them, the passes go on over the expression ([`super::contract::pass`]), and a
//! pass over an expression ranks the sum's bases ([`rank_sum`]).

use super::contract::{
    is_angle, merged_term, pass, rebuild_from, signed_base, Candidate, ANGLE_IDENTITIES, PASS_LIMIT,
};
use super::rule::fixpoint;
use crate::algebra::expr::{Expr, Func, Kind};
use crate::algebra::fast_hash::{FxHashMap, FxHasher};
use crate::algebra::number::Rational;
use crate::algebra::poly::{cmp_ranked, Ranked};
use std::collections::hash_map::Entry;
use std::hash::{Hash, Hasher};

/// [`super::contract::contract_normal`] of the canonical sum of `ranked`, its passes of the angle-sum
/// identities made on ranked terms ([`RankedSum::contract`]); with the result's ranked terms when
/// the passes ended in ranks (the grouping goes on from them, [`super::leading`]).
pub(super) fn contract_ranked(ranked: Ranked<'_>) -> (Expr, Option<RankedSum>) {
    match contract_to_ranks(ranked) {
        Ok(sum) => (sum.to_expr(), Some(sum)),
        Err(e) => (e, None),
    }
}

/// [`contract_ranked`] without building the canonical sum when the passes end in ranks: the
/// ranked terms (`Ok`), or the contracted expression when they left the ranks (`Err`). For a
/// caller that goes on from the ranks alone (a class's quotient, [`super::classes`]).
pub(super) fn contract_to_ranks(ranked: Ranked<'_>) -> Result<RankedSum, Expr> {
    if !contractible_ranked(&ranked) {
        return Ok(RankedSum::of(ranked));
    }
    if !ranked.bases.iter().all(Expr::is_plain_base) {
        return Err(fixpoint(&ranked.to_expr(), PASS_LIMIT, pass));
    }
    #[cfg(debug_assertions)]
    let on_expressions = fixpoint(&ranked.to_expr(), PASS_LIMIT, pass);
    let contracted = RankedSum::of(ranked).contract();
    #[cfg(debug_assertions)]
    assert_eq!(
        match &contracted {
            Ok(sum) => sum.to_expr(),
            Err(e) => e.clone(),
        },
        on_expressions,
        "contracted in ranks as on expressions"
    );
    contracted
}

/// [`super::contract::contractible`] of the canonical sum of `ranked`: a term has two sines or
/// cosines of angles (powers counted), and there are two terms.
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

/// The other factors `R` of a candidate pair: its term's factors less one power of those at
/// places `i` and `j`.
#[derive(Clone, Copy)]
struct RestOf {
    term: usize,
    i: usize,
    j: usize,
}

impl RestOf {
    /// `R`'s factors by rank, in order.
    fn factors<'t>(
        self,
        terms: &'t [(&'t [(u32, i32)], &'t Rational)],
    ) -> impl Iterator<Item = (u32, i32)> + 't {
        terms[self.term]
            .0
            .iter()
            .enumerate()
            .filter_map(move |(n, &(r, k))| {
                let k = if n == self.i || n == self.j { k - 1 } else { k };
                (k != 0).then_some((r, k))
            })
    }
}

/// The candidates of one `(R, A, B)` met so far in a pass.
struct Pending<'t> {
    rest: RestOf,
    a: u32,
    b: u32,
    first: Candidate<'t>,
    more: Vec<Candidate<'t>>,
}

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
    let terms: Vec<(&[(u32, i32)], &Rational)> = ranked
        .terms
        .iter()
        .map(|(f, c)| (f.as_slice(), *c))
        .collect();
    let mut merged = Vec::new();
    // `R` as an expression, built once for the pairs of a group.
    let mut rest_expr: Option<(usize, Expr)> = None;
    let used = pair_terms(&ranked.bases, &terms, |group, rest, h, c| {
        let r = match &rest_expr {
            Some((g, r)) if *g == group => r,
            _ => &rest_expr.insert((group, ranked.monomial(rest))).1,
        };
        merged.push(merged_term(h, c, r));
    });
    let kept = ts
        .iter()
        .zip(&used)
        .filter(|(_, u)| !**u)
        .map(|((t, c), _)| (t, c));
    rebuild_from(constant.clone(), kept, merged)
}

/// The hash of a factor `(rank, exponent)` of a term's `R` ([`pair_terms`]), 0 for a power 0 (a
/// factor that is not there); `R`'s hash is the sum of its factors'.
fn factor_hash(r: u32, k: i32) -> u64 {
    if k == 0 {
        return 0;
    }
    let mut h = FxHasher::default();
    (r, k).hash(&mut h);
    // One more round of mixing: sums of the plain multiply-rotate values collide too easily.
    let x = h.finish();
    (x ^ (x >> 29)).wrapping_mul(0xbf58_476d_1ce4_e5b9)
}

/// The pairs that one pass of the angle-sum identities merges among `terms` (ranked factor lists
/// over `bases` in the canonical order of their monomials, with their coefficients). For each
/// pair, in the canonical order of `(R, A, B)`, `merge(group, R, h, c)`: the index of its group
/// (the pairs of a group share `R`), `R`'s factors, the value `h = h(A ± B)` and the first term's
/// coefficient `c`; the merged term is `c · h · R`. Returns which terms were merged.
fn pair_terms<'t>(
    bases: &[Expr],
    terms: &[(&[(u32, i32)], &'t Rational)],
    mut merge: impl FnMut(usize, &[(u32, i32)], &Expr, &'t Rational),
) -> Vec<bool> {
    // The angles, by rank in the canonical order, and each base's function and angle.
    let mut angles: Vec<&Expr> = bases.iter().filter_map(trig).map(|t| t.1).collect();
    angles.sort();
    angles.dedup();
    let funcs: Vec<Option<(Func, u32)>> = bases
        .iter()
        .map(|b| {
            trig(b).map(|(f, x)| {
                let a = angles.binary_search(&x).expect("collected above");
                (f, a as u32)
            })
        })
        .collect();
    // The candidates of each distinct `(R, A, B)`, each `R` read from its first candidate's term
    // (built as a list only for the keys of two candidates or more, the few a pass merges), found
    // by a hash of `R` and the angles: about two pairs of trig factors a term.
    let mut groups: Vec<Pending> = Vec::with_capacity(2 * terms.len());
    let mut by_hash: FxHashMap<u64, u32> =
        FxHashMap::with_capacity_and_hasher(2 * terms.len(), Default::default());
    // Groups whose hash another group has: searched after the first, in creation order.
    let mut collided: Vec<(u64, u32)> = Vec::new();
    // Each term's sines and cosines of angles (their places, functions and angles), in one list
    // cleared for each term.
    let mut trig: Vec<(usize, Func, u32)> = Vec::with_capacity(8);
    for (index, &(factors, coeff)) in terms.iter().enumerate() {
        trig.clear();
        trig.extend(factors.iter().enumerate().filter_map(|(i, &(r, k))| {
            match funcs[r as usize] {
                Some((f, a)) if k > 0 => Some((i, f, a)),
                _ => None,
            }
        }));
        if trig.len() < 2 {
            continue;
        }
        // `R`'s hash, for every pair at once: the sum of its factors' own hashes, so a pair's
        // is the term's with its two factors' hashes changed for one power less (a factor gone
        // at power 0). Groups are told apart by their keys, never by the hash (a shared hash only
        // costs a comparison), so a weaker hash changes no result.
        let whole = factors
            .iter()
            .fold(0u64, |h, &(r, k)| h.wrapping_add(factor_hash(r, k)));
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
                let rest = RestOf { term: index, i, j };
                let hash = {
                    let one_less =
                        |(r, k): (u32, i32)| factor_hash(r, k - 1).wrapping_sub(factor_hash(r, k));
                    let mut h = FxHasher::default();
                    (a, b).hash(&mut h);
                    h.finish()
                        .wrapping_add(whole)
                        .wrapping_add(one_less(factors[i]))
                        .wrapping_add(one_less(factors[j]))
                };
                let candidate = Candidate {
                    index,
                    funcs: (f, g),
                    coeff,
                };
                let same = |g: &Pending| {
                    g.a == a && g.b == b && g.rest.factors(terms).eq(rest.factors(terms))
                };
                let found = match by_hash.get(&hash) {
                    Some(&k) if same(&groups[k as usize]) => Some(k),
                    Some(_) => collided
                        .iter()
                        .find(|&&(h, k)| h == hash && same(&groups[k as usize]))
                        .map(|&(_, k)| k),
                    None => None,
                };
                match found {
                    Some(k) => groups[k as usize].more.push(candidate),
                    None => {
                        let k = groups.len() as u32;
                        match by_hash.entry(hash) {
                            Entry::Vacant(v) => {
                                v.insert(k);
                            }
                            Entry::Occupied(_) => collided.push((hash, k)),
                        }
                        groups.push(Pending {
                            rest,
                            a,
                            b,
                            first: candidate,
                            more: Vec::new(),
                        });
                    }
                }
            }
        }
    }
    // Visited in the canonical order of (R, A, B), never in hash order (the keys are distinct).
    let mut groups: Vec<(Key, Vec<Candidate>)> = groups
        .into_iter()
        .filter(|g| !g.more.is_empty())
        .map(|g| {
            let mut cands = Vec::with_capacity(1 + g.more.len());
            cands.push(g.first);
            cands.extend(g.more);
            ((g.rest.factors(terms).collect(), g.a, g.b), cands)
        })
        .collect();
    groups.sort_unstable_by(|(x, _), (y, _)| {
        cmp_ranked(&x.0, &y.0)
            .then(x.1.cmp(&y.1))
            .then(x.2.cmp(&y.2))
    });
    let mut used = vec![false; terms.len()];
    // The values `h(A ± B)` met in this pass, by identity and angles.
    let mut values: FxHashMap<(usize, u32, u32), Expr> = FxHashMap::default();
    for (group, ((rest, a, b), cands)) in groups.iter().enumerate() {
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
                    merge(group, rest, h, c);
                    used[p.index] = true;
                    used[q.index] = true;
                }
            }
        }
    }
    used
}

/// A sum's terms over ranked bases, owned: what [`contract_ranked`] passes over until no identity
/// applies, the merged angles (`cos(A + B)`) ranked in among the bases as they come. Its bases are
/// plain ([`Expr::is_plain_base`]), so its canonical sum is built from the ranks as they stand.
pub(super) struct RankedSum {
    /// The bases, by rank (a base no term holds any more may stay: it orders nothing differently).
    pub(super) bases: Vec<Expr>,
    /// The terms other than the constant, in the canonical order of their monomials (as
    /// [`Ranked::terms`]).
    pub(super) terms: Vec<Term>,
    /// The constant term.
    pub(super) constant: Rational,
}

/// A term of a [`RankedSum`]: its factors by rank and its coefficient.
pub(super) type Term = (Vec<(u32, i32)>, Rational);

/// A term a pass merged: `R`'s factors by rank, its value's base (an index among the pass's
/// distinct values) and its coefficient.
type Merged = (Vec<(u32, i32)>, usize, Rational);

/// What one pass in ranks came to.
enum Pass {
    /// No pair merged: the pass is a fixpoint.
    Unchanged,
    /// Pairs merged: the sum holds the pass's result.
    Changed,
    /// A merged value is not a plain base with a coefficient: the pass is left to the expressions
    /// (the sum is as it was).
    Unranked,
}

impl RankedSum {
    /// The terms of `ranked`, owned.
    fn of(ranked: Ranked) -> RankedSum {
        RankedSum {
            bases: ranked.bases,
            terms: ranked
                .terms
                .into_iter()
                .map(|(f, c)| (f, c.clone()))
                .collect(),
            constant: ranked.constant,
        }
    }

    /// The canonical sum.
    fn to_expr(&self) -> Expr {
        let terms: Vec<(Expr, Rational)> = self
            .terms
            .iter()
            .map(|(factors, c)| (Ranked::monomial_over(&self.bases, factors), c.clone()))
            .collect();
        Expr::sum_of_sorted_monomials(self.constant.clone(), terms)
    }

    /// Whether a term holds squared cosines of angles, at least `count` of them: what the rules
    /// of squares ([`super::square::square_sum`], two in a term) and
    /// [`super::pythagoras::pythagoras`] (one) start from.
    fn squared_cosines(&self, count: usize) -> bool {
        let cosine: Vec<bool> = self
            .bases
            .iter()
            .map(|b| matches!(trig(b), Some((Func::Cos, _))))
            .collect();
        self.terms.iter().any(|(factors, _)| {
            factors
                .iter()
                .filter(|&&(r, k)| k >= 2 && cosine[r as usize])
                .count()
                >= count
        })
    }

    /// [`super::contract::contract_normal`] of the canonical sum: passes of the angle-sum
    /// identities made in ranks while no rule of squares may apply, the rest (and a pass whose
    /// merged value is not a base) by the passes on expressions; with the ranked terms when the
    /// passes ended in ranks.
    fn contract(mut self) -> Result<RankedSum, Expr> {
        let mut passes = 0;
        let on_expressions =
            |sum: &RankedSum, passes| Err(fixpoint(&sum.to_expr(), PASS_LIMIT - passes, pass));
        while passes < PASS_LIMIT {
            // A pass tries the square of an angle sum first: a term with two squared cosines may
            // start one.
            if self.squared_cosines(2) {
                return on_expressions(&self, passes);
            }
            match self.angle_pass() {
                Pass::Changed => passes += 1,
                Pass::Unchanged => break,
                Pass::Unranked => return on_expressions(&self, passes),
            }
        }
        // No angle sum left: Pythagoras, if a squared cosine is there.
        if passes < PASS_LIMIT && self.squared_cosines(1) {
            return on_expressions(&self, passes);
        }
        Ok(self)
    }

    /// One pass of the angle-sum identities ([`pair_terms`]), the merged terms `c · h · R` put in
    /// their places among the kept ones (equal monomials added, zeros dropped).
    fn angle_pass(&mut self) -> Pass {
        let terms: Vec<(&[(u32, i32)], &Rational)> =
            self.terms.iter().map(|(f, c)| (f.as_slice(), c)).collect();
        // Each merged term: R, its base h (with its sign) as an index among the distinct `hs`,
        // and its coefficient. A pass meets few distinct values, each the same expression for
        // all its pairs (so equal at the first look, the pointer).
        let mut merged: Vec<Merged> = Vec::new();
        let mut hs: Vec<Expr> = Vec::new();
        let mut unranked = false;
        let used = pair_terms(&self.bases, &terms, |_, rest, h, c| match signed_base(h) {
            Some((sign, base)) => {
                let i = match hs.iter().position(|x| x == base) {
                    Some(i) => i,
                    None => {
                        hs.push(base.clone());
                        hs.len() - 1
                    }
                };
                merged.push((rest.to_vec(), i, c * &sign));
            }
            None => unranked = true,
        });
        if unranked {
            return Pass::Unranked;
        }
        if merged.is_empty() {
            return Pass::Unchanged;
        }
        // The merged angles' functions not among the bases yet, ranked in (every rank after one
        // moves up by the bases put before it).
        let mut fresh: Vec<Expr> = hs
            .iter()
            .filter(|b| self.bases.binary_search(b).is_err())
            .cloned()
            .collect();
        drop(terms);
        fresh.sort();
        fresh.dedup();
        if !fresh.is_empty() {
            let mut bases: Vec<Expr> = Vec::with_capacity(self.bases.len() + fresh.len());
            let mut remap: Vec<u32> = Vec::with_capacity(self.bases.len());
            let mut fresh = fresh.into_iter().peekable();
            for b in std::mem::take(&mut self.bases) {
                while let Some(f) = fresh.next_if(|f| *f < b) {
                    bases.push(f);
                }
                remap.push(bases.len() as u32);
                bases.push(b);
            }
            bases.extend(fresh);
            self.bases = bases;
            for (f, _) in &mut self.terms {
                for x in f.iter_mut() {
                    x.0 = remap[x.0 as usize];
                }
            }
            for (rest, _, _) in &mut merged {
                for x in rest.iter_mut() {
                    x.0 = remap[x.0 as usize];
                }
            }
        }
        let ranks: Vec<u32> = hs
            .iter()
            .map(|h| self.bases.binary_search(h).expect("ranked in above") as u32)
            .collect();
        let mut new: Vec<Term> = merged
            .into_iter()
            .map(|(mut f, h, c)| {
                let r = ranks[h];
                match f.binary_search_by_key(&r, |&(s, _)| s) {
                    Ok(i) if f[i].1 == -1 => {
                        f.remove(i);
                    }
                    Ok(i) => f[i].1 += 1,
                    Err(i) => f.insert(i, (r, 1)),
                }
                (f, c)
            })
            .collect();
        new.sort_by(|x, y| cmp_ranked(&x.0, &y.0));
        // The kept terms keep their order (ranks moved up in order), the merged ones go in
        // between, equal monomials added.
        let mut constant = std::mem::take(&mut self.constant);
        let mut out: Vec<Term> = Vec::with_capacity(self.terms.len());
        let mut push = |out: &mut Vec<Term>, (f, c): Term| {
            if f.is_empty() {
                constant += &c;
                return;
            }
            match out.last_mut() {
                Some((last, sum)) if *last == f => *sum += &c,
                _ => {
                    if out.last().is_some_and(|(_, sum)| sum.is_zero()) {
                        out.pop();
                    }
                    out.push((f, c));
                }
            }
        };
        let mut new = new.into_iter().peekable();
        let old = std::mem::take(&mut self.terms);
        for (term, _) in old.into_iter().zip(&used).filter(|(_, u)| !**u) {
            while let Some(n) = new.next_if(|(n, _)| cmp_ranked(n, &term.0).is_lt()) {
                push(&mut out, n);
            }
            push(&mut out, term);
        }
        for n in new {
            push(&mut out, n);
        }
        if out.last().is_some_and(|(_, c)| c.is_zero()) {
            out.pop();
        }
        self.terms = out;
        self.constant = constant;
        Pass::Changed
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::tidy::contract::contract_normal;
    use crate::algebra::tidy::testing::{example_components, example_derivations};

    /// On the Newton–Euler vectors (both frames) and the inertia matrices of the example scenes,
    /// the contraction on ranked terms is the contraction of the expression: sums passed over,
    /// sums contracted over several passes in ranks (each pass's sum the canonical sum of its
    /// ranks), and sums the passes leave to Pythagoras.
    #[test]
    fn the_ranked_passes_contract_as_the_expression_does() {
        let (mut passed, mut contracted, mut total, mut in_ranks) = (0, 0, 0, 0);
        let names = ["elbow", "rpp", "scara", "stanford", "puma560"];
        let mut polys = example_components(&names);
        for der in example_derivations(&names) {
            polys.extend(der.mass_matrix().d.iter().flatten().cloned());
        }
        for p in polys.iter().filter(|p| (2..=200).contains(&p.len())) {
            let ranked = p.ranked().expect("symbols, sines and cosines");
            let e = p.to_expr();
            assert_eq!(ranked.to_expr(), e, "{e:?}");
            // Pass by pass in ranks, each pass the expressions' pass of the sum before it.
            let mut sum = RankedSum::of(p.ranked().expect("ranked above"));
            let mut ranked_passes = 0;
            while !sum.squared_cosines(2) {
                let before = sum.to_expr();
                match sum.angle_pass() {
                    Pass::Changed => {
                        assert_eq!(Some(sum.to_expr()), pass(&before), "{before:?}");
                        ranked_passes += 1;
                    }
                    Pass::Unchanged | Pass::Unranked => break,
                }
            }
            in_ranks += usize::from(ranked_passes >= 2);
            passed += usize::from(!contractible_ranked(&ranked));
            let got = contract_ranked(ranked).0;
            assert_eq!(got, contract_normal(&e), "{e:?}");
            total += 1;
            contracted += usize::from(got != e);
        }
        assert!(
            passed > 50 && contracted > 100 && passed + contracted + 20 < total && in_ranks >= 4,
            "{passed} passed over, {contracted} contracted ({in_ranks} over two passes in ranks), \
             of {total}"
        );
    }
}
