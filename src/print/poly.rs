//! Printing a polynomial of the normal form without building its canonical expression.
//!
//! [`poly_to_string`] prints exactly what `to_string(&p.to_expr(), style)` prints, at a fraction of the
//! cost: instead of building the canonical sum (every term a canonical product, the sum a sorted map
//! of expressions), it ranks the polynomial's few distinct atoms once by the canonical order of their
//! bases (`Expr`'s `cmp`), sorts each monomial's factors by rank and the terms by the canonical order
//! of products (factor lists compared base by base, the higher power first for an equal base, the
//! shorter list first), and lays out the [`Piece`]s the printers already print. Polynomials with
//! atoms outside the plain class (opaque expressions, sines of constant angles) take the canonical
//! route, so the result is always the same text.

use super::{latex, text, Piece, Product, Style};
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::{Expr, Poly, Rational};
use std::cmp::Ordering;

/// The atoms of some polynomials, ranked by the canonical order of their bases.
pub struct Ranks {
    /// Atom id → rank.
    of: FxHashMap<AtomId, u32>,
    /// The base of each rank.
    bases: Vec<Expr>,
}

/// Whether an atom prints as a plain base of a canonical product: a symbol, π, a surd, or `sin`/`cos`
/// of a symbol.
fn plain(id: AtomId) -> bool {
    match atom::class(id) {
        Class::Param | Class::Coord | Class::Pi | Class::Sqrt => true,
        Class::Sin | Class::Cos => atom::symbol_of(id).is_some(),
        Class::Other => false,
    }
}

impl Ranks {
    /// Ranks for the atoms of `polys`, or `None` if one of them is not plain.
    pub fn of<'a, I: IntoIterator<Item = &'a Poly>>(polys: I) -> Option<Ranks> {
        let mut ids: Vec<AtomId> = Vec::new();
        for p in polys {
            for (m, _) in p.terms() {
                ids.extend(m.factors().iter().map(|&(id, _)| id));
            }
        }
        ids.sort_unstable();
        ids.dedup();
        if !ids.iter().all(|&id| plain(id)) {
            return None;
        }
        let mut bases: Vec<(AtomId, Expr)> =
            ids.into_iter().map(|id| (id, atom::to_expr(id))).collect();
        bases.sort_by(|a, b| a.1.cmp(&b.1));
        Some(Ranks {
            of: bases
                .iter()
                .enumerate()
                .map(|(r, (id, _))| (*id, r as u32))
                .collect(),
            bases: bases.into_iter().map(|(_, e)| e).collect(),
        })
    }

    /// The pieces of `p` in the canonical order: terms as a canonical sum stores them, the constant
    /// last. `p`'s atoms must have been ranked.
    fn pieces(&self, p: &Poly) -> Vec<Piece> {
        let mut terms: Vec<(Vec<(u32, i32)>, &Rational)> = Vec::with_capacity(p.len());
        let mut constant = None;
        for (m, c) in p.terms() {
            if m.factors().is_empty() {
                constant = Some(c);
                continue;
            }
            let mut key: Vec<(u32, i32)> = m
                .factors()
                .iter()
                .map(|&(id, e)| (self.of[&id], e))
                .collect();
            key.sort_unstable_by_key(|&(r, _)| r);
            terms.push((key, c));
        }
        terms.sort_by(|a, b| cmp_factor_lists(&a.0, &b.0));
        let mut out: Vec<Piece> = terms
            .into_iter()
            .map(|(key, c)| {
                let factors: Vec<(Expr, i64)> = key
                    .iter()
                    .map(|&(r, e)| (self.bases[r as usize].clone(), e as i64))
                    .collect();
                Piece {
                    negative: c.is_negative(),
                    product: Product::new(&c.abs(), &factors),
                }
            })
            .collect();
        if let Some(c) = constant {
            out.push(Piece {
                negative: c.is_negative(),
                product: Product::new(&c.abs(), &[]),
            });
        }
        out
    }
}

/// Factor lists in the canonical order of products: base by base (by rank), for an equal base the
/// higher power first, then the shorter list first.
fn cmp_factor_lists(a: &[(u32, i32)], b: &[(u32, i32)]) -> Ordering {
    for (x, y) in a.iter().zip(b) {
        let o = x.0.cmp(&y.0).then_with(|| y.1.cmp(&x.1));
        if o != Ordering::Equal {
            return o;
        }
    }
    a.len().cmp(&b.len())
}

/// `p` printed in `style`: the same text as `to_string(&p.to_expr(), style)`.
pub fn poly_to_string(p: &Poly, style: Style) -> String {
    match Ranks::of([p]) {
        Some(r) => sum_string(&r.pieces(p), style, false),
        None => super::to_string(&p.to_expr(), style),
    }
}

/// Several polynomials printed in `style`, their atoms ranked once.
pub fn polys_to_strings(ps: &[&Poly], style: Style) -> Vec<String> {
    match Ranks::of(ps.iter().copied()) {
        Some(r) => ps
            .iter()
            .map(|p| sum_string(&r.pieces(p), style, false))
            .collect(),
        None => ps
            .iter()
            .map(|p| super::to_string(&p.to_expr(), style))
            .collect(),
    }
}

fn sum_string(pieces: &[Piece], style: Style, nested: bool) -> String {
    match style {
        Style::Text | Style::Ascii => text::Printer::new(style).sum(pieces, nested),
        Style::Latex => latex::sum(pieces, nested),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn prints_what_the_canonical_expression_prints() {
        let rows = [
            "0",
            "-3/2",
            "m1 + m2 + m3",
            "(m1 + m2)*g*cos(q1) - 2*a*sin(q1)*cos(q2)^2 + 1/2*I2*qdd1 - 3",
            "m2*lc2^2*sin(q2)^2 + 2*m2*l1*lc2*cos(q2) + I1 + I2 + m1*lc1^2",
            "qd1^2*qd2 - qd1*qd2^2 + qd1*qd2 + qd2^3*sin(q1)*sin(q3) + x^2 + x*y + y^2",
            "pi*m1/2 + sqrt(2)*a/3 - m1/lc2 + g*m1/(l1*l2)",
            "(a + b)^4*qdd3*sin(q2)*cos(q1) + theta1*alpha2 - lambda*gamma",
        ];
        for s in rows {
            let poly = p(s);
            for style in [Style::Text, Style::Ascii, Style::Latex] {
                assert_eq!(
                    poly_to_string(&poly, style),
                    super::super::to_string(&poly.to_expr(), style),
                    "{s} in {style:?}"
                );
            }
        }
    }
}
