//! Compact programs as text: one line per named intermediate, `w3_2 = …`, then the quantities and
//! equations over the names (text, ASCII, or a LaTeX `align*` environment), and as JSON documents.
//!
//! - Newton–Euler ([`program`], [`program_json`]): the intermediates, then `u_k = τ_k`.
//! - Euler–Lagrange ([`lagrange_program`], [`lagrange_json`]): the intermediates of `D` (composite
//!   rigid bodies, `D1_2`), of the Christoffel symbols (`c1_2_3 = c_123`, from the derivatives of
//!   `D`'s names, `D1_2_q3 = ∂D1_2/∂q3`) and of `g` (`g1`, from `P`), then each equation in the book's
//!   form, `Σ_j d_kj q̈_j + Σ_{i≤j} (2 − δ_ij) c_ijk q̇_i q̇_j + g_k = u_k`: the Coriolis and
//!   centrifugal terms by their Christoffel symbols.

use crate::algebra::compact::Compact;
use crate::algebra::{Expr, Poly, Rational, Symbol};
use crate::dynamics::compact::CompactDynamics;
use crate::dynamics::ne_compact::{CompactProgram, OpCount};
use crate::print::{self, Style};
use serde_json::{json, Value};

fn line(name: &Expr, value: &Poly, style: Style) -> (String, String) {
    (
        print::to_string(name, style),
        print::to_string(&value.to_expr(), style),
    )
}

/// The program, one line per intermediate (`w3_2 = q̇1 sin(q2) + …`), then one per actuated input
/// (`u1 = n1_3`). In LaTeX, an `align*` environment.
pub fn program(p: &CompactProgram, inputs: &[String], style: Style) -> String {
    let mut lines: Vec<(String, String)> = p
        .intermediates
        .iter()
        .map(|l| line(&Expr::sym(l.symbol.clone()), &l.value, style))
        .collect();
    for (t, u) in p.tau.iter().zip(inputs) {
        lines.push(line(&Expr::sym(Symbol::new(u)), t, style));
    }
    super::equalities(&lines, style)
}

/// The program as JSON: `{"robot", "method": "newton-euler-compact", "frame",
/// "intermediates": [{"name", "value"}], "tau": [{"input", "value"}], "ops": {"mul", "add"}}`, with
/// expressions in parser-readable ASCII.
pub fn program_json(p: &CompactProgram, robot_name: &str, frame: &str, inputs: &[String]) -> Value {
    let ops = p.op_count();
    json!({
        "robot": robot_name,
        "method": "newton-euler-compact",
        "frame": frame,
        "intermediates": p.intermediates.iter().map(|l| json!({
            "name": l.symbol.ascii_name(),
            "value": ascii(&l.value),
        })).collect::<Vec<_>>(),
        "tau": p.tau.iter().zip(inputs).map(|(t, u)| json!({
            "input": u,
            "value": ascii(t),
        })).collect::<Vec<_>>(),
        "ops": {"mul": ops.mul, "add": ops.add},
    })
}

fn ascii(p: &Poly) -> String {
    print::to_string(&p.to_expr(), Style::Ascii)
}

/// Every output of the compact Euler–Lagrange derivation, in listing order.
fn lagrange_outputs(cd: &CompactDynamics) -> Vec<&Poly> {
    let n = cd.d.len();
    let mut out: Vec<&Poly> = Vec::new();
    for k in 0..n {
        out.extend(cd.d[k][k..].iter());
    }
    for (_, _, _, c) in cd.nonzero_christoffel() {
        out.push(c);
    }
    out.extend(cd.g.iter());
    out.push(&cd.p);
    out.extend(cd.tau.iter());
    out
}

/// The intermediates `outputs` need, as `name = value` lines.
fn intermediate_lines(arena: &Compact, outputs: &[&Poly], style: Style) -> Vec<(String, String)> {
    arena
        .live(outputs.iter().copied())
        .into_iter()
        .map(|k| {
            let d = &arena.defs()[k];
            line(&Expr::sym(d.symbol.clone()), &d.value, style)
        })
        .collect()
}

/// Equation `k`'s left side in the book's form, as display terms: `d_kj q̈_j`, then
/// `(2 − δ_ij) c_ijk q̇_i q̇_j` for `i ≤ j`, then `g_k` (zero terms left out).
fn lagrange_terms(cd: &CompactDynamics, k: usize) -> Vec<Expr> {
    let n = cd.d.len();
    let mut terms = Vec::new();
    for j in 0..n {
        let d = &cd.d[k][j];
        if !d.is_zero() {
            terms.push(d.to_expr() * Expr::qdd(j as u32 + 1));
        }
    }
    for i in 0..n {
        for j in i..n {
            let c = &cd.christoffel[i][j][k];
            if c.is_zero() {
                continue;
            }
            let rates = Expr::qd(i as u32 + 1) * Expr::qd(j as u32 + 1);
            let two = if i == j {
                Rational::one()
            } else {
                Rational::int(2)
            };
            terms.push((c.to_expr() * rates).scale(&two));
        }
    }
    if !cd.g[k].is_zero() {
        terms.push(cd.g[k].to_expr());
    }
    terms
}

/// The compact Euler–Lagrange derivation: the intermediates (`D`, the Christoffel symbols, `g`, all
/// named), then one equation per input in the book's form. In LaTeX, an `align*` environment.
pub fn lagrange_program(cd: &CompactDynamics, inputs: &[String], style: Style) -> String {
    let mut lines = intermediate_lines(&cd.arena, &lagrange_outputs(cd), style);
    for (k, u) in inputs.iter().enumerate() {
        let terms = lagrange_terms(cd, k);
        let lhs = if terms.is_empty() {
            "0".to_string()
        } else {
            print::sum_to_string(&terms, style)
        };
        lines.push((lhs, print::to_string(&Expr::sym(Symbol::new(u)), style)));
    }
    super::equalities(&lines, style)
}

/// The compact Euler–Lagrange derivation as JSON, with the keys of the expanded document
/// (`mass_matrix`, `coriolis`, `christoffel`, `gravity`, `potential`, `equations`, `tau`) holding
/// expressions over the names, and `intermediates` (`[{"name", "value"}]`) defining the names in
/// order; `ops` counts the operations of the intermediates and the outputs (no sharing counted).
pub fn lagrange_json(cd: &CompactDynamics, robot_name: &str, inputs: &[String]) -> Value {
    let outputs = lagrange_outputs(cd);
    let live = cd.arena.live(outputs.iter().copied());
    let matrix = |m: &[Vec<Poly>]| -> Value {
        Value::Array(
            m.iter()
                .map(|r| Value::Array(r.iter().map(|p| Value::String(ascii(p))).collect()))
                .collect(),
        )
    };
    let ops = OpCount::of_all(
        live.iter()
            .map(|&k| &cd.arena.defs()[k].value)
            .chain(cd.tau.iter()),
    );
    json!({
        "robot": robot_name,
        "method": "lagrange",
        "compact": true,
        "intermediates": live.iter().map(|&k| {
            let d = &cd.arena.defs()[k];
            json!({"name": d.symbol.ascii_name(), "value": ascii(&d.value)})
        }).collect::<Vec<_>>(),
        "mass_matrix": matrix(&cd.d),
        "coriolis": matrix(&cd.c),
        "christoffel": cd.nonzero_christoffel().into_iter().map(|(i, j, k, c)| {
            json!({"i": i, "j": j, "k": k, "value": ascii(c)})
        }).collect::<Vec<_>>(),
        "gravity": cd.g.iter().map(ascii).collect::<Vec<_>>(),
        "potential": ascii(&cd.p),
        "equations": inputs.iter().enumerate().map(|(k, u)| {
            let terms = lagrange_terms(cd, k);
            let lhs = if terms.is_empty() { "0".to_string() } else { print::sum_to_string(&terms, Style::Ascii) };
            json!({"lhs": lhs, "rhs": u})
        }).collect::<Vec<_>>(),
        "tau": cd.tau.iter().map(ascii).collect::<Vec<_>>(),
        "ops": {"mul": ops.mul, "add": ops.add},
    })
}
