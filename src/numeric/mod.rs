//! Numbers from the derived equations: a compiled `f64` evaluator of derived polynomials
//! ([`tape`]), the forward dynamics `q̈ = D⁻¹(u − C q̇ − g)` ([`forward`]), and exact rational
//! evaluation ([`exact`]).
//!
//! The symbolic path stays exact; `f64` appears here (and in `algebra::eval`,
//! `dynamics::numeric`) only. Nothing here does I/O.

pub mod accuracy;
pub mod exact;
pub mod fd;
pub mod forward;
pub mod program;
pub mod tape;
pub mod trace;

pub use exact::{exact_forward_dynamics, exact_values, rationals};
pub use forward::{condition_number, forward_dynamics, solve, Dynamics, COND_LIMIT};
pub use program::{compile_tau, TauProgram};
pub use tape::{compile, Evaluator, Tape};

use crate::algebra::{EvalError, Symbol};
use crate::dynamics::Robot;
use std::collections::BTreeSet;
use thiserror::Error;

/// Why a number could not be computed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum NumericError {
    /// Parameters without a value, sorted.
    #[error("no value given for {}", .0.iter().map(|s| s.ascii_name()).collect::<Vec<_>>().join(", "))]
    Missing(Vec<Symbol>),
    /// Parameters without a value, sorted, of a robot too large to expand to tell which of them
    /// cancel from `τ` (a tensor's moment about an axis its link never turns about): every parameter
    /// the recursion names, a value for each doing no harm.
    #[error("no value given for {} (some of them may cancel from τ: the robot is too large to expand \
        to tell, and a value for each does no harm)",
        .0.iter().map(|s| s.ascii_name()).collect::<Vec<_>>().join(", "))]
    MissingOrUnused(Vec<Symbol>),
    /// A state vector of the wrong length.
    #[error("{what} has {got} value{}, the robot has {expected} joint{}: give {expected}",
        plural(.got), plural(.expected))]
    WrongLength {
        /// Which vector (`q`, `qd`, `qdd`, `u`).
        what: &'static str,
        /// The number of joints.
        expected: usize,
        /// The number given.
        got: usize,
    },
    /// A coordinate that the robot does not have.
    #[error("{name} is not a coordinate of a robot with {dof} joints")]
    UnknownCoordinate {
        /// The coordinate's name.
        name: String,
        /// The number of joints.
        dof: usize,
    },
    /// `D(q)` is singular or too ill-conditioned to invert.
    #[error(
        "the mass matrix D(q) is singular or ill-conditioned (condition number {}, limit {COND_LIMIT:e}): \
         the forward dynamics has no reliable value here (a massless link or chain?)",
        fmt_cond(.cond)
    )]
    Singular {
        /// The 2-norm condition number `σ_max / σ_min` (infinite when singular).
        cond: f64,
    },
    /// `D(q)` is not positive definite (a negative mass or inertia).
    #[error("the mass matrix D(q) is not positive definite (condition number {}): check the masses and inertias", fmt_cond(.cond))]
    NotPositiveDefinite {
        /// The 2-norm condition number.
        cond: f64,
    },
    /// A value that is not a finite number.
    #[error("{what} is not a finite number ({value})")]
    NotFinite {
        /// What was computed.
        what: String,
        /// Its value.
        value: f64,
    },
    /// An exact value that is not rational.
    #[error(
        "exact evaluation needs rational results, but {what} = {value} is not rational \
             (give angles as rational multiples of pi, or drop --exact for decimals)"
    )]
    NotRational {
        /// What was computed.
        what: String,
        /// Its exact value, in ASCII syntax.
        value: String,
    },
    /// A finite-difference step that is not a positive finite number.
    #[error("the finite-difference step h = {h} is not a positive finite number")]
    InvalidStep {
        /// The step given.
        h: f64,
    },
    /// Failed evaluation of an expression.
    #[error(transparent)]
    Eval(#[from] EvalError),
}

fn plural(n: &usize) -> &'static str {
    if *n == 1 {
        ""
    } else {
        "s"
    }
}

fn fmt_cond(c: &f64) -> String {
    if c.is_finite() {
        format!("{c:.3e}")
    } else {
        "infinite".into()
    }
}

/// Every symbol of a robot's scene that is not a coordinate (DH constants, masses, centres of mass,
/// inertias, gravity, the drives' rotor inertias and friction), sorted.
pub fn robot_parameters(robot: &Robot) -> BTreeSet<Symbol> {
    robot
        .expressions()
        .into_iter()
        .flat_map(|e| e.symbols())
        .filter(|s| !s.is_coord())
        .collect()
}
