//! Generated code: `τ`, `D(q)`, `h(q, q̇)`, `g(q)`, `C(q, q̇)` and the forward dynamics `q̈` as C, Rust
//! and Python functions with one fixed calling convention per language.
//!
//! The pipeline, every step exact until the last:
//! 1. [`build`]: the scene with the `--set` values folded in exactly (so zeros and ones of the
//!    geometry vanish), then every requested quantity into one compact arena
//!    ([`crate::algebra::compact`]): `τ` by the customised Newton–Euler, `h` and `g` by the same
//!    recursion with the accelerations (and velocities) zero, `D` by composite rigid bodies, `C` from
//!    the Christoffel symbols of that `D`. Never the expanded canonical form.
//! 2. [`lower`]: the arena's needed definitions and the outputs into one `f64` operation graph (the
//!    `numeric::trace` graph: constants folded, equal operations recorded once, so common
//!    subexpressions are shared across all the outputs asked for), each polynomial in greedy
//!    multivariate Horner form (the atom in most terms factored out first); `sin`/`cos` of each joint
//!    angle once; the forward dynamics solved in the graph by an unrolled `L diag(d) Lᵀ` factorisation.
//! 3. [`emit`]: one function per quantity over the nodes it needs, in C99, Rust or Python, its cost
//!    (multiplications, additions, `sin`/`cos` calls, divisions, square roots) counted on the code as
//!    emitted and written in its header comment, and a JSON manifest.

pub mod build;
pub mod emit;
pub mod eval;
pub mod lower;

use crate::algebra::{Expr, Symbol};
use crate::dynamics::model::{ModelError, Robot};
use std::collections::BTreeMap;
use thiserror::Error;

/// The target language.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// C99: one header and one source file.
    C,
    /// Rust: one module file.
    Rust,
    /// Python: one module using `math` only.
    Python,
}

impl Lang {
    /// `c`, `rust` or `python`.
    pub fn name(self) -> &'static str {
        match self {
            Lang::C => "c",
            Lang::Rust => "rust",
            Lang::Python => "python",
        }
    }
}

/// A quantity to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum What {
    /// `τ(q, q̇, q̈)`, the inverse dynamics.
    Tau,
    /// `D(q)`, the whole symmetric inertia matrix, row-major.
    M,
    /// `h(q, q̇) = C(q, q̇) q̇ + g(q)`.
    H,
    /// `g(q)`.
    G,
    /// `C(q, q̇)`, the Coriolis matrix of the book (from the Christoffel symbols), row-major.
    C,
    /// `q̈ = D(q)⁻¹ (u − h(q, q̇))`, the forward dynamics.
    Qdd,
    /// `Y_β(q, q̇, q̈)`, the base regressor (`τ = Y_β β`, [`crate::identify`]), row-major `N × NB`.
    Y,
}

impl What {
    /// The dynamics' quantities, in the order functions are emitted (the base regressor [`What::Y`]
    /// comes after them).
    pub const ALL: [What; 6] = [What::Tau, What::M, What::H, What::G, What::C, What::Qdd];

    /// The name on the command line and in the manifest: `tau`, `M`, `h`, `g`, `C`, `qdd`.
    pub fn name(self) -> &'static str {
        match self {
            What::Tau => "tau",
            What::M => "M",
            What::H => "h",
            What::G => "g",
            What::C => "C",
            What::Qdd => "qdd",
            What::Y => "Y",
        }
    }

    /// The quantity of a name.
    pub fn parse(s: &str) -> Option<What> {
        What::ALL
            .into_iter()
            .chain([What::Y])
            .find(|w| w.name() == s)
    }

    /// A sentence saying what the function computes.
    pub fn describe(self) -> &'static str {
        match self {
            What::Tau => "the inverse dynamics tau(q, qd, qdd) = D(q) qdd + C(q, qd) qd + g(q), by Newton-Euler",
            What::M => "the inertia matrix D(q), row-major, by composite rigid bodies",
            What::H => "h(q, qd) = C(q, qd) qd + g(q), by Newton-Euler with qdd = 0",
            What::G => "the gravity vector g(q), by Newton-Euler with qd = qdd = 0",
            What::C => "the Coriolis matrix C(q, qd) of the Christoffel symbols (Spong et al. 7.4; Ddot - 2C is skew), row-major",
            What::Qdd => "the forward dynamics qdd = D(q)^-1 (u - h(q, qd)), by an unrolled L diag(d) L^T factorisation of D(q)",
            What::Y => "the base regressor Y(q, qd, qdd), row-major N x NB, tau = Y beta for the base parameters beta listed above (proved by symdyn regressor --base)",
        }
    }
}

/// What to generate.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The language.
    pub lang: Lang,
    /// The quantities (duplicates ignored).
    pub what: Vec<What>,
    /// The prefix of every name (`puma560_tau`); an identifier.
    pub prefix: String,
    /// Parameter values folded in exactly.
    pub set: BTreeMap<Symbol, Expr>,
}

/// One generated function's manifest entry.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FunctionInfo {
    /// The function's name in the generated code.
    pub name: String,
    /// The quantity.
    pub what: What,
    /// Its input arrays, in order (`p`, `q`, `qd`, `qdd`, `u`).
    pub inputs: Vec<&'static str>,
    /// Its output array's length.
    pub outputs: usize,
    /// Operations as emitted.
    pub cost: Cost,
}

/// The operations of generated code, counted on it as emitted.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Cost {
    /// Multiplications.
    pub mults: usize,
    /// Additions and subtractions.
    pub adds: usize,
    /// `sin` and `cos` calls.
    pub trig: usize,
    /// Divisions.
    pub divs: usize,
    /// Negations.
    pub negs: usize,
}

/// Generated files and their description.
#[derive(Clone, Debug, PartialEq)]
pub struct Generated {
    /// The prefix.
    pub prefix: String,
    /// Joints.
    pub n: usize,
    /// The parameters of `p`, in order.
    pub parameters: Vec<String>,
    /// The functions.
    pub functions: Vec<FunctionInfo>,
    /// The base parameters of `Y`, `(name, expression in the standard parameters)`, when asked for.
    pub base_parameters: Vec<(String, String)>,
    /// File names and contents.
    pub files: Vec<(String, String)>,
}

/// Why code could not be generated.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum CodegenError {
    /// A `--set` of a symbol the scene does not have.
    #[error("--set {name}: the scene has no parameter {name} (its parameters: {known})")]
    UnknownParameter {
        /// The name given.
        name: String,
        /// The scene's parameters.
        known: String,
    },
    /// A `--set` value that is not a constant.
    #[error("--set {name}: the value must be a constant, not {value}")]
    NotConstant {
        /// The parameter.
        name: String,
        /// The value given.
        value: String,
    },
    /// The prefix is not an identifier.
    #[error(
        "the prefix `{0}` is not an identifier (letters, digits and _, not starting with a digit)"
    )]
    BadPrefix(String),
    /// No quantity asked for.
    #[error("nothing to generate: give at least one of tau, M, h, g, C, qdd, Y")]
    Nothing,
    /// The base regressor could not be built (see `symdyn regressor --base`).
    #[error("Y: {0}")]
    Regressor(String),
    /// The scene with the values folded in is not a valid robot.
    #[error(transparent)]
    Model(#[from] ModelError),
}

/// A robot's name made an identifier: `PUMA 560 (symbolic)` → `puma_560_symbolic`.
pub fn identifier(name: &str) -> String {
    let mut out = String::new();
    for c in name.chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') && !out.is_empty() {
            out.push('_');
        }
    }
    let out = out.trim_end_matches('_').to_string();
    match out.chars().next() {
        None => "robot".to_string(),
        Some(c) if c.is_ascii_digit() => format!("r_{out}"),
        _ => out,
    }
}

/// Whether `s` is an identifier in all three languages (and not a keyword of any).
pub fn is_identifier(s: &str) -> bool {
    const KEYWORDS: &[&str] = &[
        "if", "else", "for", "while", "return", "def", "fn", "let", "mut", "struct", "int",
        "double", "const", "void", "static", "pub", "use", "mod", "match", "in", "is", "not",
        "and", "or", "lambda", "class", "import", "from", "as", "type", "self", "super", "crate",
    ];
    let mut c = s.chars();
    matches!(c.next(), Some(f) if f.is_ascii_alphabetic() || f == '_')
        && c.all(|ch| ch.is_ascii_alphanumeric() || ch == '_')
        && !KEYWORDS.contains(&s)
}

/// Generates the code of `robot` (validated or not) as asked.
pub fn generate(robot: &Robot, opts: &Options) -> Result<Generated, CodegenError> {
    if !is_identifier(&opts.prefix) {
        return Err(CodegenError::BadPrefix(opts.prefix.clone()));
    }
    let mut what: Vec<What> = opts.what.clone();
    what.sort();
    what.dedup();
    if what.is_empty() {
        return Err(CodegenError::Nothing);
    }
    let built = build::build(robot, &opts.set, &what)?;
    let lowered = lower::lower(&built);
    Ok(emit::emit(&built, &lowered, opts.lang, &opts.prefix))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_identifiers() {
        assert_eq!(identifier("PUMA 560 (symbolic)"), "puma_560_symbolic");
        assert_eq!(identifier("3R arm"), "r_3r_arm");
        assert_eq!(identifier("--"), "robot");
        assert!(is_identifier("puma560") && !is_identifier("1x") && !is_identifier("def"));
    }
}
