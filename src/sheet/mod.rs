//! Solution sheets: a derivation as a complete LaTeX document that reads like a worked solution of
//! Spong, Hutchinson and Vidyasagar, ch. 7 (the scene, Euler–Lagrange, Newton–Euler in body-fixed and
//! inertial frames, and the proof that the formulations agree). Pure: returns the text, does no I/O.
//!
//! - [`layout`] (shared with `symdyn derive --format latex`, in [`crate::print`]): long expressions
//!   kept on the page;
//! - `scene`: the DH table, masses, centres of mass, gravity, inputs, transforms, inertia;
//! - `lagrange`: `J_v,i`, `J_ω,i`, `D(q)`, Christoffel symbols, `P`, `g(q)`, the equations;
//! - `newton_euler`: the forward and backward recursions per frame and the equations.
//!
//! The document uses only `amsmath`, `amssymb`, `geometry` and `booktabs` (TeX Live's
//! `texlive-latex-base` and `texlive-latex-recommended`).

mod lagrange;
pub use crate::print::layout;
mod newton_euler;
mod scene;

use crate::algebra::{Expr, Symbol};
use crate::dynamics::check::check;
use crate::dynamics::{Derivation, Frame};
use crate::print::{self, Style};
use layout::Layout;

/// Which formulations a sheet derives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Methods {
    /// Euler–Lagrange only.
    Lagrange,
    /// Newton–Euler only.
    NewtonEuler,
    /// Both (the default).
    #[default]
    Both,
}

/// The frames of the Newton–Euler recursion.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Frames {
    /// Body-fixed frames only.
    Body,
    /// The inertial frame only.
    Inertial,
    /// Both (the default).
    #[default]
    Both,
}

/// How much of the derivation a sheet shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Scope {
    /// Everything (the default).
    #[default]
    Full,
    /// The scene, then Euler–Lagrange `D(q)` and `g(q)` only: no Jacobians, Christoffel symbols,
    /// equations, Newton–Euler or proofs. For arms whose full sheet is too long to typeset quickly
    /// (the fully symbolic PUMA 560).
    MassAndGravity,
}

/// What a sheet contains.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct SheetOptions {
    /// The formulations.
    pub methods: Methods,
    /// The Newton–Euler frames.
    pub frames: Frames,
    /// How much to show.
    pub scope: Scope,
}

impl SheetOptions {
    fn lagrange(&self) -> bool {
        self.methods != Methods::NewtonEuler || self.scope == Scope::MassAndGravity
    }

    fn frames(&self) -> Vec<Frame> {
        if self.methods == Methods::Lagrange || self.scope == Scope::MassAndGravity {
            return vec![];
        }
        match self.frames {
            Frames::Body => vec![Frame::Body],
            Frames::Inertial => vec![Frame::Inertial],
            Frames::Both => vec![Frame::Body, Frame::Inertial],
        }
    }
}

/// The complete LaTeX document of the solution sheet of `der`.
pub fn sheet(der: &Derivation, opts: &SheetOptions) -> String {
    let mut lay = Layout::new();
    let mut out = String::from(PREAMBLE);
    out.push_str(&format!(
        "\\begin{{center}}\n{{\\Large\\bfseries Equations of motion: {}}}\n\\end{{center}}\n\n",
        text(&der.robot().name)
    ));
    out.push_str(&scene::section(der, &mut lay));
    if opts.lagrange() {
        out.push_str(&lagrange::section(der, &mut lay, opts.scope));
    }
    for frame in opts.frames() {
        out.push_str(&newton_euler::section(der, frame, &mut lay));
    }
    match opts.scope {
        Scope::Full => out.push_str(&agreement(der)),
        Scope::MassAndGravity => out.push_str(
            "This sheet shows $D(q)$ and $g(q)$ only; \\texttt{symdyn check} proves that the \
             Euler--Lagrange and Newton--Euler formulations agree.\n\n",
        ),
    }
    out.push_str("\\end{document}\n");
    out
}

const PREAMBLE: &str = "\\documentclass[10pt]{article}
\\usepackage[a4paper,margin=2cm]{geometry}
\\usepackage{amsmath,amssymb}
\\usepackage{booktabs}
\\allowdisplaybreaks
\\setlength{\\parindent}{0pt}
\\setlength{\\parskip}{0.5ex}
\\begin{document}
";

/// The last section: both formulations agree, each claim decided by the exact zero test.
fn agreement(der: &Derivation) -> String {
    let claims = check(der);
    let mut out = String::from("\\section*{Both formulations agree}\n");
    out.push_str(
        "Each claim below is decided by the exact zero test of the polynomial normal form \
         (the difference of the two sides reduces to zero), not by sampling.\n\\begin{itemize}\n",
    );
    for c in &claims {
        if c.holds {
            out.push_str(&format!("\\item Proved: {}.\n", claim_text(&c.statement)));
        } else {
            let fails: Vec<String> = c.failures.iter().map(|f| text(f)).collect();
            out.push_str(&format!(
                "\\item \\textbf{{Failed}}: {} (not zero: {}).\n",
                claim_text(&c.statement),
                fails.join(", ")
            ));
        }
    }
    out.push_str("\\end{itemize}\n");
    if claims.iter().all(|c| c.holds) {
        out.push_str(
            "Hence the Euler--Lagrange and Newton--Euler formulations give the same equations of \
             motion.\n\n",
        );
    } else {
        out.push_str("\\textbf{The formulations do not agree on the claims marked failed.}\n\n");
    }
    out
}

/// A claim of `check` as LaTeX text, its formulas in math mode.
fn claim_text(s: &str) -> String {
    text(s)
        .replace("$\\dot{D}$ $-$ 2C", "$\\dot{D} - 2C$")
        .replace("D(q)", "$D(q)$")
}

/// Plain text (a robot's name, a claim) as LaTeX text: special characters escaped, the few Unicode
/// characters symdyn writes spelled in LaTeX, any other non-ASCII character left to `inputenc`.
pub(crate) fn text(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        match c {
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                out.push('\\');
                out.push(c);
            }
            '~' => out.push_str("\\textasciitilde{}"),
            '^' => out.push_str("\\textasciicircum{}"),
            '\\' => out.push_str("\\textbackslash{}"),
            '–' => out.push_str("--"),
            '—' => out.push_str("---"),
            '−' => out.push_str("$-$"),
            '≠' => out.push_str("$\\neq$"),
            'Ḋ' => out.push_str("$\\dot{D}$"),
            'ω' => out.push_str("$\\omega$"),
            _ => out.push(c),
        }
    }
    out
}

/// A symbol's LaTeX.
pub(crate) fn sym(name: &str) -> String {
    print::to_string(&Expr::sym(Symbol::new(name)), Style::Latex)
}

/// An expression's LaTeX, inline.
pub(crate) fn math(e: &Expr) -> String {
    print::to_string(e, Style::Latex)
}
