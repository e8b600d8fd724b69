//! The sheet's section "Linear in the inertial parameters": the standard parameters and their values
//! from the scene (parallel axes), the regressor's structure with `Y π = τ` proved, and the base
//! parameters with their expressions, the grouping and the proof `Y_β β = Y π`
//! ([`crate::identify`]). Added by [`with_identification`] (`symdyn sheet --identification`).

use crate::algebra::compact::identity::ProofOptions;
use crate::dynamics::Derivation;
use crate::identify::base::Fate;
use crate::identify::render::{latex_equation, latex_name, latex_term, proof_summary};
use crate::identify::{base_parameters, BaseOptions, Regressor, RegressorOptions};

/// The section, in LaTeX.
pub fn section(der: &Derivation) -> String {
    let mut out = String::from("\\section*{Linear in the inertial parameters}\n");
    out.push_str(
        "The equations of motion are linear in the standard inertial parameters of each link $j$, \
         taken about the origin $o_j$ of frame $j$ and in frame $j$: \
         $\\pi_j = (XX_j, XY_j, XZ_j, YY_j, YZ_j, ZZ_j, MX_j, MY_j, MZ_j, M_j)$, the inertia tensor \
         $J_j$ about $o_j$, the first moments and the mass. From the scene's mass $m_j$, centre of \
         mass $r_j$ and inertia $I_j$ about the centre of mass (parallel axes):\n\
         \\[ J_j = I_j + m_j \\left(r_j^{T} r_j \\, \\mathbf{1} - r_j r_j^{T}\\right), \\qquad \
         (MX_j, MY_j, MZ_j) = m_j r_j, \\qquad M_j = m_j. \\]\n",
    );
    let reg = match Regressor::build(der.robot(), RegressorOptions::default()) {
        Ok(r) => r,
        Err(e) => {
            out.push_str(&format!("(No regressor: {e}.)\n\n"));
            return out;
        }
    };
    let n = reg.dof();
    let np = reg.params.len();
    let zero: Vec<String> = (0..np)
        .filter(|&k| reg.zero_column(k))
        .map(|k| format!("${}$", latex_name(&reg.params[k].name())))
        .collect();
    let (holds, how) = proof_summary(&reg.prove_tau(&ProofOptions::default()));
    out.push_str(&format!(
        "The regressor $Y(q, \\dot q, \\ddot q)$ with $\\tau = Y \\pi$ has {n} rows and {np} columns; \
         {} of them are structurally zero{}{}. $Y \\pi = \\tau$ for the scene's $\\pi$ is {} ({}).\n\n",
        zero.len(),
        if zero.is_empty() { "" } else { ": " },
        zero.join(", "),
        if holds { "proved" } else { "\\textbf{not proved}" },
        if how == "exact" { "exact zero test".to_string() } else { how.clone() }
    ));
    let b = match base_parameters(&reg, &BaseOptions::default()) {
        Ok(b) => b,
        Err(e) => {
            out.push_str(&format!("(No base parameters: {e}.)\n\n"));
            return out;
        }
    };
    out.push_str(&format!(
        "\\subsection*{{Base parameters}}\nThe columns of $Y$ are linearly dependent: {} base \
         parameters $\\beta$ remain, each a standard parameter with others grouped into it (named as \
         Khalil does, $\\mathrm{{ZZR}}_1$ when something is grouped into $ZZ_1$), found by exact \
         elimination at random rational states, the columns taken link by link.\n",
        b.count()
    ));
    for p in &b.base {
        if p.terms.len() == 1 {
            continue;
        }
        let terms: Option<Vec<String>> = p
            .terms
            .iter()
            .map(|(k, c)| Some(latex_term(c.as_ref()?, &latex_name(&reg.params[*k].name()))))
            .collect();
        if let Some(terms) = terms {
            out.push_str(&latex_equation(&latex_name(&p.name), &terms));
        }
    }
    let alone: Vec<String> = b
        .base
        .iter()
        .filter(|p| p.terms.len() == 1)
        .map(|p| format!("${}$", latex_name(&p.name)))
        .collect();
    if !alone.is_empty() {
        out.push_str(&format!("Identifiable alone: {}.\n\n", alone.join(", ")));
    }
    let none: Vec<String> = b
        .eliminated
        .iter()
        .filter(|(_, f)| matches!(f, Fate::NoEffect | Fate::Vanishes))
        .map(|(k, _)| format!("${}$", latex_name(&reg.params[*k].name())))
        .collect();
    if !none.is_empty() {
        out.push_str(&format!("Without effect: {}.\n\n", none.join(", ")));
    }
    match &b.coefficients {
        Ok(()) => {
            let (h1, how1) = proof_summary(&b.dependency_proofs);
            let (h2, how2) = proof_summary(&b.tau_proofs);
            out.push_str(&format!(
                "Each grouped column is proved to be the stated combination of the base columns ({how1}{}), \
                 so $Y_\\beta \\beta = Y \\pi$ for every $\\pi$; $Y_\\beta \\beta = \\tau$ for the scene's \
                 parameters is {} ({how2}). Hence exactly {} base parameters.\n\n",
                if h1 { "" } else { ", \\textbf{failed}" },
                if h2 { "proved" } else { "\\textbf{not proved}" },
                b.count()
            ));
        }
        Err(why) => out.push_str(&format!("The count is not proved: {why}.\n\n")),
    }
    out
}

/// A sheet with the section added before the agreement of the formulations (or at the end).
pub fn with_identification(der: &Derivation, tex: &str) -> String {
    let section = section(der);
    let at = tex
        .find("\\section*{Both formulations agree}")
        .or_else(|| tex.rfind("\\end{document}"))
        .unwrap_or(tex.len());
    format!("{}{section}{}", &tex[..at], &tex[at..])
}
