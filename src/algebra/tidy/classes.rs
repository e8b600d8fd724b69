//! The display form by leading parameter ([`super::Grouping::Leading`]) of a polynomial, class by
//! class, each class's quotient remembered.
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
//! class (the terms of one leading parameter) contracted and grouped alone.
//!
//! A class `s L^k Q` (its leading parameter `L^k`, its first coefficient `s`) is contracted and
//! grouped as its quotient `Q` is, times `s L^k`:
//! - `L` is the first factor of each of its terms in the canonical order (no base orders before a
//!   parameter but π, and a sum holding π goes the whole sum's way), so dividing it out keeps the
//!   order of the terms and of every candidate pair of a pass, and each pass pairs and merges `Q`'s
//!   terms as the class's; every rule is linear in the coefficients (a pair is `c`, `±c`), so
//!   scaling by `1/s` changes none of them;
//! - the group of the class is `Q` contracted (the grouping divides the key out), and its factors
//!   are those of `Q`'s, the content times `s`.
//!
//! A quotient recurs from vector to vector, under the same and other leading parameters: in the
//! inertial frame a link's share of the force `f_i`, `m_j (a_c,j − g)`, is the same in every `f_i`
//! up to that link, the SCARA arm's links 3 and 4 share `a_c`'s first two components (`m_3 Ξ` and
//! `m_4 Ξ`), a link's inertia terms recur in every moment `n_i` up to it, and the products of
//! inertia of a link multiply the same sums with either sign (`I_{4xz} Ξ_16 − I_{4yz} Ξ_17`, then
//! `−I_{4yz} Ξ_16 − I_{4xz} Ξ_17`). [`QUOTIENTS`]
//! remembers each quotient's factors, so one met again is not contracted and grouped again. The
//! SCARA arm's sheet meets 232 classes in its distinct components: remembered as classes, 158 were
//! new (1 400 terms); as quotients, 87 (990 terms). Instructions on one thread: its sheet 27.95 →
//! 26.48 M (30.5 M with no memo); the RPP arm's 7.79 → 7.75 M; the Stanford arm's and the
//! all-symbolic PUMA 560's within 0.1%.
//!
//! Each class goes the way [`super::tidy_poly_by`] takes a whole sum on ranks; wherever that way
//! would leave the ranks (a base that is not plain, a contraction that ends on the expressions with
//! no sum to rank), the whole sum goes the old way instead. Debug builds check every result against
//! the whole sum's.

use super::leading::key_divided;
use super::memo::Memo;
use super::ranked::{contract_to_ranks, rank_sum};
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
        items.extend(class.item()?);
    }
    Some(share_cofactors(&Expr::sum(items)))
}

/// The factors each quotient of a class met makes ([`Class::item`]): `Some(None)` for one whose
/// terms cancel, `None` for one that cannot be taken on ranks.
pub(super) static QUOTIENTS: Memo<Quotient, Option<Option<Vec<Expr>>>> = Memo::new();

/// The terms of one leading parameter `L^k` of a sum, as `s L^k Q`: `Q` their quotient, whose
/// first coefficient is 1.
struct Class {
    /// `L` and `k`, or `None` for the terms without a parameter.
    lead: Lead,
    /// `s`.
    scale: Rational,
    /// `Q`.
    quotient: Quotient,
}

/// A class's quotient ([`Class`]) with its hash, found once: the memo's lookup and its insertion
/// hash the number alone.
#[derive(Clone, PartialEq, Eq)]
pub(super) struct Quotient {
    hash: u64,
    poly: Poly,
}

impl Quotient {
    fn new(poly: Poly) -> Quotient {
        let mut h = crate::algebra::fast_hash::FxHasher::default();
        poly.hash(&mut h);
        Quotient {
            hash: h.finish(),
            poly,
        }
    }
}

impl Hash for Quotient {
    fn hash<H: Hasher>(&self, state: &mut H) {
        state.write_u64(self.hash);
    }
}

impl Class {
    /// The class's display item, `None` when its terms cancel: the factors of its quotient
    /// contracted and grouped ([`factors_of`], remembered), the first of them, the content, times
    /// the class's scale, and the key `L^k`. `None` (outer) when the quotient cannot be taken on
    /// ranks.
    fn item(self) -> Option<Option<Expr>> {
        let Some(mut factors) = QUOTIENTS.get_or_owned(self.quotient, |q| factors_of(&q.poly))?
        else {
            return Some(None);
        };
        if !self.scale.is_one() {
            let Kind::Num(content) = factors[0].kind() else {
                unreachable!("the factors of a group start with its content")
            };
            factors[0] = Expr::num(content * &self.scale);
        }
        if let Some((id, k)) = self.lead {
            factors.push(
                atom::to_expr(id)
                    .pow(i64::from(k))
                    .expect("a parameter is not zero"),
            );
        }
        Some(Some(Expr::product(factors)))
    }
}

/// The terms of `p` by leading parameter, each class as its quotient and scale; `None` when an
/// atom of `p` is not a plain base (a symbol, a sine or cosine of a sum of symbols), or is π (the
/// one plain base that orders before the parameters).
fn classes(p: &Poly) -> Option<Vec<Class>> {
    let (atoms, _) = atom::distinct(p.terms().iter().map(|(m, _)| m.factors()));
    let mut params: Vec<(AtomId, Expr)> = Vec::new();
    for &id in &atoms {
        let e = atom::to_expr(id);
        if !(e.is_plain_base() && super::factor::plain(&e)) || matches!(e.kind(), Kind::Pi) {
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
    // The classes by leading factor, in the order met (a sum has a dozen or so): each term divided
    // by its leading factor, which is the first of its factors in the canonical order (no base
    // here orders before a parameter). So the quotient's terms keep their canonical order, and
    // every pass pairs and merges them as it would the class's.
    // Each term's class, and each class's lead and size (so that its terms are gathered in a
    // vector of their number).
    let mut leads: Vec<(Lead, usize)> = Vec::with_capacity(16);
    let class_of: Vec<usize> = p
        .terms()
        .iter()
        .map(|(m, _)| {
            // A monomial's factors are sorted by id, and a parameter's id comes first (its class
            // is 0).
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
            match leads.iter().position(|(l, _)| *l == lead) {
                Some(i) => {
                    leads[i].1 += 1;
                    i
                }
                None => {
                    leads.push((lead, 1));
                    leads.len() - 1
                }
            }
        })
        .collect();
    let mut by_lead: Vec<(Lead, Vec<(Mono, Rational)>)> = leads
        .into_iter()
        .map(|(lead, n)| (lead, Vec::with_capacity(n)))
        .collect();
    for ((m, c), &i) in p.terms().iter().zip(&class_of) {
        let (lead, terms) = &mut by_lead[i];
        let lead = *lead;
        let m = match lead {
            Some((id, _)) => Mono::from_sorted(
                m.factors()
                    .iter()
                    .filter(|&&(a, _)| a != id)
                    .copied()
                    .collect(),
            ),
            None => m.clone(),
        };
        terms.push((m, c.clone()));
    }
    Some(
        by_lead
            .into_iter()
            .map(|(lead, mut terms)| {
                // The quotient's terms sorted again: the monomials' own order is by atom id, which
                // dividing by a parameter may change.
                terms.sort_unstable_by(|x, y| x.0.cmp(&y.0));
                // Scaled by `1/s` (nothing to do for 1, a negation for −1: the common cases).
                let scale = terms[0].1.clone();
                if scale.is_minus_one() {
                    for (_, c) in &mut terms {
                        *c = -&*c;
                    }
                } else if !scale.is_one() {
                    let over = scale.recip().expect("a term's coefficient is not zero");
                    for (_, c) in &mut terms {
                        *c = &*c * &over;
                    }
                }
                Class {
                    lead,
                    scale,
                    quotient: Quotient::new(Poly::from_sorted_terms(terms)),
                }
            })
            .collect(),
    )
}

/// A term's leading parameter and its power, by atom; `None` for a term without a parameter.
type Lead = Option<(AtomId, i32)>;

/// The factors of a class's quotient ([`Class::item`]): its terms contracted on ranks and
/// factored as the grouping by leading parameter factors a group ([`key_divided`]).
fn factors_of(quotient: &Poly) -> Option<Option<Vec<Expr>>> {
    match contract_to_ranks(quotient.ranked()?) {
        Ok(s) => key_divided(&s.bases, &s.terms, &s.constant),
        Err(contracted) => {
            let r = rank_sum(&contracted)?;
            key_divided(&r.bases, &r.terms, &r.constant)
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
    /// expressions, one quotient under several leading parameters and scales, negative and
    /// fractional ones, a quotient with a constant, π).
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
            "m3*a*cos(q1)*cos(q2) - m3*a*sin(q1)*sin(q2) - 2*m4*a*cos(q1)*cos(q2) \
             + 2*m4*a*sin(q1)*sin(q2) + I2*a*cos(q1)*cos(q2)/3 - I2*a*sin(q1)*sin(q2)/3",
            "-m2^2*cos(q1)^2*b + m2^2*b + m3*b*sin(q1)^2 - 5*lc1*b*cos(q1)^2 + 5*lc1*b",
            "m2*qd1 + m2 - m3*qd1 - m3 + 2*a*qd1 + 2*a",
            "pi*m1*a + pi*m1*b + m2*cos(q1)",
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

    /// A class's terms are `p`'s terms of one leading parameter `L^k`, as `s L^k Q`: every term in
    /// one class, the classes apart, `Q` with the first coefficient 1 (in the polynomial's order,
    /// where a constant comes first); a sum holding π is left to the whole sum's way.
    #[test]
    fn the_classes_split_the_terms_by_leading_parameter() {
        let ascii = |e: &Expr| crate::print::to_string(e, crate::print::Style::Ascii);
        let p = crate::algebra::to_poly(
            &parse_expr("m2^2*l1 + m2*lc1 + 2*m2*m1*a - 4*m1*b*cos(q1) + qd1/3 + 3").unwrap(),
        );
        let mut shown: Vec<String> = classes(&p)
            .unwrap()
            .iter()
            .map(|c| {
                let lead = c.lead.map_or(Expr::one(), |(id, k)| {
                    atom::to_expr(id).pow(i64::from(k)).unwrap()
                });
                format!(
                    "{} | {} | {}",
                    c.scale,
                    ascii(&lead),
                    ascii(&c.quotient.poly.to_expr())
                )
            })
            .collect();
        shown.sort();
        assert_eq!(
            shown,
            [
                "1 | m2 | lc1",
                "1 | m2^2 | l1",
                "2 | m1 | m2*a - 2*b*cos(q1)", // m1 leads m1 m2 a (m1 < m2)
                "3 | 1 | 1/9*qd1 + 1",         // the constant is the first term
            ]
        );
        let with_pi = crate::algebra::to_poly(&parse_expr("pi*m1*a + m2*b").unwrap());
        assert!(classes(&with_pi).is_none());
    }
}
