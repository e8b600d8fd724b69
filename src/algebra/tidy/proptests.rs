//! Property tests: every display rule keeps the value (the exact zero test of the normal form), on
//! random small sums of products of parameters, coordinates, velocities, accelerations, `sin`/`cos`
//! of coordinates and of sums and differences of two coordinates, and small sums of those.

use super::*;
use crate::algebra::normal::{equal, normal_form};
use crate::algebra::Func;
use proptest::prelude::*;

fn coordinate() -> impl Strategy<Value = Expr> {
    (1u32..=3).prop_map(Expr::q)
}

/// `q_i`, `q_i + q_j` or `q_i − q_j`.
fn angle() -> impl Strategy<Value = Expr> {
    prop_oneof![
        coordinate(),
        (coordinate(), coordinate()).prop_map(|(a, b)| a + b),
        (coordinate(), coordinate()).prop_map(|(a, b)| a - b),
    ]
}

fn trig() -> impl Strategy<Value = Expr> {
    (function(), angle()).prop_map(|(f, a)| Expr::fun(f, &a))
}

fn function() -> impl Strategy<Value = Func> {
    prop_oneof![Just(Func::Sin), Just(Func::Cos)]
}

/// `sin`/`cos` of `q_i`, `q_i + q_j` or `q_i − q_j` with `i < j` (no double angles).
fn trig_of_distinct() -> impl Strategy<Value = Expr> {
    let angle = (1u32..=3, 1u32..=3, 0u8..3).prop_map(|(i, j, how)| match (i.cmp(&j), how) {
        (std::cmp::Ordering::Equal, _) | (_, 0) => Expr::q(i),
        (_, 1) => Expr::q(i) + Expr::q(j),
        _ => Expr::q(i) - Expr::q(j),
    });
    (function(), angle).prop_map(|(f, a)| Expr::fun(f, &a))
}

fn atom() -> impl Strategy<Value = Expr> {
    prop_oneof![
        3 => prop_oneof![Just("a"), Just("b"), Just("m1"), Just("g")].prop_map(Expr::symbol),
        1 => coordinate(),
        1 => (1u32..=2).prop_map(Expr::qd),
        1 => (1u32..=2).prop_map(Expr::qdd),
        3 => trig(),
    ]
}

/// An atom, or now and then a small sum of atoms (so factoring has something nested to do).
fn factor() -> impl Strategy<Value = Expr> {
    prop_oneof![
        4 => atom(),
        1 => prop::collection::vec((-2i64..=2, atom()), 2..=3)
            .prop_map(|ts| Expr::sum(ts.into_iter().map(|(c, t)| Expr::int(c) * t))),
    ]
}

fn term() -> impl Strategy<Value = Expr> {
    (-3i64..=3, prop::collection::vec(factor(), 1..=3))
        .prop_map(|(c, fs)| Expr::product(std::iter::once(Expr::int(c)).chain(fs)))
}

fn expression() -> impl Strategy<Value = Expr> {
    prop::collection::vec(term(), 1..=5).prop_map(Expr::sum)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn factor_common_keeps_the_value(e in expression()) {
        prop_assert!(equal(&e, &factor_common(&e)));
        let n = normal_form(&e);
        prop_assert!(equal(&n, &factor_common(&n)));
    }

    #[test]
    fn contract_trig_keeps_the_value(e in expression()) {
        let c = contract_trig(&e);
        prop_assert!(equal(&e, &c), "{:?} -> {:?}", e, c);
        prop_assert!(c.node_count() <= normal_form(&e).node_count() + 1);
    }

    #[test]
    fn tidy_keeps_the_value_and_is_canonical(e in expression()) {
        let t = tidy(&e);
        prop_assert!(equal(&e, &t), "{:?} -> {:?}", e, t);
        prop_assert_eq!(&tidy(&normal_form(&e)), &t);
        prop_assert_eq!(&tidy(&t), &t);
        prop_assert_eq!(&tidy(&contract_trig(&e)), &t);
        prop_assert_eq!(&tidy(&factor_common(&e)), &t);
        prop_assert!(equal(&e, &tidy_by(&e, Grouping::Leading)));
    }

    /// The grouping by leading parameter on ranked terms is the grouping on the expressions: of a
    /// sum ranked again, and of a polynomial's contraction that hands its ranks over.
    #[test]
    fn the_grouping_on_ranks_is_the_grouping_on_expressions(e in expression()) {
        let c = contract_trig(&e);
        let on_expressions = group::grouped_on_expressions(&c, Grouping::Leading);
        if let Some(items) = leading::leading_groups(&c, None) {
            prop_assert_eq!(share::share_cofactors(&Expr::sum(items)), on_expressions.clone());
        }
        let p = crate::algebra::to_poly(&e);
        if p.len() >= 2 {
            let contracted = contract::contract_normal(&p.to_expr());
            prop_assert_eq!(
                tidy_poly_by(&p, Grouping::Leading),
                group::grouped_on_expressions(&contracted, Grouping::Leading)
            );
        }
    }

    #[test]
    fn collect_adds_back_up(e in expression()) {
        let n = normal_form(&e);
        for keys in [KeyClass::Acceleration, KeyClass::Velocity, KeyClass::Trig] {
            let groups = collect(&n, keys);
            let back = Expr::sum(groups.iter().map(|(k, c)| k * c));
            prop_assert!(equal(&n, &back));
            // Keys strictly increasing, `1` only last; no key atom left in a coefficient.
            let keys_only: Vec<&Expr> = groups.iter().map(|(k, _)| k).collect();
            let (last, rest) = match keys_only.split_last() {
                Some((l, r)) if l.is_one() => (Some(*l), r),
                _ => (None, &keys_only[..]),
            };
            prop_assert!(rest.windows(2).all(|w| w[0] < w[1]));
            prop_assert!(rest.iter().all(|k| !k.is_one()));
            prop_assert!(last.is_none_or(|l| l.is_one()));
            for (_, c) in &groups {
                for (t, _) in c.terms() {
                    prop_assert!(t.factors().iter().all(|(b, _)| !keys.is_key(b)));
                }
            }
        }
    }

    #[test]
    fn equation_terms_add_back_up(e in expression()) {
        let terms = equation_terms(&e);
        prop_assert!(equal(&e, &Expr::sum(terms.iter().cloned())));
        prop_assert!(terms.iter().all(|t| !t.is_zero()));
    }

    /// Distinct parameters times `sin`/`cos` of angle sums: the expansion contracts back exactly.
    #[test]
    fn angle_sums_come_back(parts in prop::collection::vec((trig_of_distinct(), -3i64..=3), 1..=3)) {
        let names = ["a", "b", "c"];
        let e = Expr::sum(parts.iter().zip(names).map(|((t, c), n)| Expr::int(*c) * Expr::symbol(n) * t));
        prop_assert_eq!(contract_trig(&normal_form(&e)), e);
    }
}
