//! Terms that share an abbreviation share one coefficient: when two terms of a line have the same
//! sum abbreviated (`\Xi_{13}`) and differ only in their masses, lengths and coefficient, the line
//! reads `-\left(m_{3} + m_{4}\right) \Xi_{13}`, as a person would write it, not
//! `-m_{3} \Xi_{13} - m_{4} \Xi_{13}`.
//!
//! Only terms whose abbreviation was made by [`super::Layout::lines`] take part: a sum that fits its
//! line is shown as the display form gives it (`m_{2} \ddot{q}_{2} + m_{3} \ddot{q}_{2}` in the PPP
//! sheet stays), so the merging never changes what a reader sees of a short result. The merged term
//! is kept only when it fits the line; it equals the terms it replaces, `Σ P_i R = (Σ P_i) R`.

use crate::algebra::tidy::factor_list;
use crate::algebra::{Expr, Kind, Symbol};

/// One term of a line after [`super::Layout::fit_term`]: its LaTeX and, when a sum of it was
/// abbreviated, the term split as `P R`: `P` its coefficient and its masses and lengths, `R` the
/// abbreviation with the other factors.
pub(super) struct Fitted {
    /// The term's LaTeX.
    pub text: String,
    /// `(P, R)` when a sum of the term was abbreviated.
    pub split: Option<(Expr, Expr)>,
}

/// A parameter or a coordinate (a prismatic joint's `q3` is a length like `d4`), or a sum of
/// products of them (`l_{c3} - q_{3}`): what may go into a shared coefficient.
pub(super) fn is_length(b: &Expr) -> bool {
    let plain = |e: &Expr| {
        matches!(
            e.kind(),
            Kind::Sym(Symbol::Param(_)) | Kind::Sym(Symbol::Coord { order: 0, .. })
        )
    };
    match b.kind() {
        Kind::Add(_, ts) => ts
            .iter()
            .all(|(t, _)| plain(t) || t.factors().iter().all(|(f, _)| plain(f))),
        _ => plain(b),
    }
}

/// The LaTeX of the terms of a line, those that share an abbreviation merged into the first of
/// them (when the merged term is at most `room` wide). `latex` prints one signed term.
pub(super) fn merge(
    terms: Vec<Fitted>,
    room: usize,
    latex: impl Fn(&Expr) -> String,
) -> Vec<String> {
    // The terms with each `R` that occurs more than once, in order of first occurrence.
    let mut groups: Vec<(&Expr, Vec<usize>)> = Vec::new();
    for (i, t) in terms.iter().enumerate() {
        if let Some((_, r)) = &t.split {
            match groups.iter_mut().find(|(key, _)| *key == r) {
                Some((_, members)) => members.push(i),
                None => groups.push((r, vec![i])),
            }
        }
    }
    // Position of a group's first term -> its merged text; the other members are dropped.
    let mut merged: Vec<(usize, Option<String>)> = Vec::new();
    let mut dropped = vec![false; terms.len()];
    for (r, members) in groups.iter().filter(|(_, m)| m.len() >= 2) {
        let coefficient = Expr::sum(members.iter().map(|&i| {
            let (p, _) = terms[i].split.as_ref().expect("a member has a split");
            p.clone()
        }));
        let text = if coefficient.is_zero() {
            None
        } else {
            let term = Expr::product(factor_list(&coefficient).into_iter().chain([(*r).clone()]));
            let text = latex(&term);
            if super::width(&text) > room {
                continue;
            }
            Some(text)
        };
        merged.push((members[0], text));
        for &i in &members[1..] {
            dropped[i] = true;
        }
    }
    terms
        .into_iter()
        .enumerate()
        .filter(|(i, _)| !dropped[*i])
        .filter_map(|(i, t)| match merged.iter().find(|(at, _)| *at == i) {
            Some((_, text)) => text.clone(),
            None => Some(t.text),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::parse_expr;

    fn fitted(p: &str, r: Option<&str>) -> Fitted {
        let p = parse_expr(p).unwrap();
        match r {
            Some(r) => {
                let r = parse_expr(r).unwrap();
                Fitted {
                    text: ascii(&(&p * &r)),
                    split: Some((p, r)),
                }
            }
            None => Fitted {
                text: ascii(&p),
                split: None,
            },
        }
    }

    fn ascii(e: &Expr) -> String {
        crate::print::to_string(e, crate::print::Style::Ascii)
    }

    #[test]
    fn terms_that_share_an_abbreviation_share_their_coefficient() {
        let terms = vec![
            fitted("-m3", Some("Xi1")),
            fitted("g", None),
            fitted("-m4", Some("Xi1")),
            fitted("m2", Some("Xi2*qd1")),
        ];
        let got = merge(terms, 66, ascii);
        assert_eq!(got.len(), 3, "{got:?}");
        assert_eq!(got[0], ascii(&parse_expr("-(m3 + m4)*Xi1").unwrap()));
        assert_eq!(got[2], ascii(&parse_expr("m2*Xi2*qd1").unwrap()));
        // Lengths in the coefficient, and a coefficient that cancels.
        let terms = vec![
            fitted("m3*(lc3 - q3)", Some("Xi3")),
            fitted("-m4*(d4 - lc4 + q3)", Some("Xi3")),
            fitted("a", Some("Xi4")),
            fitted("-a", Some("Xi4")),
        ];
        let got = merge(terms, 66, ascii);
        let want = parse_expr("(m3*(lc3 - q3) - m4*(d4 - lc4 + q3))*Xi3").unwrap();
        assert_eq!(got, vec![ascii(&want)]);
    }

    #[test]
    fn a_merged_term_too_wide_for_the_line_is_not_made() {
        let terms = vec![
            fitted("m3*(lc3 - q3)", Some("Xi3")),
            fitted("-m4*d4", Some("Xi3")),
        ];
        let texts: Vec<String> = terms.iter().map(|t| t.text.clone()).collect();
        assert_eq!(merge(terms, 10, ascii), texts);
    }

    #[test]
    fn lengths() {
        for (text, yes) in [
            ("m3", true),
            ("q3", true),
            ("lc3 - q3", true),
            ("a1*a2 + d4", true),
            ("qd1", false),
            ("cos(q1)", false),
            ("qd1 + a", false),
        ] {
            assert_eq!(is_length(&parse_expr(text).unwrap()), yes, "{text}");
        }
    }
}
