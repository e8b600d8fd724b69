//! The compact Newton–Euler program as text: one line per intermediate, `w3_2 = …`, then the equations
//! `τ_k = u_k` (text, ASCII, or a LaTeX `align*` environment), and as a JSON document.

use crate::algebra::{Expr, Poly, Symbol};
use crate::dynamics::ne_compact::CompactProgram;
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

/// The program as JSON: `{"robot", "method": "newton-euler-compact", "frame": "body",
/// "intermediates": [{"name", "value"}], "tau": [{"input", "value"}], "ops": {"mul", "add"}}`, with
/// expressions in parser-readable ASCII.
pub fn program_json(p: &CompactProgram, robot_name: &str, inputs: &[String]) -> Value {
    let ascii = |poly: &Poly| print::to_string(&poly.to_expr(), Style::Ascii);
    let ops = p.op_count();
    json!({
        "robot": robot_name,
        "method": "newton-euler-compact",
        "frame": "body",
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
