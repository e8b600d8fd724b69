//! Joint rates as the book writes them: terms that differ only in their rates share one factor,
//! `s12 q̈1 + s12 q̈2` is `s12 (q̈1 + q̈2)`, and a perfect square of rates comes back whole,
//! `c12 q̇1² + 2 c12 q̇1 q̇2 + c12 q̇2²` is `c12 (q̇1 + q̇2)²`.
//!
//! The Newton–Euler vectors of a revolute chain are made of exactly these: `α_i` holds
//! `q̈1 + … + q̈i` and `ω_i × (ω_i × r)` holds `(q̇1 + … + q̇i)²` (Spong, Hutchinson and Vidyasagar,
//! §7.5 and its planar elbow example), which the expanded normal form spreads over many terms.
//!
//! [`group_rates`] splits each term of a sum into its rates (`q̇`, `q̈`) and the rest `N` (parameters,
//! sines and cosines); terms with the same `N` and the same degree in the rates form a group:
//! - of degree 2 in `q̇` only, when it is `N k L²` for a linear form `L = Σ l_i q̇_i` (integers, the
//!   first positive, no common divisor), it is written so;
//! - otherwise it is `N k (Σ a_i r_i)`, `r_i` its rate monomials, with `k` the rational content of
//!   the coefficients (negative when the first would be) and integer `a_i`: `s12 (q̈1 + q̈2)`, and
//!   the book's Coriolis habit `−l1 lc2 s2 (2 q̇1 q̇2 + q̇2²)`.
//!
//! Then terms that agree in everything but their parameters and coordinates (a prismatic joint's
//! `q3` is a length like `d4`), when that rest holds a rate, share it:
//! `(q̇1 + q̇2)² a2 d4 s4 − (q̇1 + q̇2)² a2 lc4 s4` is `(d4 − lc4) (q̇1 + q̇2)² a2 s4`; and a base every
//! term then has comes out of the sum.
//!
//! Groups of one term, and sums without rates, are left as they are. The result is equal to the input
//! as a function; the order of its terms is the canonical one.

use super::factor::factor_list;
use super::memo::Memo;
use crate::algebra::expr::{Expr, Kind};
use crate::algebra::fast_hash::{FxHashMap, FxHashSet, FxHasher};
use crate::algebra::number::Rational;
use crate::algebra::poly::Ranked;
use crate::algebra::symbol::Symbol;
use std::collections::BTreeMap;
use std::hash::{Hash, Hasher};

/// The order of a rate symbol (`q̇`: 1, `q̈`: 2) and its coordinate's index, for a base that is one.
fn rate(base: &Expr) -> Option<(u8, u32)> {
    match base.kind() {
        Kind::Sym(Symbol::Coord { index, order }) if *order > 0 => Some((*order, *index)),
        _ => None,
    }
}

/// A monomial of rates: its factors `((order, index), exponent)`, `order` 1 for `q̇`, 2 for `q̈`.
type RateMonomial = Vec<((u8, u32), i64)>;

/// One term split: its coefficient, its rates and the rest.
struct Split {
    coeff: Rational,
    rates: RateMonomial,
    rest: Expr,
    /// The whole term's monomial (rates and rest), as the sum holds it.
    monomial: Expr,
}

fn split(t: Expr, coeff: Rational) -> Split {
    let mut rates = Vec::new();
    let mut rest = Vec::new();
    for (b, k) in t.factors() {
        match rate(&b) {
            Some(r) if k > 0 => rates.push((r, k)),
            _ => rest.push((b, k)),
        }
    }
    let rest = if rest.iter().all(|(b, _)| b.is_plain_base()) {
        Expr::monomial_of_sorted_bases(rest)
    } else {
        Expr::product(
            rest.into_iter()
                .map(|(b, k)| b.pow(k).expect("bases of a canonical product are non-zero")),
        )
    };
    Split {
        coeff,
        rates,
        rest,
        monomial: t,
    }
}

/// The rate symbol's expression.
fn rate_expr((order, index): (u8, u32)) -> Expr {
    Expr::sym(Symbol::Coord { index, order })
}

/// `a / b` for a non-zero `b` (a term's coefficient, or a product of them).
fn div(a: &Rational, b: &Rational) -> Rational {
    a * &b.recip().expect("a coefficient of a term is non-zero")
}

/// `Σ c_i r_i` (rate monomials `r_i`) as `k (Σ a_i r_i)` with integer `a_i` without a common
/// divisor and the first `a_i` positive.
fn linear(terms: &[(Expr, Rational)]) -> (Rational, Expr) {
    let mut k = terms.iter().fold(Rational::zero(), |g, (_, c)| g.gcd(c));
    if terms[0].1.is_negative() {
        k = -k;
    }
    let inner = Expr::sum(terms.iter().map(|(r, c)| r.scale(&div(c, &k))));
    (k, inner)
}

/// `P = Σ a_ij q̇_i q̇_j` as `(k, L)` with `P = k L²`, `L = Σ l_i q̇_i` (integers without a common
/// divisor, the first positive), if it is one.
fn square(terms: &[(RateMonomial, Rational)]) -> Option<(Rational, Expr)> {
    // The coefficients of the squares and of the products, by index.
    let mut diag: BTreeMap<u32, Rational> = BTreeMap::new();
    let mut cross: BTreeMap<(u32, u32), Rational> = BTreeMap::new();
    for (rates, c) in terms {
        match rates.as_slice() {
            [((1, i), 2)] => {
                diag.insert(*i, c.clone());
            }
            [((1, i), 1), ((1, j), 1)] => {
                cross.insert((*i.min(j), *i.max(j)), c.clone());
            }
            _ => return None,
        }
    }
    // l_i = ±sqrt(a_ii / a_11) with the sign of a_1i (l_1 = 1): the square's coefficient is a_11.
    let (&first, k) = diag.iter().next()?;
    let k = k.clone();
    let mut l: BTreeMap<u32, Rational> = BTreeMap::new();
    for (&i, a) in &diag {
        let ratio = div(a, &k);
        let root = ratio.sqrt_exact()?;
        let root = if i == first {
            root
        } else {
            let c = cross.get(&(first, i))?;
            if c.is_negative() == k.is_negative() {
                root
            } else {
                -root
            }
        };
        l.insert(i, root);
    }
    // Every coefficient of k L² must be there, and nothing else.
    let indices: Vec<u32> = l.keys().copied().collect();
    let pairs = indices.len() * (indices.len() - 1) / 2;
    if cross.len() != pairs {
        return None;
    }
    let two = Rational::int(2);
    for (x, i) in indices.iter().enumerate() {
        for j in &indices[x + 1..] {
            let want = &(&(&two * &k) * &l[i]) * &l[j];
            if cross.get(&(*i, *j)) != Some(&want) {
                return None;
            }
        }
    }
    // Integer l_i: scale by the lcm of their denominators (k by its square).
    let small = l.values().try_fold(1i64, |m, r| {
        let (_, d) = r.as_small()?;
        m.checked_mul(d / num_integer::Integer::gcd(&m, &d))
    });
    let den = match small {
        Some(d) => Rational::int(d),
        None => Rational::from(l.values().fold(num_bigint::BigInt::from(1), |m, r| {
            num_integer::Integer::lcm(&m, &r.denom())
        })),
    };
    let form = Expr::sum(
        l.iter()
            .map(|(&i, li)| rate_expr((1, i)).scale(&(li * &den))),
    );
    let k = div(&k, &(&den * &den));
    Some((k, form))
}

/// `e` with its rates grouped as the module says; `e` itself when it is not a sum or has no group
/// to write.
pub fn group_rates(e: &Expr) -> Expr {
    // Most sums of a sheet (D(q), c_ijk, g) hold no rate: decided without taking them apart.
    if !matches!(e.kind(), Kind::Add(..)) || !has_rate(e) {
        return e.clone();
    }
    if nothing_to_group(e) {
        return e.clone();
    }
    GROUPED.get_or(e, grouped)
}

/// The sums [`group_rates`] has grouped, with their results: the vectors of a Newton–Euler section
/// repeat a few factors many times (the SCARA arm's sheet groups 60 distinct sums in 178 calls).
pub(super) static GROUPED: Memo<Expr, Expr> = Memo::new();

/// [`group_rates`] of `e`, the canonical sum whose `i`-th term (the constant aside) has the factors
/// `terms[i]` over the plain `bases` (by rank): the same result, the terms split into their rates
/// and the rest on their ranks rather than taken apart again (the grouping by leading parameter,
/// [`super::leading`], has them: the SCARA arm's sheet groups its rates in a tenth fewer
/// instructions so, 0.5 M of its 34 M). Checked against [`group_rates`] in debug builds.
pub(super) fn group_rates_ranked(e: &Expr, bases: &[Expr], terms: &[Vec<(u32, i32)>]) -> Expr {
    if !matches!(e.kind(), Kind::Add(..)) || !has_rate(e) || nothing_to_group(e) {
        return e.clone();
    }
    let out = GROUPED.get_or(e, |e| grouped_ranked(e, bases, terms));
    debug_assert_eq!(
        out,
        grouped(e),
        "rates grouped on ranks as on expressions: {e:?}"
    );
    out
}

/// A term's factors by rank, `(rank, exponent)`.
type Factors = Vec<(u32, i32)>;

/// [`grouped`] of the sum `e` with rates, whose terms have the factors `ranked` over `bases`
/// ([`group_rates_ranked`]). The terms as they stand and the groups of rates are found on ranks,
/// and so are the groups of [`collect_parameters`] among the terms as they stand: a group's rest
/// there is a monomial of plain bases, which the rest of a product of grouped rates (it holds
/// their sum) never equals, so the two kinds of terms are collected apart.
fn grouped_ranked(e: &Expr, bases: &[Expr], ranked: &[Vec<(u32, i32)>]) -> Expr {
    let Kind::Add(constant, ts) = e.kind() else {
        unreachable!("grouped only for a sum")
    };
    debug_assert_eq!(ts.len(), ranked.len(), "a factor list for each term");
    let rates: Vec<Option<(u8, u32)>> = bases.iter().map(rate).collect();
    // By (rest, degree in the rates), the terms of a group in canonical order.
    let mut groups: FxHashMap<(Factors, i64), Vec<usize>> = FxHashMap::default();
    let mut any_rate = false;
    for (i, fs) in ranked.iter().enumerate() {
        let mut rest = Vec::with_capacity(fs.len());
        let mut degree = 0;
        for &(r, k) in fs {
            match rates[r as usize] {
                Some(_) if k > 0 => degree += i64::from(k),
                _ => rest.push((r, k)),
            }
        }
        any_rate |= degree > 0;
        groups.entry((rest, degree)).or_default().push(i);
    }
    if !any_rate {
        return e.clone();
    }
    let term = |i: usize| ts[i].0.scale(&ts[i].1);
    let mut changed = false;
    // Each group of rates as `k · R · inner` (`R` its rest by rank), collected on ranks below.
    let mut products: Vec<RateProduct> = Vec::new();
    let mut standing: Vec<usize> = Vec::new();
    for ((rest, degree), members) in groups {
        if members.len() < 2 || degree == 0 {
            standing.extend(members);
            continue;
        }
        let pairs: Vec<(RateMonomial, Rational)> = members
            .iter()
            .map(|&i| {
                let rates: RateMonomial = ranked[i]
                    .iter()
                    .filter_map(|&(r, k)| match rates[r as usize] {
                        Some(rate) if k > 0 => Some((rate, i64::from(k))),
                        _ => None,
                    })
                    .collect();
                (rates, ts[i].1.clone())
            })
            .collect();
        let (k, inner) = rate_form(&pairs, degree);
        changed = true;
        products.push(RateProduct { k, rest, inner });
    }
    let (mut kept, mut collected) = collect_rate_products(bases, products);
    // The terms as they stand whose factors other than parameters and coordinates hold a rate, by
    // those factors: each term's parameters and coordinates with its coefficient.
    let mut by_rest: FxHashMap<Factors, Vec<(Factors, usize)>> = FxHashMap::default();
    for i in standing {
        let (params, others): (Factors, Factors) = ranked[i]
            .iter()
            .partition(|&&(r, _)| is_length(&bases[r as usize]));
        if others.iter().any(|&(r, _)| rates[r as usize].is_some()) {
            by_rest.entry(others).or_default().push((params, i));
        } else {
            kept.push(term(i));
        }
    }
    for (others, parts) in by_rest {
        if let [(_, i)] = parts.as_slice() {
            kept.push(term(*i));
            continue;
        }
        collected = true;
        let sum = Expr::sum(
            parts
                .iter()
                .map(|(params, i)| Ranked::monomial_over(bases, params).scale(&ts[*i].1)),
        );
        kept.push(Expr::product(
            factor_list(&sum)
                .into_iter()
                .chain([Ranked::monomial_over(bases, &others)]),
        ));
    }
    if !constant.is_zero() {
        kept.push(Expr::num(constant.clone()));
    }
    finish(e, kept, changed || collected)
}

/// A group of terms with their rates grouped, `k · R · inner` ([`grouped_ranked`]): `R` the
/// rest the terms share, by rank, and `inner` the rates' form ([`rate_form`]), a sum or the square
/// of one.
struct RateProduct {
    k: Rational,
    rest: Factors,
    inner: Expr,
}

impl RateProduct {
    /// The product as an expression.
    fn to_expr(&self, bases: &[Expr]) -> Expr {
        Expr::product([
            Expr::num(self.k.clone()),
            Ranked::monomial_over(bases, &self.rest),
            self.inner.clone(),
        ])
    }
}

/// [`collect_parameters`] of the rate products' expressions, found on their ranks: two products
/// agree in everything but their parameters and coordinates when the rest of their `R` does and
/// their `inner` is the same (their only factor that is not a base of the sum, and the one that
/// holds the rates, so every product is collected with its like). Only the products left alone
/// and the collected sums are built, not every product to be taken apart again. A product with
/// nothing but `inner` (`R` = 1, whose expression a lone number may be distributed over) sends
/// them all the way of the expressions.
fn collect_rate_products(bases: &[Expr], products: Vec<RateProduct>) -> (Vec<Expr>, bool) {
    if products.iter().any(|p| p.rest.is_empty()) {
        return collect_parameters(products.iter().map(|p| p.to_expr(bases)).collect());
    }
    // By (the rest less its parameters and coordinates, inner): the products, each with its
    // parameters and coordinates. A sum has a few groups: searched in turn.
    type Key = (Factors, Expr);
    let mut groups: Vec<(Key, Vec<(Factors, RateProduct)>)> = Vec::with_capacity(products.len());
    for p in products {
        let (params, others): (Factors, Factors) = p
            .rest
            .iter()
            .partition(|&&(r, _)| is_length(&bases[r as usize]));
        match groups
            .iter_mut()
            .find(|((o, inner), _)| *o == others && *inner == p.inner)
        {
            Some((_, parts)) => parts.push((params, p)),
            None => groups.push(((others, p.inner.clone()), vec![(params, p)])),
        }
    }
    let mut kept = Vec::with_capacity(groups.len());
    let mut collected = false;
    for ((others, inner), parts) in groups {
        if let [(_, p)] = parts.as_slice() {
            kept.push(p.to_expr(bases));
            continue;
        }
        collected = true;
        let sum = Expr::sum(
            parts
                .iter()
                .map(|(params, p)| Ranked::monomial_over(bases, params).scale(&p.k)),
        );
        let rest = Expr::product([Ranked::monomial_over(bases, &others), inner]);
        kept.push(Expr::product(factor_list(&sum).into_iter().chain([rest])));
    }
    (kept, collected)
}

/// The sum of the `out` terms (their common factors taken out) when the grouping `changed`
/// anything, else `e` itself.
fn finish(e: &Expr, out: Vec<Expr>, changed: bool) -> Expr {
    if !changed {
        return e.clone();
    }
    let sum = Expr::sum(out);
    // What every term now shares comes out: `(d4 − lc4) (… + …)` (without a shared base, the
    // canonical sum would only take the content back in).
    if shares_a_base(&sum) {
        Expr::product(factor_list(&sum))
    } else {
        sum
    }
}

/// A group of terms with one rest and `degree` in their rates (`pairs`: each term's rates and
/// coefficient) as `k · inner`: the square of a linear form when it is one, else `k` times the
/// sum of the rate monomials with integer coefficients ([`square`], [`linear`]).
fn rate_form(pairs: &[(RateMonomial, Rational)], degree: i64) -> (Rational, Expr) {
    // The form of the coefficients over the first one, remembered: `k` scales with them and the
    // inner sum does not (every choice below is of ratios and signs relative to the first), and
    // a few forms recur in most sums (`(q̇1 + q̇2)²`, `q̈1 + q̈2`).
    let first = pairs[0].1.clone();
    let over = first.recip().expect("a coefficient of a term is non-zero");
    let key: Vec<(RateMonomial, Rational)> = pairs
        .iter()
        .map(|(r, c)| {
            (
                r.clone(),
                if c == &first {
                    Rational::one()
                } else {
                    c * &over
                },
            )
        })
        .collect();
    let (k, inner) = FORMS.get_or_owned(key, |key| rate_form_of(key, degree));
    (&k * &first, inner)
}

/// The forms [`rate_form`] has found, by the rates and coefficients over the first (the first 1).
pub(super) static FORMS: Memo<Vec<(RateMonomial, Rational)>, (Rational, Expr)> = Memo::new();

/// [`rate_form`] of the coefficients as they are.
fn rate_form_of(pairs: &[(RateMonomial, Rational)], degree: i64) -> (Rational, Expr) {
    let square = (degree == 2).then(|| square(pairs)).flatten();
    match square {
        Some((k, form)) => (k, form.pow(2).expect("a non-zero form")),
        None => {
            let terms: Vec<(Expr, Rational)> = pairs
                .iter()
                .map(|(rates, c)| {
                    let m = Expr::product(
                        rates
                            .iter()
                            .map(|&(r, k)| rate_expr(r).pow(k).expect("a rate is non-zero")),
                    );
                    (m, c.clone())
                })
                .collect();
            linear(&terms)
        }
    }
}

/// [`group_rates`] of a sum with rates, term by term.
fn grouped(e: &Expr) -> Expr {
    let terms = e.terms();
    let split: Vec<Split> = terms.into_iter().map(|(t, c)| split(t, c)).collect();
    if split.iter().all(|s| s.rates.is_empty()) {
        return e.clone();
    }
    // By (rest, degree in the rates). The terms of a group stay in canonical order; the groups may
    // come in any, since their results are added into a canonical sum.
    let mut groups: FxHashMap<(Expr, i64), Vec<Split>> = FxHashMap::default();
    for s in split {
        let degree = s.rates.iter().map(|(_, k)| k).sum();
        groups.entry((s.rest.clone(), degree)).or_default().push(s);
    }
    let mut changed = false;
    let mut out: Vec<Expr> = Vec::new();
    for ((rest, degree), members) in groups {
        let as_they_stand = |members: &[Split]| -> Vec<Expr> {
            members.iter().map(|s| s.monomial.scale(&s.coeff)).collect()
        };
        if members.len() < 2 || degree == 0 {
            out.extend(as_they_stand(&members));
            continue;
        }
        let pairs: Vec<(RateMonomial, Rational)> = members
            .iter()
            .map(|s| (s.rates.clone(), s.coeff.clone()))
            .collect();
        let (k, inner) = rate_form(&pairs, degree);
        changed = true;
        out.push(Expr::product([Expr::num(k), rest.clone(), inner]));
    }
    let (out, collected) = collect_parameters(out);
    finish(e, out, changed || collected)
}

/// Whether no two terms of the sum `e` can share a factor here: no two with a rate agree in their
/// rest and degree (the groups of rates), and no two agree in the factors other than parameters and
/// coordinates where those hold a rate (the groups of [`collect_parameters`]). Decided on hashes of
/// the terms' factors as they stand; a shared hash only sends the sum down the full path.
fn nothing_to_group(e: &Expr) -> bool {
    let Kind::Add(_, ts) = e.kind() else {
        return true;
    };
    let mut rests: FxHashSet<u64> = FxHashSet::default();
    let mut others: FxHashSet<u64> = FxHashSet::default();
    for (t, _) in ts {
        let one;
        let factors: &[(Expr, i64)] = match t.kind() {
            Kind::Mul(_, fs) => fs,
            _ => {
                one = [(t.clone(), 1)];
                &one
            }
        };
        let (mut rest, mut other) = (FxHasher::default(), FxHasher::default());
        let (mut degree, mut other_rate) = (0, false);
        for (b, k) in factors {
            match rate(b) {
                Some(_) if *k > 0 => degree += k,
                _ => (b, k).hash(&mut rest),
            }
            if !is_length(b) {
                (b, k).hash(&mut other);
                other_rate |= has_rate(b);
            }
        }
        degree.hash(&mut rest);
        if degree > 0 && !rests.insert(rest.finish()) {
            return false;
        }
        if other_rate && !others.insert(other.finish()) {
            return false;
        }
    }
    true
}

/// A parameter or a coordinate (a prismatic joint's `q3` is a length like `d4`).
fn is_length(b: &Expr) -> bool {
    matches!(
        b.kind(),
        Kind::Sym(Symbol::Param(_)) | Kind::Sym(Symbol::Coord { order: 0, .. })
    )
}

/// Whether some base is a factor of every term of the sum `e`.
fn shares_a_base(e: &Expr) -> bool {
    // A constant term has no base; a single term has no other to share with.
    let Kind::Add(constant, ts) = e.kind() else {
        return false;
    };
    if !constant.is_zero() || ts.len() < 2 {
        return false;
    }
    let has = |t: &Expr, b: &Expr| match t.kind() {
        Kind::Mul(_, fs) => fs.iter().any(|(c, _)| c == b),
        _ => t == b,
    };
    let (first, rest) = ts.split_first().expect("two terms");
    match first.0.kind() {
        Kind::Mul(_, fs) => fs.iter().any(|(b, _)| rest.iter().all(|(t, _)| has(t, b))),
        _ => rest.iter().all(|(t, _)| has(t, &first.0)),
    }
}

/// Whether `e` holds a rate (`q̇` or `q̈`) anywhere.
fn has_rate(e: &Expr) -> bool {
    match e.kind() {
        Kind::Sym(Symbol::Coord { order, .. }) => *order > 0,
        Kind::Add(_, ts) => ts.iter().any(|(t, _)| has_rate(t)),
        Kind::Mul(_, fs) => fs.iter().any(|(b, _)| has_rate(b)),
        Kind::Fun(_, a) => has_rate(a),
        Kind::Num(_) | Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) => false,
    }
}

/// Terms that agree in everything but their parameters and coordinates (a prismatic joint's `q3`
/// is a length like `d4`) and coefficient, when that holds a rate, share it, the rest summed and
/// factored: `(q̇1 + q̇2)² a2 d4 s4 − (q̇1 + q̇2)² a2 lc4 s4` is
/// `(q̇1 + q̇2)² a2 (d4 − lc4) s4`. Whether any did.
fn collect_parameters(terms: Vec<Expr>) -> (Vec<Expr>, bool) {
    type Factors = Vec<(Expr, i64)>;
    let power = |(b, k): (Expr, i64)| b.pow(k).expect("bases of a canonical product are non-zero");
    let mut kept = Vec::with_capacity(terms.len());
    // The rest (with a rate), by its factors -> each term's coefficient times its parameters, and
    // the term. Keyed by the factor list, which is the rest's expression's as it stands (a
    // canonical product's factors are sorted, merged, and its sums primitive): the expression is
    // built only for a group of two terms or more.
    let mut groups: FxHashMap<Factors, Vec<(Expr, Expr)>> = FxHashMap::default();
    for t in terms {
        let (c, m) = t.split_coeff();
        let (params, others): (Factors, Factors) =
            m.factors().into_iter().partition(|(b, _)| is_length(b));
        if !others.iter().any(|(b, _)| has_rate(b)) {
            kept.push(t);
            continue;
        }
        // Parameters and coordinates are symbols: their product is one as it stands.
        let part = Expr::monomial_of_sorted_bases(params).scale(&c);
        groups.entry(others).or_default().push((part, t));
    }
    let mut collected = false;
    for (others, mut parts) in groups {
        if parts.len() == 1 {
            kept.push(parts.pop().expect("one part").1);
            continue;
        }
        collected = true;
        let rest = if others.iter().all(|(b, _)| b.is_plain_base()) {
            Expr::monomial_of_sorted_bases(others)
        } else {
            Expr::product(others.into_iter().map(power))
        };
        let sum = Expr::sum(parts.into_iter().map(|(part, _)| part));
        kept.push(Expr::product(factor_list(&sum).into_iter().chain([rest])));
    }
    (kept, collected)
}

#[cfg(test)]
mod tests {
    use super::super::testing::{check_rule, example_components};
    use super::*;
    use crate::algebra::normal::equal;
    use crate::parse::parse_expr;

    /// The Newton–Euler vectors of the example scenes in both frames, each component contracted
    /// as [`super::super::tidy_poly_by`] gives it to the grouping.
    fn example_sums() -> Vec<Expr> {
        let mut out = Vec::new();
        for c in example_components(&["elbow", "rpp", "scara", "elbow_payload"]) {
            let e = super::super::contract::contract_normal(&c.to_expr());
            out.extend(factor_list(&e));
            out.push(e);
        }
        out
    }

    /// The grouping on ranks, whose rate products are collected on their ranks
    /// ([`collect_rate_products`]), is the grouping on expressions: on the example sums, on
    /// products that share everything but their lengths (collected, with a length common to
    /// both), and on a group of rates with no other factor (the products' expressions then).
    #[test]
    fn rate_products_collect_on_ranks_as_on_expressions() {
        let mut sums = example_sums();
        for text in [
            // (q̇1 + q̇2)² a2 s4 with d4 and with −lc4: collected as a2 (d4 − lc4) (…).
            "a2*d4*sin(q4)*qd1^2 + 2*a2*d4*sin(q4)*qd1*qd2 + a2*d4*sin(q4)*qd2^2 \
             - a2*lc4*sin(q4)*qd1^2 - 2*a2*lc4*sin(q4)*qd1*qd2 - a2*lc4*sin(q4)*qd2^2",
            // The same with q3 (a prismatic coordinate is a length) and a term left alone.
            "d4*cos(q2)*qdd1 + d4*cos(q2)*qdd2 + q3*cos(q2)*qdd1 + q3*cos(q2)*qdd2 + g*sin(q2)",
            // Products of different rates or different trig factors stay apart.
            "a1*sin(q1)*qdd1 + a1*sin(q1)*qdd2 + a2*cos(q1)*qd1^2 + 2*a2*cos(q1)*qd1*qd2 \
             + a2*cos(q1)*qd2^2",
            "a1*sin(q1)*qdd1 + a1*sin(q1)*qdd2 + a2*sin(q1)*qd1^2 + 2*a2*sin(q1)*qd1*qd2 \
             + a2*sin(q1)*qd2^2",
            // A square of rates with no other factor, beside a term.
            "qd1^2 + 2*qd1*qd2 + qd2^2 + m1*qdd1",
        ] {
            sums.push(parse_expr(text).unwrap());
        }
        let mut ranked = 0;
        for e in &sums {
            if !matches!(e.kind(), Kind::Add(..)) || !has_rate(e) {
                continue;
            }
            let Some(r) = super::super::ranked::rank_sum(e) else {
                continue;
            };
            if !r.bases.iter().all(Expr::is_plain_base) {
                continue;
            }
            let terms: Vec<Vec<(u32, i32)>> = r.terms.iter().map(|(f, _)| f.clone()).collect();
            ranked += 1;
            assert_eq!(grouped_ranked(e, &r.bases, &terms), grouped(e), "{e:?}");
        }
        assert!(ranked > 50, "only {ranked} sums on ranks");
        // The collected product reads as the book writes it.
        let e = parse_expr(
            "a2*d4*sin(q4)*qd1^2 + 2*a2*d4*sin(q4)*qd1*qd2 + a2*d4*sin(q4)*qd2^2 \
             - a2*lc4*sin(q4)*qd1^2 - 2*a2*lc4*sin(q4)*qd1*qd2 - a2*lc4*sin(q4)*qd2^2",
        )
        .unwrap();
        let want = parse_expr("a2*(d4 - lc4)*sin(q4)*(qd1 + qd2)^2").unwrap();
        assert_eq!(group_rates(&e), want);
    }

    /// The remembered form of a group of rates is the form of its coefficients as they are: the
    /// memo's key divides them by the first, and `k` scales back while the inner sum stays (squares,
    /// linear forms, either sign, fractions).
    #[test]
    fn a_remembered_rate_form_is_the_form_of_the_coefficients_as_they_are() {
        let q = |i: u32| ((1u8, i), 1i64);
        let sq = |i: u32| ((1u8, i), 2i64);
        let acc = |i: u32| ((2u8, i), 1i64);
        let r = |n: i64, d: i64| Rational::new(n, d).expect("a non-zero denominator");
        let groups: Vec<(Vec<(RateMonomial, Rational)>, i64)> = vec![
            // (q̇1 + q̇2)²
            (
                vec![
                    (vec![sq(1)], r(1, 1)),
                    (vec![q(1), q(2)], r(2, 1)),
                    (vec![sq(2)], r(1, 1)),
                ],
                2,
            ),
            // (q̇1 − 2 q̇3)²
            (
                vec![
                    (vec![sq(1)], r(1, 1)),
                    (vec![q(1), q(3)], r(-4, 1)),
                    (vec![sq(3)], r(4, 1)),
                ],
                2,
            ),
            // 2 q̇1 q̇2 + q̇2²: not a square
            (vec![(vec![q(1), q(2)], r(2, 1)), (vec![sq(2)], r(1, 1))], 2),
            // q̈1 + q̈2 − q̈4
            (
                vec![
                    (vec![acc(1)], r(1, 1)),
                    (vec![acc(2)], r(1, 1)),
                    (vec![acc(4)], r(-1, 1)),
                ],
                1,
            ),
            // q̈1 / 3 + q̈2 / 2
            (vec![(vec![acc(1)], r(1, 3)), (vec![acc(2)], r(1, 2))], 1),
        ];
        for (pairs, degree) in groups {
            for scale in [r(1, 1), r(-1, 1), r(3, 1), r(-2, 7), r(5, 4)] {
                let scaled: Vec<(RateMonomial, Rational)> =
                    pairs.iter().map(|(m, c)| (m.clone(), c * &scale)).collect();
                let direct = rate_form_of(&scaled, degree);
                // Twice: computed, then from the memo.
                assert_eq!(rate_form(&scaled, degree), direct, "{scaled:?}");
                assert_eq!(rate_form(&scaled, degree), direct, "{scaled:?}");
            }
        }
    }

    /// The shortcut passes over only sums that the full path leaves as they are, and the full path
    /// changes some of the example sums (so the shortcut is not taken everywhere).
    #[test]
    fn nothing_to_group_passes_over_only_what_stays() {
        let (mut passed, mut changed) = (0, 0);
        for e in example_sums() {
            if !matches!(e.kind(), Kind::Add(..)) || !has_rate(&e) {
                continue;
            }
            let full = grouped(&e);
            if nothing_to_group(&e) {
                passed += 1;
                assert_eq!(full, e, "the shortcut passed over a sum that groups: {e:?}");
            }
            changed += usize::from(full != e);
        }
        assert!(
            passed > 0 && changed > 0,
            "passed {passed}, changed {changed}"
        );
        for text in [
            "s*qdd1 + s*qdd2",
            "a*d4*qd1^2 - a*lc4*qd1^2",
            "c*qd1^2 + 2*c*qd1*qd2",
        ] {
            assert!(!nothing_to_group(&parse_expr(text).unwrap()), "{text}");
        }
    }

    fn check(input: &str, expected: &str) {
        check_rule(group_rates, input, expected);
    }

    #[test]
    fn rates_that_differ_only_in_their_index_share_one_factor() {
        check("s*qdd1 + s*qdd2", "s*(qdd1 + qdd2)");
        check(
            "-a*s*qdd1 - a*s*qdd2 + a*s*qdd4",
            "-a*s*(qdd1 + qdd2 - qdd4)",
        );
        check("2*x*qdd1 + 4*x*qdd3", "2*x*(qdd1 + 2*qdd3)");
        check("x*qdd1/2 + x*qdd2/3", "x*(3*qdd1 + 2*qdd2)/6");
        // Another rest, or one term: as they stand.
        check("s*qdd1 + c*qdd2", "s*qdd1 + c*qdd2");
        check("s*qdd1 + g", "s*qdd1 + g");
    }

    #[test]
    fn perfect_squares_of_rates_come_back_whole() {
        check("c*qd1^2 + 2*c*qd1*qd2 + c*qd2^2", "c*(qd1 + qd2)^2");
        check(
            "c*qd1^2 + 2*c*qd1*qd2 - 2*c*qd1*qd4 + c*qd2^2 - 2*c*qd2*qd4 + c*qd4^2",
            "c*(qd1 + qd2 - qd4)^2",
        );
        check("-a*qd1^2 - 2*a*qd1*qd2 - a*qd2^2", "-a*(qd1 + qd2)^2");
        check("qd1^2 + 4*qd1*qd2 + 4*qd2^2 + g", "(qd1 + 2*qd2)^2 + g");
        check("x*qd1^2/4 + x*qd1*qd2 + x*qd2^2", "x*(qd1 + 2*qd2)^2/4");
        // Not squares (a missing or a wrong product, a product without its squares): the rates
        // share their factor, as the book writes the Coriolis terms.
        check("c*qd1^2 + c*qd2^2", "c*(qd1^2 + qd2^2)");
        check(
            "c*qd1^2 + 3*c*qd1*qd2 + c*qd2^2",
            "c*(qd1^2 + 3*qd1*qd2 + qd2^2)",
        );
        check("-2*c*qd1*qd2 - c*qd2^2", "-c*(2*qd1*qd2 + qd2^2)");
        check("c*qd1*qd2 + c*qd2*qd3", "c*(qd1*qd2 + qd2*qd3)");
        check(
            "2*c*qd1^2 + 2*c*qd1*qd2 + c*qd2^2",
            "c*(2*qd1^2 + 2*qd1*qd2 + qd2^2)",
        );
        // Another rest, or another degree: apart.
        check("c*qd1^2 + s*qd1*qd2", "c*qd1^2 + s*qd1*qd2");
        check("c*qd1^2 + c*qdd2", "c*qd1^2 + c*qdd2");
    }

    #[test]
    fn both_kinds_in_one_sum_as_in_an_acceleration() {
        // a_c,2 of the planar elbow in frame 0 (Spong §7.5): lc2 (s12 (q̈1 + q̈2) + c12 (q̇1 + q̇2)²).
        check(
            "s12*qdd1 + s12*qdd2 + c12*qd1^2 + 2*c12*qd1*qd2 + c12*qd2^2 + l1*s1*qdd1",
            "s12*(qdd1 + qdd2) + c12*(qd1 + qd2)^2 + l1*s1*qdd1",
        );
        // Terms that differ in their parameters only share the rest.
        check(
            "(qd1 + qd2)^2*a2*d4*s4 - (qd1 + qd2)^2*a2*lc4*s4 + a1*s1*qdd1",
            "a2*(d4 - lc4)*s4*(qd1 + qd2)^2 + a1*s1*qdd1",
        );
        check("l1*s2*qdd1 + lc2*s2*qdd1", "(l1 + lc2)*s2*qdd1");
        // A prismatic joint's coordinate is a length like the parameters.
        check("d4*c2*qdd1 + q3*c2*qdd1", "(d4 + q3)*c2*qdd1");
        // Without a rate in the rest, parameters stay where they are.
        check("a*s2 + b*s2 + c*qdd1", "a*s2 + b*s2 + c*qdd1");
        // No rates: the sum itself.
        let e = parse_expr("m1*l1^2 + m2*l2").unwrap();
        assert_eq!(group_rates(&e), e);
    }

    proptest::proptest! {
        #[test]
        fn an_expanded_square_comes_back_and_the_value_stays(
            l in proptest::collection::vec(-3i64..=3, 3),
            (num, den) in (1i64..=6, 1i64..=4),
            negative in proptest::bool::ANY,
            rest in 0usize..3,
            noise in proptest::collection::vec((-2i64..=2, 1u32..=3), 0..3),
        ) {
            // k N L² expanded, L = Σ l_i q̇_i with at least two rates, next to terms of other rests.
            proptest::prop_assume!(l.iter().filter(|&&x| x != 0).count() >= 2);
            let form = Expr::sum(l.iter().enumerate().map(|(i, &li)| Expr::int(li) * Expr::qd(i as u32 + 1)));
            let k = Rational::new(if negative { -num } else { num }, den).unwrap();
            let n = [Expr::symbol("a"), Expr::symbol("a") * Expr::cos(&Expr::q(1)), Expr::one()][rest].clone();
            let square = Expr::product([Expr::num(k), n, form.pow(2).unwrap()]);
            let others = Expr::sum(noise.iter().map(|&(c, i)| Expr::int(c) * Expr::symbol("b") * Expr::qdd(i)));
            let e = crate::algebra::normal::normal_form(&(square + others));
            let got = group_rates(&e);
            proptest::prop_assert!(equal(&e, &got), "{e:?} -> {got:?}");
            let text = crate::print::to_string(&got, crate::print::Style::Ascii);
            proptest::prop_assert!(text.contains(")^2"), "{e:?} -> {text}");
        }
    }
}
