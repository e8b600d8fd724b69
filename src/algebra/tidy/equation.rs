//! The display terms of one side of an equation of motion, in the order of Spong et al. (ch. 7):
//! `Σ_j d_kj q̈_j + Σ_ij c_ijk q̇_i q̇_j + φ_k`.
//!
//! [`equation_terms`] expands the side, then
//! 1. collects it by the accelerations: one term `d_kj q̈_j` per coordinate `j`, by index;
//! 2. collects what is left by the products of velocities: `q̇1²`, `q̇1 q̇2`, `q̇2²`, …;
//! 3. splits the rest (gravity, springs) into groups by trig monomial, simpler trig parts first.
//!
//! The coefficients of 1. and 2. are contracted ([`super::contract_trig`]), grouped by leading
//! parameter (the masses, [`super::Grouping::Leading`]) and factored; the groups of 3. are contracted
//! and factored ([`super::Grouping::Trig`]). Every term is `coefficient × key`, and the terms add up
//! to the side exactly.

use super::factor::factor_list;
use super::group::Grouping;
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::expr::Expr;
use crate::algebra::normal::to_poly;
use crate::algebra::number::Rational;
use crate::algebra::poly::{Mono, Poly};
use crate::algebra::symbol::Symbol;

/// The ordered display terms of an equation side `lhs`: its `q̈` terms by coordinate index, its
/// `q̇`-product terms, then its remaining terms grouped by trig monomial; each term a factored
/// coefficient times its key. The terms add up to `lhs` (as functions); zero gives no terms.
///
/// `m1 q̈1 + m2 q̈1 + m3 q̈1 + m1 g + m2 g + m3 g` gives `[(m1 + m2 + m3) q̈1, (m1 + m2 + m3) g]`.
pub fn equation_terms(lhs: &Expr) -> Vec<Expr> {
    equation_terms_poly(&to_poly(lhs))
}

/// [`equation_terms`] of a polynomial (its own normal form). The side is collected by its key atoms
/// on the polynomial's own monomials, so every coefficient is a polynomial the display rules take
/// as it stands ([`super::tidy_poly_by`], then [`factor_list`]).
pub fn equation_terms_poly(lhs: &Poly) -> Vec<Expr> {
    let mut out = Vec::new();
    let mut rest = lhs.clone();
    for role in [Order::Acceleration, Order::Rate] {
        let (groups, left) = collect_poly(&rest, role);
        for (key, coeff) in groups {
            // On the polynomial's ranks, class by class ([`super::tidy_poly_by`]): what the passes
            // on its expression give, its classes remembered with the vectors' of a sheet.
            let coeff = super::tidy_poly_by(&coeff, Grouping::Leading);
            out.push(Expr::product(factor_list(&coeff).into_iter().chain([key])));
        }
        rest = left;
    }
    // Simpler trig parts first (`… cos(q1) + … cos(q1+q2)`, as Spong writes φ1), then canonical order.
    let mut others: Vec<Expr> = super::tidy_poly_by(&rest, Grouping::Trig)
        .terms()
        .into_iter()
        .map(|(t, c)| t.scale(&c))
        .collect();
    others.sort_by_key(trig_size);
    out.extend(others);
    out
}

/// The derivative order whose coordinates key a collection: `q̈` or `q̇`.
#[derive(Clone, Copy)]
enum Order {
    Acceleration = 2,
    Rate = 1,
}

/// The terms of `p` collected by their factors among the coordinates of `order`
/// ([`super::collect::collect`] on the polynomial's monomials): `(key, coefficient)` pairs in the
/// canonical order of the keys, and the terms without such factors. Dropping key atoms from the
/// distinct monomials of one key leaves distinct monomials, so no coefficient is zero.
fn collect_poly(p: &Poly, order: Order) -> (Vec<(Expr, Poly)>, Poly) {
    let is_key = |id: AtomId| {
        atom::class(id) == Class::Coord
            && matches!(atom::symbol_of(id), Some(Symbol::Coord { order: o, .. }) if o == order as u8)
    };
    let mut groups: std::collections::BTreeMap<Mono, Vec<(Mono, Rational)>> = Default::default();
    let mut left = Vec::new();
    for (m, c) in p.terms() {
        let (key, other): (Vec<_>, Vec<_>) = m.factors().iter().partition(|(id, _)| is_key(*id));
        if key.is_empty() {
            left.push((m.clone(), c.clone()));
        } else {
            groups
                .entry(Mono::from_sorted(key))
                .or_default()
                .push((Mono::from_sorted(other), c.clone()));
        }
    }
    let mut keyed: Vec<(Expr, Poly)> = groups
        .into_iter()
        .map(|(key, terms)| {
            (
                Poly::term(key, Rational::one()).to_expr(),
                Poly::from_terms(terms),
            )
        })
        .collect();
    keyed.sort_by(|a, b| a.0.cmp(&b.0));
    (keyed, Poly::from_terms(left))
}

/// The size of the trig factors of a term (0 for none).
fn trig_size(term: &Expr) -> usize {
    term.factors()
        .iter()
        .filter(|(b, _)| matches!(b.kind(), crate::algebra::expr::Kind::Fun(..)))
        .map(|(b, _)| b.node_count())
        .sum()
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

    /// `equation_terms(input)` is `expected` structurally, and adds up to `input`.
    fn check(input: Expr, expected: Vec<Expr>) {
        let got = equation_terms(&input);
        assert_eq!(got, expected, "equation_terms({input:?})");
        assert!(equal(&input, &Expr::sum(got)), "value changed");
    }

    #[test]
    fn a_polynomial_gives_the_terms_of_its_expression() {
        let e = crate::parse::parse_expr(
            "m1*qdd1 + m2*qdd1 + m2*l1*cos(q2)*qdd2 - 2*m2*l1*sin(q2)*qd1*qd2 + m1*g*cos(q1) + m2*g*cos(q1)",
        )
        .unwrap();
        let p = crate::algebra::to_poly(&e);
        assert_eq!(equation_terms_poly(&p), equation_terms(&e));
    }

    #[test]
    fn ppp_manipulator() {
        let (m1, m2, m3, g) = (s("m1"), s("m2"), s("m3"), s("g"));
        let (qdd1, qdd2) = (Expr::qdd(1), Expr::qdd(2));
        let masses = Expr::sum([m1.clone(), m2.clone(), m3.clone()]);
        check(
            Expr::sum([
                &m1 * &qdd1,
                &m2 * &qdd1,
                &m3 * &qdd1,
                &m1 * &g,
                &m2 * &g,
                &m3 * &g,
            ]),
            vec![
                Expr::product([masses.clone(), qdd1.clone()]),
                Expr::product([masses, g.clone()]),
            ],
        );
        check(
            &m2 * &qdd2 + &m3 * &qdd2,
            vec![Expr::product([&m2 + &m3, qdd2.clone()])],
        );
        check(&m3 * Expr::qdd(3), vec![&m3 * Expr::qdd(3)]);
        check(Expr::zero(), vec![]);
    }

    /// Spong's two-link planar elbow arm (§7.4.2), first equation, from its closed form.
    #[test]
    fn elbow_arm() {
        let (m1, m2, l1, lc1, lc2, g) = (s("m1"), s("m2"), s("l1"), s("lc1"), s("lc2"), s("g"));
        let (i1, i2) = (s("I1"), s("I2"));
        let (q1, q2) = (Expr::q(1), Expr::q(2));
        let (qd1, qd2, qdd1, qdd2) = (Expr::qd(1), Expr::qd(2), Expr::qdd(1), Expr::qdd(2));
        let c2 = Expr::cos(&q2);
        let d11 = Expr::sum([
            &m1 * sq(&lc1),
            &m2 * (sq(&l1) + sq(&lc2) + Expr::int(2) * &l1 * &lc2 * &c2),
            i1.clone(),
            i2.clone(),
        ]);
        let d12 = &m2 * (sq(&lc2) + &l1 * &lc2 * &c2) + &i2;
        let h = -(&m2 * &l1 * &lc2 * Expr::sin(&q2));
        // φ1 expanded, as the derivation delivers it.
        let phi1 = (&m1 * &lc1 + &m2 * &l1) * &g * Expr::cos(&q1)
            + &m2 * &lc2 * &g * (Expr::cos(&q1) * &c2 - Expr::sin(&q1) * Expr::sin(&q2));
        let lhs = Expr::sum([
            &d11 * &qdd1,
            &d12 * &qdd2,
            &h * &qd1 * &qd2,
            &h * &qd2 * &qd1,
            &h * sq(&qd2),
            phi1,
        ]);
        let spong_d11 = Expr::sum([
            &m1 * sq(&lc1),
            Expr::product([
                m2.clone(),
                Expr::sum([sq(&l1), sq(&lc2), Expr::int(2) * &l1 * &lc2 * &c2]),
            ]),
            i1.clone(),
            i2.clone(),
        ]);
        let d12_factored = Expr::sum([
            Expr::product([m2.clone(), lc2.clone(), &lc2 + &l1 * &c2]),
            i2.clone(),
        ]);
        check(
            lhs,
            vec![
                Expr::product([spong_d11, qdd1.clone()]),
                Expr::product([d12_factored, qdd2.clone()]),
                Expr::int(-2) * &m2 * &l1 * &lc2 * Expr::sin(&q2) * &qd1 * &qd2,
                -(&m2 * &l1 * &lc2 * Expr::sin(&q2) * sq(&qd2)),
                Expr::product([&m1 * &lc1 + &m2 * &l1, g.clone(), Expr::cos(&q1)]),
                &m2 * &lc2 * &g * Expr::cos(&(&q1 + &q2)),
            ],
        );
    }
}
