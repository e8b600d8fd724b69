//! The regressor and the base parameters as text, LaTeX and JSON: pure functions, the CLI prints
//! what they return.
//!
//! Entries of `Y` are printed expanded while each expands within [`DISPLAY_BUDGET`] terms; beyond, in
//! compact form over named intermediates, which are listed first (`intermediates` in JSON).

use super::base::{BaseParameters, Fate};
use super::regressor::{Gravity, Regressor};
use crate::algebra::compact::identity::{Outcome, Proof};
use crate::algebra::compact::Compact;
use crate::algebra::{Poly, Symbol};
use crate::print::layout::width;
use crate::print::poly::poly_to_string;
use crate::print::Style;
use serde_json::{json, Value};

/// The largest expanded entry (terms) printed expanded.
pub const DISPLAY_BUDGET: usize = 400;

/// Whether a set of proofs holds, and how it was decided (`exact`, or `randomized: k random rational
/// points, P(wrong) < 2^e` by the union bound).
pub fn proof_summary(outcomes: &[Outcome]) -> (bool, String) {
    let mut holds = true;
    let mut points = 0;
    let mut error = 0.0f64;
    let mut randomized = false;
    for o in outcomes {
        match o {
            Outcome::Equal(Proof::Exact) => {}
            Outcome::Equal(p @ Proof::Randomized { points: k, .. }) => {
                randomized = true;
                points = points.max(*k);
                error += (p.error_log2() + 200.0).exp2();
            }
            _ => holds = false,
        }
    }
    let how = if !holds {
        "FAILED".to_string()
    } else if randomized {
        format!(
            "randomized: {points} random rational points, P(wrong) < 2^{}",
            (error.log2() - 200.0).ceil() as i64
        )
    } else {
        "exact".to_string()
    };
    (holds, how)
}

/// The entries of `Y` (or any polynomials over the regressor's arena) ready to print: expanded where
/// small, and the intermediates the others need.
struct Printed {
    entries: Vec<Vec<Poly>>,
    intermediates: Vec<(Symbol, Poly)>,
}

fn printable(arena: &Compact, rows: &[Vec<Poly>]) -> Printed {
    let mut ex = arena.expander(DISPLAY_BUDGET);
    let mut compact: Vec<&Poly> = Vec::new();
    let entries = rows
        .iter()
        .map(|row| {
            row.iter()
                .map(|p| match ex.expand(p) {
                    Ok(e) => e,
                    Err(_) => {
                        compact.push(p);
                        p.clone()
                    }
                })
                .collect()
        })
        .collect();
    let intermediates = arena
        .live(compact)
        .into_iter()
        .map(|k| {
            let d = &arena.defs()[k];
            (d.symbol.clone(), d.value.clone())
        })
        .collect();
    Printed {
        entries,
        intermediates,
    }
}

fn gravity_words(reg: &Regressor) -> String {
    match reg.options.gravity {
        Gravity::Scene => format!(
            "gravity: the scene's, [{}]",
            reg.model
                .gravity
                .iter()
                .map(|g| g.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Gravity::Input => {
            "gravity: an input vector [gx, gy, gz] in frame 0 (--gravity-input)".into()
        }
    }
}

fn names(reg: &Regressor, ks: impl IntoIterator<Item = usize>) -> Vec<String> {
    ks.into_iter().map(|k| reg.params[k].name()).collect()
}

/// `Y` (and, with `base`, the base parameters) as text in `style` (`Text` or `Ascii`).
pub fn text(
    reg: &Regressor,
    base: Option<&BaseParameters>,
    tau_proof: &[Outcome],
    style: Style,
) -> String {
    let mut s = String::new();
    let n = reg.dof();
    let np = reg.params.len();
    s.push_str(&format!(
        "{}: tau = Y pi, Y is {n} x {np} ({})\n",
        reg.robot,
        gravity_words(reg)
    ));
    s.push_str(&format!(
        "standard parameters (per link: inertia about the frame origin, first moments, mass{}):\n  {}\n",
        if reg.options.rotors { ", rotor inertia" } else { "" },
        names(reg, 0..np).join(" ")
    ));
    if reg.model.payload.is_some() {
        s.push_str(&format!(
            "the payload is part of link {n}: its parameters about o_{n} add to link {n}'s (the fit identifies the two together)\n"
        ));
    }
    let zero: Vec<usize> = (0..np).filter(|&k| reg.zero_column(k)).collect();
    s.push_str(&format!(
        "structurally zero columns ({}): {}\n",
        zero.len(),
        names(reg, zero.iter().copied()).join(" ")
    ));
    let (holds, how) = proof_summary(tau_proof);
    s.push_str(&format!(
        "{} [{how}]: Y pi = tau (pi from the scene's masses, centres of mass and inertias by parallel axes)\n",
        if holds { "proved" } else { "NOT proved" }
    ));
    match base {
        None => {
            let printed = printable(&reg.arena, &reg.y);
            if !printed.intermediates.is_empty() {
                s.push_str("where\n");
                for (sym, v) in &printed.intermediates {
                    s.push_str(&format!(
                        "  {} = {}\n",
                        sym.ascii_name(),
                        poly_to_string(v, style)
                    ));
                }
            }
            for (i, row) in printed.entries.iter().enumerate() {
                s.push_str(&format!("row {}:\n", i + 1));
                for (k, e) in row.iter().enumerate() {
                    if !e.is_zero() {
                        s.push_str(&format!(
                            "  Y{}[{}] = {}\n",
                            i + 1,
                            reg.params[k].name(),
                            poly_to_string(e, style)
                        ));
                    }
                }
            }
        }
        Some(b) => s.push_str(&base_text(reg, b, style)),
    }
    s
}

/// The base parameters as text.
pub fn base_text(reg: &Regressor, b: &BaseParameters, style: Style) -> String {
    let mut s = String::new();
    s.push_str(&format!(
        "base parameters: {} of {} ({})\n",
        b.count(),
        reg.params.len(),
        gravity_words(reg)
    ));
    if !b.random_symbols.is_empty() {
        s.push_str(&format!(
            "  symbolic geometry (random values in the elimination): {}; the scene's numbers decide special values\n",
            b.random_symbols.join(", ")
        ));
    }
    if let Err(why) = &b.coefficients {
        s.push_str(&format!("  note: {why}\n"));
    }
    for p in &b.base {
        let rhs = match b.expression(p, &reg.params) {
            Some(e) => poly_to_string(&e, style),
            None => p
                .terms
                .iter()
                .map(|(k, _)| reg.params[*k].name())
                .collect::<Vec<_>>()
                .join(", "),
        };
        if p.terms.len() == 1 {
            s.push_str(&format!("  {} (alone)\n", p.name));
        } else {
            let sep = if b.coefficients.is_ok() {
                "="
            } else {
                "groups"
            };
            s.push_str(&format!("  {} {sep} {rhs}\n", p.name));
        }
    }
    let no_effect: Vec<String> = b
        .eliminated
        .iter()
        .filter(|(_, f)| matches!(f, Fate::NoEffect | Fate::Vanishes))
        .map(|(k, _)| reg.params[*k].name())
        .collect();
    s.push_str(&format!(
        "no effect ({}): {}\n",
        no_effect.len(),
        no_effect.join(" ")
    ));
    s.push_str("grouped:\n");
    for (k, f) in &b.eliminated {
        if let Fate::Grouped { into, rule } = f {
            let into: Vec<&str> = into.iter().map(|&r| b.base[r].name.as_str()).collect();
            s.push_str(&format!(
                "  {} into {}: {rule}\n",
                reg.params[*k].name(),
                into.join(", ")
            ));
        }
    }
    if b.coefficients.is_ok() {
        let (h1, how1) = proof_summary(&b.dependency_proofs);
        let (h2, how2) = proof_summary(&b.tau_proofs);
        let word = |h| if h { "proved" } else { "NOT proved" };
        s.push_str(&format!(
            "{} [{how1}]: Y_beta beta = Y pi for every pi (each grouped column a combination of the base columns, row by row)\n",
            word(h1)
        ));
        s.push_str(&format!(
            "{} [{how2}]: Y_beta beta = tau for the scene's parameters\n",
            word(h2)
        ));
        s.push_str(&format!(
            "so the count is exact: {} independent columns at a random state, and the other columns proved dependent\n",
            b.count()
        ));
    } else {
        s.push_str(&format!(
            "the count {} is the rank of Y at random exact states ({} rows): a lower bound that is exact with high probability, not proved\n",
            b.count(),
            b.rows
        ));
    }
    s
}

/// The base parameters in LaTeX: one display per grouped parameter, then those alone.
pub fn latex(reg: &Regressor, b: &BaseParameters) -> String {
    let mut s = String::new();
    let mut alone = Vec::new();
    for p in &b.base {
        let name = latex_name(&p.name);
        if p.terms.len() == 1 {
            alone.push(name);
            continue;
        }
        let terms: Option<Vec<String>> = p
            .terms
            .iter()
            .map(|(k, c)| Some(latex_term(c.as_ref()?, &latex_name(&reg.params[*k].name()))))
            .collect();
        match terms {
            Some(t) => s.push_str(&latex_equation(&name, &t)),
            None => s.push_str(&format!(
                "\\[ {name} \\ni {} \\]\n",
                p.terms
                    .iter()
                    .map(|(k, _)| latex_name(&reg.params[*k].name()))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        }
    }
    if !alone.is_empty() {
        s.push_str(&format!("\\[ {} \\]\n", alone.join(",\\; ")));
    }
    s
}

/// `c · name` in LaTeX: `name`, `-name`, `a_{2}^{2} name`, `(… + …) name`.
pub fn latex_term(c: &Poly, name: &str) -> String {
    if let Some(k) = c.as_constant() {
        if k.is_one() {
            return name.to_string();
        }
        if k.is_minus_one() {
            return format!("-{name}");
        }
    }
    let cs = poly_to_string(c, Style::Latex);
    if c.len() == 1 {
        format!("{cs} \\, {name}")
    } else {
        format!("\\left({cs}\\right) {name}")
    }
}

/// `lhs = t1 + t2 + …` as display math, broken across `align*` lines at about 60 characters of
/// rendered width.
pub fn latex_equation(lhs: &str, terms: &[String]) -> String {
    let mut lines: Vec<String> = vec![String::new()];
    for t in terms {
        let last = lines.last_mut().expect("a line");
        let joined = if last.is_empty() {
            t.clone()
        } else if let Some(rest) = t.strip_prefix('-') {
            format!("{last} - {rest}")
        } else {
            format!("{last} + {t}")
        };
        if !last.is_empty() && width(&joined) > 60 {
            let next = if let Some(rest) = t.strip_prefix('-') {
                format!("- {rest}")
            } else {
                format!("+ {t}")
            };
            lines.push(next);
        } else {
            *last = joined;
        }
    }
    if lines.len() == 1 {
        return format!("\\[ {lhs} = {} \\]\n", lines[0]);
    }
    let body: Vec<String> = lines
        .iter()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                format!("{lhs} &= {l}")
            } else {
                format!("&\\quad {l}")
            }
        })
        .collect();
    format!(
        "\\begin{{align*}}\n{}\n\\end{{align*}}\n",
        body.join(" \\\\\n")
    )
}

/// `XXR2` as `\mathrm{XXR}_{2}`.
pub fn latex_name(name: &str) -> String {
    let split = name
        .find(|c: char| c.is_ascii_digit())
        .unwrap_or(name.len());
    format!("\\mathrm{{{}}}_{{{}}}", &name[..split], &name[split..])
}

/// The JSON document: `{"robot", "gravity", "standard", "regressor", "intermediates", "proved",
/// "base", "unidentifiable", "base_regressor", "count"}`, expressions in the ASCII syntax.
pub fn json(reg: &Regressor, base: Option<&BaseParameters>, tau_proof: &[Outcome]) -> Value {
    let ascii = |p: &Poly| poly_to_string(p, Style::Ascii);
    let mut rows = reg.y.clone();
    if let Some(b) = base {
        rows.extend(b.base_regressor(reg));
    }
    let printed = printable(&reg.arena, &rows);
    let (y, yb) = printed.entries.split_at(reg.dof());
    let (holds, how) = proof_summary(tau_proof);
    let mut doc = json!({
        "robot": reg.robot,
        "gravity": match reg.options.gravity { Gravity::Scene => "scene", Gravity::Input => "input" },
        "standard": names(reg, 0..reg.params.len()),
        "regressor": y.iter().map(|r| r.iter().map(ascii).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "intermediates": printed.intermediates.iter().map(|(s, v)| json!({"name": s.ascii_name(), "value": ascii(v)})).collect::<Vec<_>>(),
        "tau_proved": {"holds": holds, "how": how},
    });
    if let Some(b) = base {
        let m = doc.as_object_mut().expect("object");
        m.insert(
            "base".into(),
            Value::Array(
                b.base
                    .iter()
                    .map(|p| {
                        json!({
                            "name": p.name,
                            "expression": b.expression(p, &reg.params).map(|e| ascii(&e)),
                            "grouped": p.terms.iter().skip(1).map(|(k, _)| reg.params[*k].name()).collect::<Vec<_>>(),
                            "rules": p.rules,
                        })
                    })
                    .collect(),
            ),
        );
        m.insert(
            "unidentifiable".into(),
            json!(b
                .eliminated
                .iter()
                .filter(|(_, f)| matches!(f, Fate::NoEffect | Fate::Vanishes))
                .map(|(k, _)| reg.params[*k].name())
                .collect::<Vec<_>>()),
        );
        m.insert(
            "base_regressor".into(),
            json!(yb
                .iter()
                .map(|r| r.iter().map(ascii).collect::<Vec<_>>())
                .collect::<Vec<_>>()),
        );
        m.insert("count".into(), json!(b.count()));
        let (h1, how1) = proof_summary(&b.dependency_proofs);
        let (h2, how2) = proof_summary(&b.tau_proofs);
        m.insert(
            "base_proved".into(),
            json!({
                "coefficients": b.coefficients.as_ref().err(),
                "dependencies": {"holds": h1 && b.coefficients.is_ok(), "how": how1},
                "tau": {"holds": h2 && b.coefficients.is_ok(), "how": how2},
            }),
        );
    }
    doc
}

/// The non-zero entries of `Y` as a LaTeX `align*` (compact entries over their intermediates).
pub fn y_latex(reg: &Regressor) -> String {
    let printed = printable(&reg.arena, &reg.y);
    let mut lines: Vec<String> = printed
        .intermediates
        .iter()
        .map(|(s, v)| {
            format!(
                "{} &= {}",
                crate::print::to_string(
                    &crate::algebra::Expr::symbol(&s.ascii_name()),
                    Style::Latex
                ),
                poly_to_string(v, Style::Latex)
            )
        })
        .collect();
    for (i, row) in printed.entries.iter().enumerate() {
        for (k, e) in row.iter().enumerate() {
            if !e.is_zero() {
                lines.push(format!(
                    "Y_{{{},\\,{}}} &= {}",
                    i + 1,
                    latex_name(&reg.params[k].name()),
                    poly_to_string(e, Style::Latex)
                ));
            }
        }
    }
    format!(
        "\\begin{{align*}}\n{}\n\\end{{align*}}\n",
        lines.join(" \\\\\n")
    )
}
