//! A large equation side measured as it is printed: the display terms that
//! [`print::equation`](crate::print::equation) lays out from the normal form are written straight
//! into a [`MeasuredSum`] (their texts one after another, each with its width, the groups too wide
//! for a row kept apart to be named), so no display term is built and no text is copied or scanned
//! twice. The result is the [`measure`](super::measure) of
//! [`equation::pieces`](crate::print::equation::pieces), which a test pins.

use super::{
    measured_bytes, measured_hash, room_before, width, Left, Measured, MeasuredBody, MeasuredSum,
    PreparedEquation, BUDGET,
};
use crate::algebra::atom::AtomId;
use crate::algebra::{Poly, Rational};
use crate::print::equation::{lay_out_parts, parentheses, parts_ranks, separator, Sink};
use crate::print::poly::Renderer;
use crate::print::Style;
use std::sync::Arc;

/// A sum being measured: its terms so far, their width with their signs (a sign is two units),
/// whether one of them has a space (a sum in parentheses is compact without), and for a group the
/// text of the factors before its parentheses.
struct Open {
    sum: MeasuredSum,
    width: usize,
    spaced: bool,
    before: String,
}

impl Open {
    fn new(before: String, capacity: usize) -> Open {
        Open {
            sum: MeasuredSum {
                text: String::with_capacity(capacity),
                terms: Vec::new(),
                hash: 0,
            },
            width: 0,
            spaced: false,
            before,
        }
    }

    /// Counts the sign of a new term: every term's but a first positive one.
    fn sign(&mut self, negative: bool) {
        if negative || !self.sum.terms.is_empty() {
            self.width += 2;
        }
    }

    /// The [`width`] of the sum printed: `0` when it has no terms.
    fn width(&self) -> usize {
        if self.sum.terms.is_empty() {
            1
        } else {
            self.width
        }
    }
}

/// The sink of [`PreparedEquation::from_poly`]: the open sums, the side's own first, and the room of
/// the side's rows.
struct Measuring {
    frames: Vec<Open>,
    room: usize,
    /// Whether a group that fits its row holds one too wide for a row (which the rooms' order rules
    /// out; the caller then measures the side the other way).
    mixed: bool,
}

impl Measuring {
    /// The room of the rows of the sum at `depth`: the side's own, or an abbreviation's (given on
    /// rows of its own after the equations). Never less at a greater depth, so a group too wide
    /// for its row is always inside groups too wide for theirs.
    fn room(&self, depth: usize) -> usize {
        if depth == 0 {
            self.room
        } else {
            room_before("")
        }
    }
}

/// The text of a group's factors (`m_{2}`, `\ddot{q}_{1}`), or nothing for none.
fn factors_text(r: &mut Renderer, factors: &[(u32, i32)]) -> String {
    let mut out = String::new();
    if !factors.is_empty() {
        r.product_into(&mut out, &Rational::one(), factors);
    }
    out
}

impl Sink for Measuring {
    fn product(&mut self, r: &mut Renderer, c: &Rational, factors: &[(u32, i32)]) {
        let f = self.frames.last_mut().expect("a frame");
        f.sign(c.is_negative());
        let start = f.sum.text.len();
        let m = r.measured_product(&mut f.sum.text, c, factors);
        let end = f.sum.text.len();
        let w = m.width;
        f.spaced |= m.spaced;
        f.width += w;
        f.sum.terms.push(Measured {
            negative: c.is_negative(),
            body: MeasuredBody::Text {
                start,
                end,
                width: w,
            },
        });
    }

    fn open(&mut self, r: &mut Renderer, before: &[(u32, i32)]) {
        let before = factors_text(r, before);
        self.frames.push(Open::new(before, 0));
    }

    fn close(&mut self, r: &mut Renderer, after: &[(u32, i32)]) {
        let inner = self.frames.pop().expect("an open group");
        let after = factors_text(r, after);
        // `\left(` and `\right)` are one unit each.
        let w = width(&inner.before) + width(&after) + 2 + inner.width();
        let room = self.room(self.frames.len() - 1);
        let has_wide = inner
            .sum
            .terms
            .iter()
            .any(|t| matches!(t.body, MeasuredBody::Wide { .. }));
        let parent = self.frames.last_mut().expect("the side's frame");
        parent.sign(false);
        parent.width += w;
        // In LaTeX a group with factors is spaced (`m_{2} \left(…\right)`).
        parent.spaced |= !inner.before.is_empty() || !after.is_empty() || inner.spaced;
        if w > room {
            let mut sum = inner.sum;
            sum.hash = measured_hash(&sum);
            parent.sum.terms.push(Measured {
                negative: false,
                body: MeasuredBody::Wide {
                    before: inner.before,
                    inner: Arc::new(sum),
                    after,
                },
            });
            return;
        }
        self.mixed |= has_wide;
        // The group as one text, as `Body::write` prints it.
        let out = &mut parent.sum.text;
        let start = out.len();
        let (open, close) = parentheses(Style::Latex);
        if !inner.before.is_empty() {
            out.push_str(&inner.before);
            out.push(separator(Style::Latex));
        }
        out.push_str(open);
        if inner.sum.terms.is_empty() {
            out.push('0');
        }
        let (plus, minus) = if inner.spaced {
            (" + ", " - ")
        } else {
            ("+", "-")
        };
        for (i, t) in inner.sum.terms.iter().enumerate() {
            match (i, t.negative) {
                (0, false) => {}
                (0, true) => out.push('-'),
                (_, false) => out.push_str(plus),
                (_, true) => out.push_str(minus),
            }
            if let MeasuredBody::Text { start, end, .. } = t.body {
                out.push_str(&inner.sum.text[start..end]);
            }
        }
        out.push_str(close);
        if !after.is_empty() {
            out.push(separator(Style::Latex));
            out.push_str(&after);
        }
        let end = out.len();
        let width = width(&out[start..end]);
        parent.sum.terms.push(Measured {
            negative: false,
            body: MeasuredBody::Text { start, end, width },
        });
    }
}

impl PreparedEquation {
    /// [`PreparedEquation::new`] of the display terms of a large side `p`
    /// ([`equation::pieces`](crate::print::equation::pieces) in LaTeX), measured as they are
    /// printed. `None` when an atom of `p` is outside the plain class, or the side could fit on one
    /// line beside `rhs`: [`PreparedEquation::new`] takes those.
    pub fn from_poly(p: &Poly, rhs: String) -> Option<PreparedEquation> {
        PreparedEquation::from_parts(&[(p, &[])], rhs)
    }

    /// [`PreparedEquation::from_poly`] of the side `Σ_i p_i · m_i` from its parts, without
    /// multiplying it out ([`side_text_of_parts`](crate::print::equation::side_text_of_parts));
    /// `None` also when the side cannot be laid out from them.
    pub fn from_parts(
        parts: &[(&Poly, &[(AtomId, i32)])],
        rhs: String,
    ) -> Option<PreparedEquation> {
        let (ranks, terms) = parts_ranks(parts)?;
        let mut sink = Measuring {
            frames: vec![Open::new(String::new(), 48 * terms)],
            room: room_before(&format!(" = {rhs}")),
            mixed: false,
        };
        if !lay_out_parts(parts, &[], &ranks, Style::Latex, &mut sink) {
            return None;
        }
        let side = sink.frames.pop().expect("the side's frame");
        let fits = BUDGET
            .checked_sub(2 + width(&rhs))
            .is_some_and(|room| side.width() <= room);
        if sink.mixed || fits {
            return None;
        }
        let mut sum = side.sum;
        sum.hash = measured_hash(&sum);
        let bytes = rhs.len() + measured_bytes(&sum);
        Some(PreparedEquation {
            rhs,
            line: None,
            left: Left::Measured(Arc::new(sum)),
            bytes,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Layout, Side};
    use super::*;
    use crate::algebra::to_poly;
    use crate::parse::parse_expr;
    use crate::print::equation::pieces;

    fn p(s: &str) -> Poly {
        to_poly(&parse_expr(s).expect("valid expression"))
    }

    /// The equation prepared from its display terms, the way `from_poly` is checked against.
    fn from_pieces(p: &Poly, rhs: &str) -> PreparedEquation {
        let shown = pieces(p, Style::Latex).expect("plain atoms");
        PreparedEquation::new(Side::Shown(shown), rhs.to_string())
    }

    /// Sides of many kinds, each scaled up until its groups are too wide for a row: products and
    /// groups by acceleration and rate, groups by leading parameter inside them (compact and spaced),
    /// negative leading terms, a constant.
    fn sides() -> Vec<Poly> {
        let long =
            "(a1*sin(q2) + a2*cos(q3) + a3*sin(q2)*cos(q3) + a4*sin(q4) + a5 + a6*cos(q2)^2)";
        [
            "m1*(rx1^2 + rz1^2)*qdd1 + m2*(l1^2 + 2*l1*lc2*cos(q2) + lc2^2)*qdd1 - m2*l1*lc2*sin(q2)*qd2^2 \
             + I2*qdd2 + g*m1*cos(q1) - 1/2*g*m2*sin(q1)*cos(q2) + qd1*qd2*(a - b) - 7"
                .to_string(),
            format!("m2*{long}^2*qdd1 + m3*{long}*qdd1 - 2/3*m4*{long}*qd1*qd2 + b*qd2^2 + {long}*g"),
            format!("-{long}^3*qdd2 + (c + d)*qd1*qd3 - x*{long}*qd3^2 + m1*{long} - 1/7*m2*sin(q5)"),
            "qdd1*(m1 + m2) + qdd2*(m3^2*x - y) + m4*(u + v)*cos(q4) - 3".to_string(),
        ]
        .iter()
        .map(|s| p(s))
        .collect()
    }

    #[test]
    fn measured_while_printed_is_measured_from_the_display_terms() {
        let (mut checked, mut wide) = (0, 0);
        for side in sides() {
            // Right sides of every width from 1 to 40 units, so that a group's width meets the
            // room of its row exactly for one of them, and passes it by one for the next.
            for rhs in (1..=40).map(|k| "u".repeat(k)) {
                let rhs = rhs.as_str();
                let Some(prepared) = PreparedEquation::from_poly(&side, rhs.to_string()) else {
                    // Only a side that fits a line beside rhs is left to the other way.
                    let fits = from_pieces(&side, rhs).line.is_some();
                    assert!(fits, "{side:?} = {rhs} was not measured");
                    continue;
                };
                let expected = from_pieces(&side, rhs);
                wide += format!("{expected:?}").matches("Wide").count();
                assert_eq!(format!("{prepared:?}"), format!("{expected:?}"), "{rhs}");
                assert_eq!(
                    Layout::new().equations_prepared(vec![prepared]),
                    Layout::new().equations_prepared(vec![expected])
                );
                checked += 1;
            }
        }
        assert!(
            checked >= 6,
            "most sides are too long for a line: {checked}"
        );
        assert!(wide >= 6, "groups too wide for a row, nested too: {wide}");
    }

    #[test]
    fn a_side_that_fits_a_line_is_left_to_the_display_terms() {
        let side = p("m1*qdd1 + g*m1");
        assert!(PreparedEquation::from_poly(&side, "u_{1}".into()).is_none());
        assert!(from_pieces(&side, "u_{1}").line.is_some());
    }
}
