//! The JSON document of `symdyn derive --format json`: every expression in the ASCII syntax that the
//! parser reads back (`qdd1`, `qd2`, `^`, explicit `*`).
//!
//! ```text
//! { "robot": name, "method": "lagrange" | "newton-euler", "frame": null | "body" | "inertial",
//!   "coordinates": ["q1", ...], "inputs": ["u1", ...],
//!   "mass_matrix": [[expr]], "coriolis": [[expr]], "gravity": [expr],
//!   "christoffel": [{"i": 1, "j": 2, "k": 1, "value": expr}],     // the non-zero c_ijk
//!   "potential": expr,
//!   "equations": [{"lhs": expr, "rhs": "u1"}], "tau": [expr],
//!   "facts": [sentence], "warnings": [sentence] }
//! ```
//! `mass_matrix`, `coriolis`, `christoffel`, `gravity` and `potential` come from Euler–Lagrange;
//! `equations` and `tau` from the chosen method (they are proved equal by `symdyn check`).

use super::{lhs_terms, tau, Method};
use crate::algebra::tidy::tidy;
use crate::algebra::Poly;
use crate::dynamics::Derivation;
use crate::print::{self, Style};
use serde_json::{json as j, Value};

fn ascii(p: &Poly) -> Value {
    Value::String(print::to_string(&tidy(&p.to_expr()), Style::Ascii))
}

fn matrix(m: &[Vec<Poly>]) -> Value {
    Value::Array(
        m.iter()
            .map(|r| Value::Array(r.iter().map(ascii).collect()))
            .collect(),
    )
}

/// The JSON document of a derivation.
pub fn json(der: &Derivation, method: Method) -> Value {
    let el = der.lagrange();
    let (method_name, frame) = match method {
        Method::Lagrange => ("lagrange", Value::Null),
        Method::NewtonEuler(f) => ("newton-euler", Value::String(f.name().into())),
    };
    let tau = tau(der, method);
    let equations: Vec<Value> = tau
        .iter()
        .zip(&der.robot().inputs)
        .map(|(t, u)| {
            let lhs = print::sum_to_string(&lhs_terms(t), Style::Ascii);
            j!({ "lhs": lhs, "rhs": u })
        })
        .collect();
    let christoffel: Vec<Value> = el
        .nonzero_christoffel()
        .into_iter()
        .map(|(i, jj, k, c)| j!({ "i": i, "j": jj, "k": k, "value": ascii(c) }))
        .collect();
    j!({
        "robot": der.robot().name,
        "method": method_name,
        "frame": frame,
        "coordinates": der.coordinates().iter().map(|s| s.ascii_name()).collect::<Vec<_>>(),
        "inputs": der.robot().inputs,
        "mass_matrix": matrix(&el.d),
        "coriolis": matrix(&el.c),
        "christoffel": christoffel,
        "gravity": el.g.iter().map(ascii).collect::<Vec<_>>(),
        "potential": ascii(&el.p),
        "equations": equations,
        "tau": tau.iter().map(|t| print::sum_to_string(&lhs_terms(t), Style::Ascii)).collect::<Vec<_>>(),
        "facts": der.facts().iter().map(|f| f.to_string()).collect::<Vec<_>>(),
        "warnings": der.warnings().iter().map(|w| w.to_string()).collect::<Vec<_>>(),
    })
}
