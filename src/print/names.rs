//! Symbol names, one function per output style.
//!
//! | symbol            | [`text`]   | [`ascii`]  | [`latex`]                |
//! |-------------------|------------|------------|--------------------------|
//! | `q_1`             | `q1`       | `q1`       | `q_{1}`                  |
//! | `q̇_1`             | `q̇1`       | `qd1`      | `\dot{q}_{1}`            |
//! | `q̈_1`             | `q̈1`       | `qdd1`     | `\ddot{q}_{1}`           |
//! | 3rd derivative    | `q1_d3`    | `q1_d3`    | `\dddot{q}_{1}`          |
//! | 4th derivative    | `q1_d4`    | `q1_d4`    | `\ddddot{q}_{1}`         |
//! | k-th, `k >= 5`    | `q1_dk`    | `q1_dk`    | `{q_{1}^{(k)}}`          |
//! | parameter `lc2`   | `lc2`      | `lc2`      | `l_{c2}`                 |
//!
//! Text writes the first two derivatives with a combining dot above (U+0307) or diaeresis (U+0308)
//! after the `q`, which is what [`Symbol::coord_from_name`] reads back. Derivatives of order three and
//! more are written `q{index}_d{order}` in text and ASCII (as [`Symbol::ascii_name`] does), which
//! [`Symbol::coord_from_name`] reads back as the same derivative. The equations of motion never
//! contain them.
//!
//! LaTeX names of parameters, in this order of rules:
//! 1. A name that starts with a whole Greek letter name (lower case, capitalised, or one of the
//!    `var` forms such as `varphi`) followed by nothing, a digit or `_` prints the letter:
//!    `theta1` is `\theta_{1}`, `Theta` is `\Theta`, `beta_x` is `\beta_{x}`, `varphi2` is
//!    `\varphi_{2}`. `eta` is not found inside `theta`, and `etab` is not Greek (rule 2 applies).
//!    Capitals without a LaTeX command of their own print as upright Latin letters:
//!    `Alpha` is `\mathrm{A}`; `omicron` is `o`.
//! 2. A name whose part before its first `_` is a word of three letters or more is an identifier,
//!    such as the name of a URDF joint that names its input: it prints upright and whole, its `_`
//!    escaped: `panda_joint1` is `\mathrm{panda\_joint1}`, `shoulder_pan_joint` is
//!    `\mathrm{shoulder\_pan\_joint}` (not `p_{anda,joint1}`).
//! 3. Otherwise the first character is the base: `m2` is `m_{2}`, `lc2` is `l_{c2}`, `g` is `g`.
//! 4. The rest is the subscript, with one leading `_` dropped and any further `_` written as a comma:
//!    `I_xx1` is `I_{xx1}`, `I_xx_1` is `I_{xx,1}`.

use crate::algebra::Symbol;

/// The name in the text style: parameters as they are, `q1`, `q̇1`, `q̈1`, and `q1_d3` for order 3+.
pub fn text(s: &Symbol) -> String {
    match s {
        Symbol::Param(name) => name.to_string(),
        Symbol::Coord { index, order: 0 } => format!("q{index}"),
        Symbol::Coord { index, order: 1 } => format!("q\u{307}{index}"),
        Symbol::Coord { index, order: 2 } => format!("q\u{308}{index}"),
        Symbol::Coord { index, order } => format!("q{index}_d{order}"),
    }
}

/// The name in the ASCII style, the one the parser reads: `q1`, `qd1`, `qdd1`, `q1_d3`, parameters as
/// they are (this is [`Symbol::ascii_name`]).
pub fn ascii(s: &Symbol) -> String {
    s.ascii_name()
}

/// The name in LaTeX: `q_{1}`, `\dot{q}_{1}`, `\ddot{q}_{1}`, `m_{2}`, `l_{c2}`, `\theta_{1}`. The result
/// is a single group that can take a superscript (`l_{c2}^{2}`).
pub fn latex(s: &Symbol) -> String {
    match s {
        Symbol::Param(name) => latex_param(name),
        Symbol::Coord { index, order: 0 } => format!("q_{{{index}}}"),
        Symbol::Coord { index, order: 1 } => format!("\\dot{{q}}_{{{index}}}"),
        Symbol::Coord { index, order: 2 } => format!("\\ddot{{q}}_{{{index}}}"),
        Symbol::Coord { index, order: 3 } => format!("\\dddot{{q}}_{{{index}}}"),
        Symbol::Coord { index, order: 4 } => format!("\\ddddot{{q}}_{{{index}}}"),
        Symbol::Coord { index, order } => format!("{{q_{{{index}}}^{{({order})}}}}"),
    }
}

/// Greek letter names and their LaTeX. Longer names come before their prefixes where it matters
/// (`epsilon` is matched as a whole word anyway, so order only needs to be deterministic).
const GREEK: &[(&str, &str)] = &[
    ("alpha", "\\alpha"),
    ("beta", "\\beta"),
    ("gamma", "\\gamma"),
    ("delta", "\\delta"),
    ("epsilon", "\\epsilon"),
    ("varepsilon", "\\varepsilon"),
    ("zeta", "\\zeta"),
    ("eta", "\\eta"),
    ("theta", "\\theta"),
    ("vartheta", "\\vartheta"),
    ("iota", "\\iota"),
    ("kappa", "\\kappa"),
    ("lambda", "\\lambda"),
    ("mu", "\\mu"),
    ("nu", "\\nu"),
    ("xi", "\\xi"),
    ("omicron", "o"),
    ("pi", "\\pi"),
    ("varpi", "\\varpi"),
    ("rho", "\\rho"),
    ("varrho", "\\varrho"),
    ("sigma", "\\sigma"),
    ("varsigma", "\\varsigma"),
    ("tau", "\\tau"),
    ("upsilon", "\\upsilon"),
    ("phi", "\\phi"),
    ("varphi", "\\varphi"),
    ("chi", "\\chi"),
    ("psi", "\\psi"),
    ("omega", "\\omega"),
    ("Alpha", "\\mathrm{A}"),
    ("Beta", "\\mathrm{B}"),
    ("Gamma", "\\Gamma"),
    ("Delta", "\\Delta"),
    ("Epsilon", "\\mathrm{E}"),
    ("Zeta", "\\mathrm{Z}"),
    ("Eta", "\\mathrm{H}"),
    ("Theta", "\\Theta"),
    ("Iota", "\\mathrm{I}"),
    ("Kappa", "\\mathrm{K}"),
    ("Lambda", "\\Lambda"),
    ("Mu", "\\mathrm{M}"),
    ("Nu", "\\mathrm{N}"),
    ("Xi", "\\Xi"),
    ("Omicron", "\\mathrm{O}"),
    ("Pi", "\\Pi"),
    ("Rho", "\\mathrm{P}"),
    ("Sigma", "\\Sigma"),
    ("Tau", "\\mathrm{T}"),
    ("Upsilon", "\\Upsilon"),
    ("Phi", "\\Phi"),
    ("Chi", "\\mathrm{X}"),
    ("Psi", "\\Psi"),
    ("Omega", "\\Omega"),
];

/// Splits a parameter name into its LaTeX base and the raw subscript text (rules 1 and 2).
fn split_base(name: &str) -> (String, &str) {
    for (word, tex) in GREEK {
        if let Some(rest) = name.strip_prefix(word) {
            if rest.is_empty() || rest.starts_with(|c: char| c.is_ascii_digit() || c == '_') {
                return ((*tex).to_string(), rest);
            }
        }
    }
    let mut chars = name.chars();
    match chars.next() {
        Some(first) => (first.to_string(), chars.as_str()),
        None => (String::new(), ""),
    }
}

/// Whether a name is an identifier (rule 2): a word of three ASCII letters or more, then `_`.
fn is_identifier(name: &str) -> bool {
    name.split_once('_')
        .is_some_and(|(word, _)| word.len() >= 3 && word.bytes().all(|b| b.is_ascii_alphabetic()))
}

/// A parameter's LaTeX name: an identifier upright (rule 2), else base, then `_{subscript}` when
/// there is one (rules 1, 3 and 4).
fn latex_param(name: &str) -> String {
    let (base, rest) = split_base(name);
    if base.len() == 1 && is_identifier(name) {
        return format!("\\mathrm{{{}}}", name.replace('_', "\\_"));
    }
    let sub = rest.strip_prefix('_').unwrap_or(rest).replace('_', ",");
    if sub.is_empty() {
        base
    } else {
        format!("{base}_{{{sub}}}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latex_parameter_names() {
        let rows = [
            ("m2", "m_{2}"),
            ("lc2", "l_{c2}"),
            ("I_xx1", "I_{xx1}"),
            ("I_xx_1", "I_{xx,1}"),
            ("g", "g"),
            ("rx1", "r_{x1}"),
            ("theta1", "\\theta_{1}"),
            ("theta", "\\theta"),
            ("eta2", "\\eta_{2}"),
            ("etab", "e_{tab}"),
            ("Theta", "\\Theta"),
            ("beta_x", "\\beta_{x}"),
            ("varphi", "\\varphi"),
            ("Alpha1", "\\mathrm{A}_{1}"),
            // Identifiers: URDF joint names, whole and upright; Greek and short words are not.
            ("panda_joint1", "\\mathrm{panda\\_joint1}"),
            ("shoulder_pan_joint", "\\mathrm{shoulder\\_pan\\_joint}"),
            ("wrist_3_joint", "\\mathrm{wrist\\_3\\_joint}"),
            ("theta_joint", "\\theta_{joint}"),
            ("lc_2", "l_{c,2}"),
            ("ee_link", "e_{e,link}"),
            ("abc1_x", "a_{bc1,x}"),
        ];
        for (name, want) in rows {
            assert_eq!(latex(&Symbol::new(name)), want, "{name}");
        }
    }
}
