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

use super::{lhs_strings, quantity_string, tau, Method, JSON_TIDY_BUDGET};
use crate::algebra::Poly;
use crate::dynamics::Derivation;
use crate::print::poly::polys_to_strings;
use crate::print::Style;
use serde_json::{json as j, Value};

/// The quantities of a document printed in ASCII, the large ones by one shared polynomial printer.
struct Quantities {
    big: std::collections::HashMap<*const Poly, String>,
}

impl Quantities {
    fn new(polys: &[&Poly]) -> Quantities {
        let large: Vec<&Poly> = polys
            .iter()
            .copied()
            .filter(|p| p.len() > JSON_TIDY_BUDGET)
            .collect();
        let strings = polys_to_strings(&large, Style::Ascii);
        Quantities {
            big: large
                .into_iter()
                .map(|p| p as *const Poly)
                .zip(strings)
                .collect(),
        }
    }

    /// `p` printed (each large polynomial's text is taken, not copied: every quantity is printed once).
    fn ascii(&mut self, p: &Poly) -> Value {
        Value::String(match self.big.remove(&(p as *const Poly)) {
            Some(s) => s,
            None => quantity_string(p, Style::Ascii, JSON_TIDY_BUDGET),
        })
    }

    fn matrix(&mut self, m: &[Vec<Poly>]) -> Value {
        Value::Array(
            m.iter()
                .map(|r| Value::Array(r.iter().map(|p| self.ascii(p)).collect()))
                .collect(),
        )
    }
}

/// The JSON document of a derivation.
pub fn json(der: &Derivation, method: Method) -> Value {
    let el = der.lagrange();
    let (method_name, frame) = match method {
        Method::Lagrange => ("lagrange", Value::Null),
        Method::NewtonEuler(f) => ("newton-euler", Value::String(f.name().into())),
    };
    let lhs: Vec<String> = lhs_strings(tau(der, method), Style::Ascii);
    let equations: Vec<Value> = lhs
        .iter()
        .zip(&der.robot().inputs)
        .map(|(l, u)| j!({ "lhs": l, "rhs": u }))
        .collect();
    let nonzero = el.nonzero_christoffel();
    let mut all: Vec<&Poly> = el.d.iter().chain(&el.c).flatten().collect();
    all.extend(nonzero.iter().map(|(_, _, _, c)| *c));
    all.extend(el.g.iter());
    all.push(&el.p);
    let mut q = Quantities::new(&all);
    let christoffel: Vec<Value> = nonzero
        .iter()
        .map(|(i, jj, k, c)| j!({ "i": i, "j": jj, "k": k, "value": q.ascii(c) }))
        .collect();
    let mass_matrix = q.matrix(&el.d);
    let coriolis = q.matrix(&el.c);
    let gravity: Vec<Value> = el.g.iter().map(|p| q.ascii(p)).collect();
    let potential = q.ascii(&el.p);
    j!({
        "robot": der.robot().name,
        "method": method_name,
        "frame": frame,
        "coordinates": der.coordinates().iter().map(|s| s.ascii_name()).collect::<Vec<_>>(),
        "inputs": der.robot().inputs,
        "mass_matrix": mass_matrix,
        "coriolis": coriolis,
        "christoffel": christoffel,
        "gravity": gravity,
        "potential": potential,
        "equations": equations,
        "tau": lhs,
        "facts": der.facts().iter().map(|f| f.to_string()).collect::<Vec<_>>(),
        "warnings": der.warnings().iter().map(|w| w.to_string()).collect::<Vec<_>>(),
    })
}
