//! Reports of a derivation as text: the equations of motion (text, ASCII or LaTeX), the JSON document
//! and the proof report. Pure functions from a [`Derivation`] to strings or JSON values; no I/O.

mod compact;
mod json;

pub use compact::{
    lagrange_json as compact_lagrange_json, lagrange_program as compact_lagrange,
    program as compact_program, program_json as compact_json,
};
pub use json::json;

use crate::algebra::tidy::equation_terms;
use crate::algebra::{Expr, Poly, Symbol};
use crate::dynamics::check::Claim;
use crate::dynamics::{Derivation, Frame};
use crate::print::{self, Style};

/// Which formulation gives the equations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Euler–Lagrange: `D(q) q̈ + C(q, q̇) q̇ + g(q) = τ`.
    Lagrange,
    /// Recursive Newton–Euler, in the given frame.
    NewtonEuler(Frame),
}

/// The left sides `τ_k` of the equations by the chosen method.
pub fn tau(der: &Derivation, method: Method) -> &[Poly] {
    match method {
        Method::Lagrange => &der.lagrange().tau,
        Method::NewtonEuler(frame) => &der.newton_euler(frame).tau,
    }
}

/// The display terms of equation `k`'s left side, in house order.
pub fn lhs_terms(tau_k: &Poly) -> Vec<Expr> {
    equation_terms(&tau_k.to_expr())
}

/// The equations of motion, one per line: `(m1+m2+m3) q̈1 + (m1+m2+m3) g = u1`. In LaTeX, an
/// `align*` environment.
pub fn equations(der: &Derivation, method: Method, style: Style) -> String {
    let lines: Vec<(String, String)> = tau(der, method)
        .iter()
        .zip(&der.robot().inputs)
        .map(|(t, u)| {
            let input = print::to_string(&Expr::sym(Symbol::new(u)), style);
            (print::sum_to_string(&lhs_terms(t), style), input)
        })
        .collect();
    equalities(&lines, style)
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
        Style::Text | Style::Ascii => lines.iter().map(|(l, r)| format!("{l} = {r}\n")).collect(),
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
