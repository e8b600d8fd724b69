//! Reports of a derivation as text: the equations of motion (text, ASCII or LaTeX), the JSON document
//! and the proof report. Pure functions from a [`Derivation`] to strings or JSON values; no I/O.

mod compact;
mod json;
mod pretty;
mod sides;

pub use compact::{
    lagrange_json as compact_lagrange_json, lagrange_program as compact_lagrange,
    program as compact_program, program_json as compact_json,
};
pub use json::{json, json_text, write_json};
pub use pretty::{doc_to_pretty, to_pretty, write_pretty, Doc};

use crate::algebra::atom::AtomId;
use crate::algebra::tidy::equation_terms_poly;
use crate::algebra::{Expr, Poly, Symbol};
use crate::dynamics::check::Claim;
use crate::dynamics::lagrange::{multiplied_out, SideParts};
use crate::dynamics::{Derivation, Frame};
use crate::print::layout::{Layout, PreparedEquation, Side};
use crate::print::{self, Style};

/// Which formulation gives the equations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Euler–Lagrange: `D(q) q̈ + C(q, q̇) q̇ + g(q) = τ`.
    Lagrange,
    /// Recursive Newton–Euler, in the given frame.
    NewtonEuler(Frame),
}

/// The left sides `τ_k` of the equations by the chosen method (by Euler–Lagrange, as soon as its
/// third stage is derived, before `C` and `K`).
pub fn tau(der: &Derivation, method: Method) -> &[Poly] {
    match method {
        Method::Lagrange => der.left_sides(),
        Method::NewtonEuler(frame) => &der.newton_euler(frame).tau,
    }
}

/// The display terms of equation `k`'s left side, in house order.
pub fn lhs_terms(tau_k: &Poly) -> Vec<Expr> {
    equation_terms_poly(tau_k)
}

/// The number of terms beyond which an expression is printed straight from its normal form (grouped
/// by accelerations, velocities and leading parameter, angle sums left expanded) rather than tidied
/// into the house style: tidying costs far more than deriving at that size and reads no better.
pub const DISPLAY_BUDGET: usize = 200;

/// Equation `k`'s left side printed in `style`: in house style ([`lhs_terms`]) while it has at most
/// [`DISPLAY_BUDGET`] terms, straight from the normal form beyond ([`print::equation`]).
pub fn lhs_string(tau_k: &Poly, style: Style) -> String {
    if tau_k.len() > DISPLAY_BUDGET {
        if let Some(text) = print::equation::side_text(tau_k, style) {
            return text;
        }
    }
    print::sum_to_string(&lhs_terms(tau_k), style)
}

/// [`lhs_string`] of `τ_k` from its parts ([`side_parts`](crate::dynamics::lagrange::side_parts)),
/// never multiplied out when it is printed from the normal form: the same text.
pub fn lhs_string_of_parts(parts: &SideParts, style: Style) -> String {
    lhs_string_of_parts_lent(parts, &[], style)
}

/// [`lhs_string_of_parts`] with the coefficients of some parts printed before (`lent[i]` for
/// part `i`; [`print::equation::Lent`]), copied where they can be: the same text.
pub(crate) fn lhs_string_of_parts_lent(
    parts: &SideParts,
    lent: &[Option<print::equation::Lent>],
    style: Style,
) -> String {
    if parts.iter().map(|(p, _)| p.len()).sum::<usize>() > DISPLAY_BUDGET {
        if let Some(text) = print::equation::side_text_of_parts_lent(&part_refs(parts), lent, style)
        {
            return text;
        }
    }
    lhs_string(&multiplied_out(parts), style)
}

/// Side parts as the printers take them: each coefficient and what it multiplies.
pub(crate) fn part_refs<'p>(parts: &'p SideParts) -> Vec<(&'p Poly, &'p [(AtomId, i32)])> {
    parts.iter().map(|(c, by)| (&**c, &by[..])).collect()
}

/// [`lhs_string`] of every equation, on several threads when there is enough to print
/// ([`print::parallel::map`], heaviest first): the large sides are printed from the normal form by
/// a renderer that reads and writes strings only (no tidying, no new atoms), the small ones tidied
/// on canonical expressions in their structural order, so the text is the same on any number of
/// threads.
pub fn lhs_strings(taus: &[Poly], style: Style) -> Vec<String> {
    print::parallel::map(taus, side_work, PARALLEL_WORK, |t| lhs_string(t, style))
}

/// The work of printing an equation side, for [`print::parallel::map`], in units of about 3 ns:
/// tidying costs about the square of its terms (the numeric PUMA 560's 185-term τ₂, 2.3 ms), printing
/// from the normal form about a quarter of a microsecond a term.
pub(crate) fn side_work(t: &Poly) -> usize {
    work_of_side(t.len())
}

/// [`side_work`] of a side of `terms` terms.
pub(crate) fn work_of_side(terms: usize) -> usize {
    if terms > DISPLAY_BUDGET {
        64 * terms
    } else {
        20 * terms * terms
    }
}

/// The work ([`side_work`]) below which the equations are printed on the calling thread: about a
/// third of a millisecond, the cost of starting a thread (the PPP, elbow and SCARA arms stay on one).
const PARALLEL_WORK: usize = 100_000;

/// Every equation `τ_k = rhs_k` prepared for the LaTeX layout ([`PreparedEquation`]: the left side
/// by [`lhs_side`], printed and measured), on several threads as [`lhs_strings`].
pub fn prepared_equations(taus: &[Poly], rhs: &[String]) -> Vec<PreparedEquation> {
    let items: Vec<(&Poly, &String)> = taus.iter().zip(rhs).collect();
    print::parallel::map(
        &items,
        |(t, _)| side_work(t),
        PARALLEL_WORK,
        |(t, r)| {
            // A large side is measured as it is printed; a small one tidied first.
            (t.len() > DISPLAY_BUDGET)
                .then(|| PreparedEquation::from_poly(t, r.to_string()))
                .flatten()
                .unwrap_or_else(|| PreparedEquation::new(lhs_side(t), r.to_string()))
        },
    )
}

/// The number of terms beyond which a quantity of a JSON document (`D`, `C`, `c_ijk`, `g`, `P`) is
/// given as its normal form rather than tidied: a document is read by programs, and tidying its many
/// medium-sized entries would cost more than deriving them.
pub const JSON_TIDY_BUDGET: usize = 16;

/// Equation `k`'s left side for the LaTeX layout: house-style terms while it has at most
/// [`DISPLAY_BUDGET`] terms, display terms from the normal form beyond.
pub fn lhs_side(tau_k: &Poly) -> Side {
    if tau_k.len() > DISPLAY_BUDGET {
        if let Some(shown) = print::equation::pieces(tau_k, Style::Latex) {
            return Side::Shown(shown);
        }
    }
    Side::Terms(lhs_terms(tau_k))
}

/// An expression printed in `style`: simplified into the house style while it has at most `budget`
/// terms, its normal form as it stands beyond.
pub fn quantity_string(p: &Poly, style: Style, budget: usize) -> String {
    if p.len() > budget {
        return print::poly::poly_to_string(p, style);
    }
    print::to_string(
        &crate::algebra::tidy::tidy_poly_by(p, crate::algebra::tidy::Grouping::Trig),
        style,
    )
}

/// The equations of motion, one per line: `(m1+m2+m3) q̈1 + (m1+m2+m3) g = u1`. In LaTeX, an
/// `align*` environment whose lines stay within [`LINE_WIDTH`](crate::print::layout::LINE_WIDTH),
/// long equations broken across rows ([`Layout::equations`]).
pub fn equations(der: &Derivation, method: Method, style: Style) -> String {
    let rhs = inputs(der, style);
    let sides = sides::left_sides(der, method);
    if style == Style::Latex {
        return Layout::new().equations_prepared(prepared_sides(&sides, &rhs));
    }
    let lines: Vec<(String, String)> = side_strings(&sides, style).into_iter().zip(rhs).collect();
    equalities(&lines, style)
}

/// The left sides printed in `style`, on several threads as [`lhs_strings`].
fn side_strings(sides: &[sides::Lhs], style: Style) -> Vec<String> {
    print::parallel::map(sides, |l| l.work(), PARALLEL_WORK, |l| l.string(style))
}

/// The equations prepared for the LaTeX layout, on several threads as [`prepared_equations`].
fn prepared_sides(sides: &[sides::Lhs], rhs: &[String]) -> Vec<PreparedEquation> {
    let items: Vec<(&sides::Lhs, &String)> = sides.iter().zip(rhs).collect();
    print::parallel::map(
        &items,
        |(l, _)| l.work(),
        PARALLEL_WORK,
        |(l, r)| l.prepared(r.to_string()),
    )
}

/// [`equations`] written to `sink` (what `symdyn derive` prints): a large robot's text an equation
/// at a time, its `align*` environment a few rows at a time, never held whole.
pub fn write_equations(
    der: &Derivation,
    method: Method,
    style: Style,
    sink: &mut dyn std::io::Write,
) -> std::io::Result<()> {
    let rhs = inputs(der, style);
    let sides = sides::left_sides(der, method);
    if style == Style::Latex {
        return Layout::new().write_equations_prepared(prepared_sides(&sides, &rhs), sink);
    }
    for (l, r) in side_strings(&sides, style).iter().zip(&rhs) {
        for piece in [l.as_str(), " = ", r.as_str(), "\n"] {
            sink.write_all(piece.as_bytes())?;
        }
    }
    Ok(())
}

/// The right sides of the equations, the robot's inputs, printed in `style`.
fn inputs(der: &Derivation, style: Style) -> Vec<String> {
    der.robot()
        .inputs
        .iter()
        .map(|u| print::to_string(&Expr::sym(Symbol::new(u)), style))
        .collect()
}

/// `left = right` lines: one per line in text and ASCII, a LaTeX `align*` aligned at `=`.
pub fn equalities(lines: &[(String, String)], style: Style) -> String {
    match style {
        Style::Latex => {
            let body: Vec<String> = lines.iter().map(|(l, r)| format!("  {l} &= {r}")).collect();
            format!(
                "\\begin{{align*}}\n{}\n\\end{{align*}}\n",
                body.join(" \\\\\n")
            )
        }
        Style::Text | Style::Ascii => {
            let mut out =
                String::with_capacity(lines.iter().map(|(l, r)| l.len() + r.len() + 4).sum());
            for (l, r) in lines {
                out.push_str(l);
                out.push_str(" = ");
                out.push_str(r);
                out.push('\n');
            }
            out
        }
    }
}

/// The proof report: one line per claim, `proved [how]` or `FAILED [how]`, with the failing entries.
pub fn check_report(robot_name: &str, claims: &[Claim]) -> String {
    let mut out = format!("{robot_name}\n");
    for c in claims {
        let mark = if c.holds { "proved" } else { "FAILED" };
        out.push_str(&format!("  {mark} [{}]: {}\n", c.proof, c.statement));
        for f in &c.failures {
            out.push_str(&format!("      {f}\n"));
        }
    }
    out
}
