//! The display form by leading parameter ([`super::Grouping::Leading`]) of a polynomial, class by
//! class, each class remembered.
//!
//! [`super::tidy_poly_by`] contracts the angle sums of the whole sum, then groups its terms by
//! leading parameter (the first parameter of a term in the canonical order, with its power). Both
//! steps keep to the terms of one leading parameter:
//! - a rule of the contraction merges two terms `c R f(A) g(B)` of one `R` (every factor but the
//!   two sines or cosines), so of one leading parameter, which is among the factors of `R`; and the
//!   merged term keeps `R`, so its leading parameter too;
//! - the grouping makes one product of each leading parameter's terms ([`super::leading`]).
//!
//! So the display form of a sum is [`share_cofactors`] of the sum of its classes' products, each
//! class (the terms of one leading parameter) contracted and grouped alone. A class recurs from
//! vector to vector: in the inertial frame a link's share of the force `f_i`, `m_j (a_c,j − g)`, is
//! the same in every `f_i` up to that link, and a link's inertia terms recur in every moment
//! `n_i` up to it. [`CLASSES`] remembers each class's product, so a class met again is not
//! contracted and grouped again (the SCARA arm's sheet meets 232 classes in its distinct components,
//! 74 of them seen before, with 37% of the terms: its sheet takes 30.5 → 28.1 M instructions on one
//! thread; the RPP arm's, whose classes seldom recur, 7.68 → 7.81 M).
//!
//! Each class goes the way [`super::tidy_poly_by`] takes a whole sum on ranks; wherever that way
//! would leave the ranks (a base that is not plain, a contraction that ends on the expressions with
//! no sum to rank), the whole sum goes the old way instead. Debug builds check every result against
//! the whole sum's.

use super::leading::groups_of;
use super::memo::Memo;
use super::ranked::{contract_ranked, rank_sum};
use super::share::share_cofactors;
use crate::algebra::atom::{self, AtomId};
use crate::algebra::expr::{Expr, Kind};
use crate::algebra::number::Rational;
use crate::algebra::poly::{Mono, Poly};
use crate::algebra::symbol::Symbol;
use std::hash::{Hash, Hasher};

/// The display form of `p` by leading parameter (what [`super::tidy_poly_by`] gives for
/// [`super::Grouping::Leading`]), class by class; `None` when a class cannot be taken on ranks
/// (then the whole sum goes the usual way).
pub(super) fn tidy_leading(p: &Poly) -> Option<Expr> {
    let classes = classes(p)?;
    let mut items = Vec::with_capacity(classes.len());
    for class in classes {
        items.extend(CLASSES.get_or_owned(Class::new(class), |c| items_of(&c.poly))?);
    }
    Some(share_cofactors(&Expr::sum(items)))
}

/// The classes met, with their products: the display items [`super::leading`] makes of a class's
/// terms once contracted (one product, or none when the terms cancel), `None` for a class that
/// cannot be taken on ranks.
pub(super) static CLASSES: Memo<Class, Option<Vec<Expr>>> = Memo::new();

/// A class with its hash, found once: the memo's lookup and its insertion hash the number alone.
#[derive(Clone, PartialEq, Eq)]
pub(super) struct Class {
    hash: u64,
    poly: Poly,
}

impl Class {
    fn new(poly: Poly) -> Class {
        let mut h = crate::algebra::fast_hash::FxHasher::default();
        poly.hash(&mut h);
        Class {
            hash: h.finish(),
            poly,
        }
    }
}

impl Hash for Class {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(self.hash);
    }
}

/// The terms of `p` by leading parameter, each class a polynomial (its terms in `p`'s order); `None`
/// when an atom of `p` is not a plain base (a symbol, π, a sine or cosine of a sum of symbols).
fn classes(p: &Poly) -> Option<Vec<Poly>> {
    let (atoms, _) = atom::distinct(p.terms().iter().map(|(m, _)| m.factors()));
    let mut params: Vec<(AtomId, Expr)> = Vec::new();
    for &id in &atoms {
        let e = atom::to_expr(id);
        if !(e.is_plain_base() && super::factor::plain(&e)) {
            return None;
        }
        if atom::class(id) == atom::Class::Param {
            debug_assert!(matches!(e.kind(), Kind::Sym(Symbol::Param(_))));
            params.push((id, e));
        }
    }
    // Each parameter's place in the canonical order (the leading one of a term comes first), by id.
    params.sort_by(|x, y| x.1.cmp(&y.1));
    let mut place: Vec<(AtomId, usize)> = params
        .iter()
        .enumerate()
        .map(|(n, (id, _))| (*id, n))
        .collect();
    place.sort_unstable();
    // The classes by leading factor, in the order met (a sum has a dozen or so).
    let mut by_lead: Vec<(Lead, Vec<(Mono, Rational)>)> = Vec::new();
    for (m, c) in p.terms() {
        // A monomial's factors are sorted by id, and a parameter's id comes first (its class is 0).
        let lead = m
            .factors()
            .iter()
            .take_while(|&&(id, _)| atom::class(id) == atom::Class::Param)
            .map(|&(id, k)| {
                let n = place
                    .binary_search_by_key(&id, |&(a, _)| a)
                    .map(|i| place[i].1)
                    .expect("a parameter of the sum");
                (n, (id, k))
            })
            .min_by_key(|&(n, _)| n)
            .map(|(_, lead)| lead);
        let terms = match by_lead.iter().position(|(l, _)| *l == lead) {
            Some(i) => &mut by_lead[i].1,
            None => {
                by_lead.push((lead, Vec::new()));
                &mut by_lead.last_mut().expect("just pushed").1
            }
        };
        terms.push((m.clone(), c.clone()));
    }
    Some(
        by_lead
            .into_iter()
            .map(|(_, terms)| Poly::from_sorted_terms(terms))
            .collect(),
    )
}

/// A term's leading parameter and its power, by atom; `None` for a term without a parameter.
type Lead = Option<(AtomId, i32)>;

/// The display items of one class: its terms contracted on ranks and grouped by their (one)
/// leading parameter.
fn items_of(class: &Poly) -> Option<Vec<Expr>> {
    let (contracted, ranks) = contract_ranked(class.ranked()?);
    match ranks {
        Some(s) => groups_of(&s.bases, &s.terms, &s.constant),
        None => {
            let r = rank_sum(&contracted)?;
            groups_of(&r.bases, &r.terms, &r.constant)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::testing::example_components;
    use super::super::{contract, group, Grouping};
    use super::*;
    use crate::parse::parse_expr;

    /// The usual way: the whole sum contracted, then grouped.
    fn whole(p: &Poly) -> Expr {
        group(&contract::contract_normal(&p.to_expr()), Grouping::Leading)
    }

    /// Class by class is the whole sum's display form: on the Newton–Euler vectors of the example
    /// scenes in both frames (most of them go class by class), and on sums made to meet the edge
    /// cases (a constant, terms without a parameter, a leading power, negative powers, a class
    /// whose terms contract to one, a class that cancels as a function, bases left to the
    /// expressions).
    #[test]
    fn class_by_class_is_the_whole_sums_display_form() {
        let mut sums: Vec<Poly> = example_components(&["elbow", "rpp", "scara", "stanford"])
            .into_iter()
            .filter(|p| p.len() >= 2)
            .collect();
        for text in [
            "m1*g + m2*g + 3",
            "m2 + m2*l1*qdd1 + m2*lc2*qdd1 - 4 + qd1*qd2",
            "m2^2*l1 + m2*lc1 + m2^2*lc2",
            "m2/x + m2*y/x - 1/x",
            "m2*l1*cos(q1)*cos(q2) - m2*l1*sin(q1)*sin(q2) + m3*g",
            "m2*cos(q1)^2 + m2*sin(q1)^2 - m2 + m3*a*cos(q1)",
            "m1*a - m1*a*cos(q2)^2 + m2*b*sin(q2)*cos(q2)",
            "sqrt(2)*m1*a + sqrt(2)*m1*b",
            "m1*sin(2*q1 + q2) + m1*cos(q1)",
        ] {
            sums.push(crate::algebra::to_poly(&parse_expr(text).unwrap()));
        }
        let mut by_classes = 0;
        for p in &sums {
            if let Some(e) = tidy_leading(p) {
                by_classes += 1;
                assert_eq!(e, whole(p), "{:?}", p.to_expr());
            }
        }
        assert!(
            by_classes > 200,
            "only {by_classes} of {} sums class by class",
            sums.len()
        );
    }

    /// A class's terms are `p`'s terms of one leading parameter: every term in one class, the
    /// classes apart.
    #[test]
    fn the_classes_split_the_terms_by_leading_parameter() {
        let p = crate::algebra::to_poly(
            &parse_expr("m2^2*l1 + m2*lc1 + m2*m1*a + m1*b*cos(q1) + qd1 + 3").unwrap(),
        );
        let mut shown: Vec<String> = classes(&p)
            .unwrap()
            .iter()
            .map(|c| crate::print::to_string(&c.to_expr(), crate::print::Style::Ascii))
            .collect();
        shown.sort();
        assert_eq!(
            shown,
            [
                "m1*m2*a + m1*b*cos(q1)", // m1 leads m1 m2 a (m1 < m2)
                "m2*lc1",
                "m2^2*l1",
                "qd1 + 3",
            ]
        );
    }
}
