//! Display-oriented simplification: the house style of the textbooks from the expanded normal form.
//!
//! The normal form ([`crate::algebra::normal`]) is expanded: `m1 g + m2 g + m3 g`,
//! `cos q2 cos q3 − sin q2 sin q3`. The functions here rewrite it the way Spong, Hutchinson and
//! Vidyasagar print dynamics (*Robot Modeling and Control*, ch. 7). Each is a pure function whose
//! result is equal to its input as a function ([`crate::algebra::normal::equal`]); none is needed for
//! correctness, only for reading.
//!
//! The rules, one example each (each is a row of a `check` table in its file):
//! - [`factor_common`]: the common monomial and rational content of a sum come out:
//!   `m1 g + m2 g + m3 g` is `(m1 + m2 + m3) g`, `2 a x + 4 a y` is `2 a (x + 2 y)`,
//!   `−m1 g − m2 g` is `−(m1 + m2) g`;
//! - [`contract_trig`]: angle sums come back: `cos q2 cos q3 − sin q2 sin q3` is `cos(q2 + q3)`,
//!   `sin q2 cos q3 + cos q2 sin q3` is `sin(q2 + q3)`, and `a − a cos² q2` is `a sin² q2`;
//!   `2 sin q cos q` stays;
//! - [`collect()`]: terms grouped by a key monomial: `m1 q̈1 + m2 q̈1 + m1 g` by accelerations is
//!   `[(q̈1, m1 + m2), (1, m1 g)]`;
//! - [`group()`]: partial grouping by trig monomial or by leading parameter:
//!   `m2 l1² + m2 lc2² + I2` by [`Grouping::Leading`] is `m2 (l1² + lc2²) + I2`;
//! - [`tidy`]: normal form, then [`contract_trig`], then one [`factor_common`] per trig group:
//!   `m1 g cos q1 + m2 g cos q1 + m2 g (cos q1 cos q2 − sin q1 sin q2)` is
//!   `(m1 + m2) g cos q1 + m2 g cos(q1 + q2)`;
//! - [`equation_terms`]: the ordered display terms of an equation side: `q̈` terms, `q̇`-product
//!   terms, the rest by trig monomial;
//! - [`rates::group_rates`] (inside [`Grouping::Leading`]): `s12 q̈1 + s12 q̈2` is `s12 (q̈1 + q̈2)`,
//!   `c12 q̇1² + 2 c12 q̇1 q̇2 + c12 q̇2²` is `c12 (q̇1 + q̇2)²`;
//! - [`share::share_cofactors`] (after [`Grouping::Leading`]): `−m3 (g − a2 q̈3) − m4 (g − a2 q̈3)`
//!   is `−(m3 + m4) (g − a2 q̈3)`; a rest of fewer than three symbols stays per mass.
//!
//! Rules are named data ([`rule::Rule`], [`contract::ANGLE_IDENTITIES`]) composed by a fixpoint with a
//! limit; each rule merges two terms into one, so it shrinks the sum. Everything is deterministic:
//! candidates are visited in the canonical order of [`Expr`], never in hash order, and [`tidy`] starts
//! from the normal form, so inputs equal as functions give identical outputs.
//!
//! Known limits: squares of sums of more than two angles are recovered only as far as the passes
//! contract their parts (`cos²(q2 + q3)` comes back whole, see [`square`]), double angles stay expanded
//! (`cos(2 q1 + q2)` is `2 cos(q1 + q2) cos q1 − cos q2`), and the greedy pairing keeps the first
//! match in canonical order, not the globally shortest result.

mod classes;
pub mod collect;
pub mod contract;
pub mod equation;
pub mod factor;
pub mod group;
mod leading;
pub mod memo;
pub mod pythagoras;
mod ranked;
pub mod rates;
pub mod rule;
pub mod share;
pub mod square;

#[cfg(test)]
mod proptests;
#[cfg(test)]
mod testing;

pub use collect::{collect, collect_with, KeyClass};
pub use contract::contract_trig;
pub use equation::{equation_terms, equation_terms_poly};
pub use factor::{factor_common, factor_list};
pub use group::{group, Grouping};

use crate::algebra::expr::Expr;

/// The display form of `e`: its normal form with angle sums contracted, the terms grouped by trig
/// monomial and each group factored. Equal to `e` as a function; equal inputs give identical outputs.
///
/// `m1 g cos(q1) + m2 g cos(q1)` gives `(m1 + m2) g cos(q1)`.
pub fn tidy(e: &Expr) -> Expr {
    tidy_by(e, Grouping::Trig)
}

/// [`tidy`] with another [`Grouping`]: [`Grouping::Leading`] is the habit for inertia entries,
/// `m1 lc1² + m2 (l1² + lc2² + 2 l1 lc2 cos q2) + I1 + I2`.
pub fn tidy_by(e: &Expr, grouping: Grouping) -> Expr {
    if is_atom(e) {
        return e.clone();
    }
    group(&contract_trig(e), grouping)
}

/// A number, a symbol or π: its own display form (the transforms and tensors of a scene are full
/// of them).
fn is_atom(e: &Expr) -> bool {
    matches!(
        e.kind(),
        crate::algebra::Kind::Num(_) | crate::algebra::Kind::Sym(_) | crate::algebra::Kind::Pi
    )
}

/// [`tidy_by`] of a polynomial, which is its own normal form: the conversion from an expression that
/// [`tidy_by`] starts with (the larger part of its cost on the intermediate vectors of a sheet) is
/// skipped, and the passes of the contraction work on the polynomial's ranked terms (module
/// `ranked`) when its atoms are symbols, sines and cosines, as does the grouping by leading
/// parameter after them (module `leading`); by leading parameter, each class of terms of one
/// leading parameter alone, remembered (module `classes`). The same result as
/// `tidy_by(&p.to_expr(), grouping)`.
pub fn tidy_poly_by(p: &crate::algebra::Poly, grouping: Grouping) -> Expr {
    // A single term is its own display form: no rule has two terms to merge, and the grouping
    // gives back the canonical product it started from.
    if p.len() <= 1 {
        return p.to_expr();
    }
    // By leading parameter, class by class (module `classes`): the classes recur from vector to
    // vector, and each is remembered.
    if grouping == Grouping::Leading {
        if let Some(shown) = classes::tidy_leading(p) {
            #[cfg(debug_assertions)]
            assert_eq!(
                shown,
                whole_poly_by(p, grouping),
                "class by class as the whole sum"
            );
            return shown;
        }
    }
    whole_poly_by(p, grouping)
}

/// [`tidy_poly_by`] of a sum of two terms or more, the whole sum at once.
fn whole_poly_by(p: &crate::algebra::Poly, grouping: Grouping) -> Expr {
    let (contracted, ranks) = match p.ranked() {
        Some(r) => ranked::contract_ranked(r),
        None => (contract::contract_normal(&p.to_expr()), None),
    };
    group::group_ranked(&contracted, ranks.as_ref(), grouping)
}

/// Forgets what the memos of the display rules hold ([`memo`]): for a benchmark that times the
/// rules from scratch, as a process meets them once, rather than their remembered results. What
/// is displayed is the same either way (each memo holds a pure function's results).
pub fn forget_memos() {
    group::DISPLAYED.clear();
    factor::FACTORED.clear();
    rates::GROUPED.clear();
    rates::FORMS.clear();
    classes::QUOTIENTS.clear();
}

/// Something shown in the house style: an expression ([`tidy_by`]) or a polynomial
/// ([`tidy_poly_by`]).
pub trait Tidy {
    /// The display form.
    fn tidy_by(&self, grouping: Grouping) -> Expr;
}

impl Tidy for Expr {
    fn tidy_by(&self, grouping: Grouping) -> Expr {
        tidy_by(self, grouping)
    }
}

impl Tidy for crate::algebra::Poly {
    fn tidy_by(&self, grouping: Grouping) -> Expr {
        tidy_poly_by(self, grouping)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::equal;

    fn s(name: &str) -> Expr {
        Expr::symbol(name)
    }

    /// `tidy(input)` is `expected` structurally, equal to `input`, and a fixpoint of `tidy`.
    fn check(input: Expr, expected: Expr) {
        let got = tidy(&input);
        assert_eq!(got, expected, "tidy({input:?})");
        assert!(equal(&input, &got), "value changed: {input:?} -> {got:?}");
        assert_eq!(tidy(&got), got, "tidy is not idempotent on {input:?}");
    }

    /// The shortcuts (an atom, a single term) give what the rules give.
    #[test]
    fn atoms_and_single_terms_are_their_own_display_form() {
        for text in [
            "0",
            "-3/4",
            "m1",
            "qdd2",
            "pi",
            "2*m2*l1*lc2*cos(q2)",
            "-m3*g*sin(q1)*cos(q2)^2",
            "sqrt(2)*a*qd1^2/2",
            "x^-1*y",
        ] {
            let e = crate::parse::parse_expr(text).unwrap();
            let p = crate::algebra::to_poly(&e);
            for g in [Grouping::Trig, Grouping::Leading] {
                let full = group(&contract::contract_normal(&p.to_expr()), g);
                assert_eq!(tidy_poly_by(&p, g), full, "{text}");
                if is_atom(&e) {
                    assert_eq!(tidy_by(&e, g), group(&contract_trig(&e), g), "{text}");
                }
            }
        }
    }

    #[test]
    fn a_polynomial_tidies_as_its_expression() {
        for text in [
            "m1*g*cos(q1) + m2*g*cos(q1) + m2*g*(cos(q1)*cos(q2) - sin(q1)*sin(q2))",
            "m2*l1^2 + m2*lc2^2 + 2*m2*l1*lc2*cos(q2) + I2",
            "a - a*cos(q2)^2 + 2*sin(q1)*cos(q1)",
            "0",
        ] {
            let e = crate::parse::parse_expr(text).unwrap();
            let p = crate::algebra::to_poly(&e);
            for g in [Grouping::Trig, Grouping::Leading] {
                assert_eq!(tidy_poly_by(&p, g), tidy_by(&e, g), "{text}");
            }
        }
    }

    #[test]
    fn rules() {
        let (g, m1, m2, m3) = (s("g"), s("m1"), s("m2"), s("m3"));
        let (q1, q2) = (Expr::q(1), Expr::q(2));
        let (c1, c2, s1, s2) = (
            Expr::cos(&q1),
            Expr::cos(&q2),
            Expr::sin(&q1),
            Expr::sin(&q2),
        );
        let rows = [
            // PPP gravity.
            (
                Expr::sum([&m1 * &g, &m2 * &g, &m3 * &g]),
                Expr::product([Expr::sum([m1.clone(), m2.clone(), m3.clone()]), g.clone()]),
            ),
            // The module example: contraction, then one factor per trig group.
            (
                &m1 * &g * &c1 + &m2 * &g * &c1 + &m2 * &g * (&c1 * &c2 - &s1 * &s2),
                Expr::product([&m1 + &m2, g.clone(), c1.clone()])
                    + &m2 * &g * Expr::cos(&(&q1 + &q2)),
            ),
            // A negative group.
            (
                -(&m1 * &g * &s1) - &m2 * &g * &s1,
                Expr::product([Expr::int(-1), &m1 + &m2, g.clone(), s1.clone()]),
            ),
            // Already tidy, and factored input comes out the same as expanded input.
            (
                Expr::product([&m1 + &m2, g.clone()]),
                Expr::product([&m1 + &m2, g.clone()]),
            ),
            (Expr::int(2) * &s1 * &c1, Expr::int(2) * &s1 * &c1),
            (Expr::zero(), Expr::zero()),
            // Squares of angle sums come back whole (a 3R arm's inertia about its first axis).
            (
                &m1 * Expr::cos(&(&q1 + &q2)).pow(2).unwrap()
                    + &m2 * Expr::sin(&(&q1 + &q2)).pow(2).unwrap(),
                &m1 * Expr::cos(&(&q1 + &q2)).pow(2).unwrap()
                    + &m2 * Expr::sin(&(&q1 + &q2)).pow(2).unwrap(),
            ),
            (
                &g * Expr::cos(&(&q1 - &q2)).pow(2).unwrap()
                    + &g * Expr::sin(&(&q1 - &q2)).pow(2).unwrap(),
                g.clone(),
            ),
        ];
        for (input, expected) in rows {
            check(input, expected);
        }
    }

    #[test]
    fn tidy_by_leading_parameter() {
        let (m2, l1, lc2, i2) = (s("m2"), s("l1"), s("lc2"), s("I2"));
        let c2 = Expr::cos(&Expr::q(2));
        // Spong's d12, expanded.
        let d12 = &m2 * lc2.pow(2).unwrap() + &m2 * &l1 * &lc2 * &c2 + &i2;
        let want = Expr::product([m2.clone(), lc2.clone(), &lc2 + &l1 * &c2]) + &i2;
        assert_eq!(tidy_by(&d12, Grouping::Leading), want);
        assert!(equal(&d12, &want));
    }

    #[test]
    fn equal_inputs_give_identical_outputs() {
        let (a, b) = (s("a"), s("b"));
        let (q1, q2) = (Expr::q(1), Expr::q(2));
        let x = &a * Expr::cos(&(&q1 + &q2)) + &b * Expr::sin(&q1).pow(2).unwrap();
        let y = &a * (Expr::cos(&q1) * Expr::cos(&q2) - Expr::sin(&q1) * Expr::sin(&q2)) + &b
            - &b * Expr::cos(&q1).pow(2).unwrap();
        assert_eq!(tidy(&x), tidy(&y));
    }
}
