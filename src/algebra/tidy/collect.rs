//! Collecting the terms of a sum by their key monomial: `d11 q̈1 + d12 q̈2 + …` out of an expanded sum.
//!
//! The *key monomial* of a term is the product of its factors that are key atoms (all `q̈` symbols, all
//! `q̇` symbols, or all `sin`/`cos` factors: a [`KeyClass`]); the rest of the term is its
//! *coefficient*. [`collect`] adds up the coefficients of equal keys. Every term is split as it stands,
//! so the result is always equal to the input as a function; pass an expanded sum (the normal form) to
//! collect completely: in `(q̈1 + q̈2) m` the sum is not a key atom and lands in the coefficient.
//!
//! Rules, one example each:
//! - a term splits into key × coefficient: `a b q̈1` gives key `q̈1`, coefficient `a b`;
//! - equal keys add their coefficients: `a q̈1 + b q̈1` gives `(q̈1, a + b)`;
//! - keys come in canonical order, terms without key atoms last under the key `1`:
//!   `g + q̇1 q̇2 + q̇1²` gives `[(q̇1², 1), (q̇1 q̇2, 1), (1, g)]`.

use crate::algebra::expr::{Expr, Kind};
use crate::algebra::symbol::Symbol;
use std::collections::BTreeMap;

/// Which factors make up a term's key monomial.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KeyClass {
    /// The accelerations `q̈_i`.
    Acceleration,
    /// The velocities `q̇_i`.
    Velocity,
    /// `sin` and `cos` factors (of any argument): the trig monomial.
    Trig,
}

impl KeyClass {
    /// Whether the factor base `b` is a key atom of this class.
    pub fn is_key(self, b: &Expr) -> bool {
        match (self, b.kind()) {
            (KeyClass::Acceleration, Kind::Sym(Symbol::Coord { order, .. })) => *order == 2,
            (KeyClass::Velocity, Kind::Sym(Symbol::Coord { order, .. })) => *order == 1,
            (KeyClass::Trig, Kind::Fun(..)) => true,
            _ => false,
        }
    }
}

/// The terms of `e` grouped by their key monomial under `keys`: `(key, coefficient)` pairs with
/// `Σ key · coefficient = e`, keys in canonical order and the key `1` (terms without key atoms) last.
/// Groups whose coefficient adds up to zero are left out.
///
/// `m1 q̈1 + m2 q̈1 + m1 g` by [`KeyClass::Acceleration`] gives `[(q̈1, m1 + m2), (1, m1 g)]`.
pub fn collect(e: &Expr, keys: KeyClass) -> Vec<(Expr, Expr)> {
    collect_with(e, &|b| keys.is_key(b))
}

/// [`collect`] with any predicate on factor bases: `is_key(b)` says whether `b` belongs to the key.
pub fn collect_with(e: &Expr, is_key: &dyn Fn(&Expr) -> bool) -> Vec<(Expr, Expr)> {
    let mut groups: BTreeMap<Expr, Vec<Expr>> = BTreeMap::new();
    for (t, c) in e.terms() {
        let (key, rest): (Vec<_>, Vec<_>) = t.factors().into_iter().partition(|(b, _)| is_key(b));
        let key = Expr::product(key.into_iter().map(|(b, k)| power(&b, k)));
        let coeff = Expr::product(
            std::iter::once(Expr::num(c)).chain(rest.into_iter().map(|(b, k)| power(&b, k))),
        );
        groups.entry(key).or_default().push(coeff);
    }
    let rest = groups.remove(&Expr::one());
    groups
        .into_iter()
        .chain(rest.map(|r| (Expr::one(), r)))
        .map(|(key, parts)| (key, Expr::sum(parts)))
        .filter(|(_, coeff)| !coeff.is_zero())
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

    /// `collect(input, keys)` is `expected`, and adds back up to `input`.
    fn check(input: Expr, keys: KeyClass, expected: Vec<(Expr, Expr)>) {
        let got = collect(&input, keys);
        assert_eq!(got, expected, "collect({input:?}, {keys:?})");
        let back = Expr::sum(got.iter().map(|(k, c)| k * c));
        assert!(equal(&input, &back), "value changed: {input:?} -> {back:?}");
    }

    #[test]
    fn rules() {
        let (a, b, g) = (s("a"), s("b"), s("g"));
        let (m1, m2) = (s("m1"), s("m2"));
        let (q1, qd1, qd2, qdd1, qdd2) = (
            Expr::q(1),
            Expr::qd(1),
            Expr::qd(2),
            Expr::qdd(1),
            Expr::qdd(2),
        );
        let qd1sq = qd1.pow(2).unwrap();
        check(
            &a * &b * &qdd1,
            KeyClass::Acceleration,
            vec![(qdd1.clone(), &a * &b)],
        );
        check(
            &a * &qdd1 + &b * &qdd1,
            KeyClass::Acceleration,
            vec![(qdd1.clone(), &a + &b)],
        );
        check(
            Expr::sum([g.clone(), &qd1 * &qd2, qd1sq.clone()]),
            KeyClass::Velocity,
            vec![
                (qd1sq.clone(), Expr::one()),
                (&qd1 * &qd2, Expr::one()),
                (Expr::one(), g.clone()),
            ],
        );
        // The brief's example, plus a second coordinate and a velocity inside a q̈ coefficient.
        check(
            Expr::sum([&m1 * &qdd1, &m2 * &qdd1, &m1 * &g, &m2 * &qdd2 * &qd1]),
            KeyClass::Acceleration,
            vec![
                (qdd1.clone(), &m1 + &m2),
                (qdd2.clone(), &m2 * &qd1),
                (Expr::one(), &m1 * &g),
            ],
        );
        // Trig monomials in canonical order (sin before cos, higher powers first); constants last.
        let (c1, s1) = (Expr::cos(&q1), Expr::sin(&q1));
        check(
            Expr::sum([
                &a * &c1,
                &b * &c1,
                &g * &c1 * &s1,
                Expr::int(3),
                c1.pow(2).unwrap(),
            ]),
            KeyClass::Trig,
            vec![
                (&c1 * &s1, g.clone()),
                (c1.pow(2).unwrap(), Expr::one()),
                (c1.clone(), &a + &b),
                (Expr::one(), Expr::int(3)),
            ],
        );
        // Zero and a sum that is not expanded.
        check(Expr::zero(), KeyClass::Trig, vec![]);
        let unexpanded = &m1 * &(&qdd1 + &qdd2);
        check(
            unexpanded.clone(),
            KeyClass::Acceleration,
            vec![(Expr::one(), unexpanded)],
        );
    }

    #[test]
    fn key_classes() {
        assert!(KeyClass::Acceleration.is_key(&Expr::qdd(3)));
        assert!(!KeyClass::Acceleration.is_key(&Expr::qd(3)));
        assert!(KeyClass::Velocity.is_key(&Expr::qd(3)));
        assert!(!KeyClass::Velocity.is_key(&Expr::q(3)));
        assert!(KeyClass::Trig.is_key(&Expr::cos(&Expr::q(1))));
        assert!(!KeyClass::Trig.is_key(&Expr::symbol("g")));
        let custom = collect_with(&(Expr::symbol("g") * Expr::symbol("m")), &|b| {
            b == &Expr::symbol("g")
        });
        assert_eq!(custom, vec![(Expr::symbol("g"), Expr::symbol("m"))]);
    }
}
