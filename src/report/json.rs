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

use super::{lhs_string, quantity_string, tau, Method, JSON_TIDY_BUDGET};
use crate::algebra::Poly;
use crate::dynamics::Derivation;
use crate::print::parallel;
use crate::print::poly::{poly_to_string, Ranks, Renderer};
use crate::print::Style;
use serde_json::{json as j, Value};
use std::collections::HashMap;

/// One expression of a document to print.
enum Job<'a> {
    /// An equation's left side ([`lhs_string`]).
    Lhs(&'a Poly),
    /// A quantity past [`JSON_TIDY_BUDGET`] terms: its normal form, by the shared renderer.
    Large(&'a Poly),
    /// A smaller quantity, tidied ([`quantity_string`]).
    Small(&'a Poly),
}

/// Every expression of a document printed in ASCII, in the order of `jobs`, on several threads
/// ([`parallel::map`]: the text is the same on any number): the large quantities share one ranking
/// of their atoms.
fn print_all(jobs: &[Job]) -> Vec<String> {
    let large: Vec<&Poly> = jobs
        .iter()
        .filter_map(|j| match j {
            Job::Large(p) => Some(*p),
            _ => None,
        })
        .collect();
    let ranks = Ranks::of(large.iter().copied());
    let weight = |j: &Job| match j {
        Job::Lhs(p) | Job::Large(p) => p.len(),
        // Tidying costs far more per term than printing.
        Job::Small(p) => 20 * p.len() * p.len(),
    };
    parallel::map(jobs, weight, PARALLEL_WORK, |j| match j {
        Job::Lhs(p) => lhs_string(p, Style::Ascii),
        Job::Large(p) => match &ranks {
            Some(r) => Renderer::new(r, Style::Ascii).sum(p, false),
            None => poly_to_string(p, Style::Ascii),
        },
        Job::Small(p) => quantity_string(p, Style::Ascii, JSON_TIDY_BUDGET),
    })
}

/// Below this much work in all ([`print_all`]'s weights), a document is printed on one thread.
const PARALLEL_WORK: usize = 4000;

/// The JSON document of a derivation.
pub fn json(der: &Derivation, method: Method) -> Value {
    let el = der.lagrange();
    let (method_name, frame) = match method {
        Method::Lagrange => ("lagrange", Value::Null),
        Method::NewtonEuler(f) => ("newton-euler", Value::String(f.name().into())),
    };
    let taus = tau(der, method);
    let nonzero = el.nonzero_christoffel();
    let mut quantities: Vec<&Poly> = el.d.iter().chain(&el.c).flatten().collect();
    // c_ijk = c_jik: each symbol printed once, for i ≤ j, and its string given to both.
    quantities.extend(
        nonzero
            .iter()
            .filter(|(i, jj, _, _)| i <= jj)
            .map(|(_, _, _, c)| *c),
    );
    quantities.extend(el.g.iter());
    quantities.push(&el.p);
    let jobs: Vec<Job> = taus
        .iter()
        .map(Job::Lhs)
        .chain(quantities.iter().map(|&p| {
            if p.len() > JSON_TIDY_BUDGET {
                Job::Large(p)
            } else {
                Job::Small(p)
            }
        }))
        .collect();
    let mut printed = print_all(&jobs).into_iter().map(Value::String);
    let mut next = || printed.next().expect("one string per expression");
    let lhs: Vec<Value> = taus.iter().map(|_| next()).collect();
    let equations: Vec<Value> = lhs
        .iter()
        .zip(&der.robot().inputs)
        .map(|(l, u)| j!({ "lhs": l, "rhs": u }))
        .collect();
    let n = el.d.len();
    let mut matrix = |rows: usize| -> Value {
        Value::Array(
            (0..rows)
                .map(|_| Value::Array((0..n).map(|_| next()).collect()))
                .collect(),
        )
    };
    let mass_matrix = matrix(el.d.len());
    let coriolis = matrix(el.c.len());
    // Printed for i ≤ j; (j, i, k) comes later in index order and takes (i, j, k)'s string.
    let mut symbols: HashMap<(usize, usize, usize), Value> = HashMap::new();
    let christoffel: Vec<Value> = nonzero
        .iter()
        .map(|&(i, jj, k, _)| {
            let value = if i <= jj {
                let v = next();
                symbols.insert((i, jj, k), v.clone());
                v
            } else {
                symbols[&(jj, i, k)].clone()
            };
            j!({ "i": i, "j": jj, "k": k, "value": value })
        })
        .collect();
    let gravity: Vec<Value> = el.g.iter().map(|_| next()).collect();
    let potential = next();
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
