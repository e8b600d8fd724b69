//! The algebra core: exact canonical expressions and the operations on them.
//!
//! Nothing here knows of robots. The only time-dependent symbols are the generalised coordinates
//! `q_i` and their derivatives, which the total time derivative needs.
//!
//! - [`expr`]: the canonical [`Expr`] and its constructors; [`number`], [`symbol`]: its leaves.
//! - [`poly`], [`atom`], [`normal`]: the polynomial normal form and the zero test.
//! - [`calculus`]: `∂/∂x` and `d/dt`; [`mod@subs`], [`eval`]: substitution and numbers.
//! - [`compact`]: named, hash-consed intermediates, their derivatives, values and identity proofs.
//! - [`random`]: the deterministic generator of random points.

pub mod atom;
pub mod calculus;
pub mod chebyshev;
pub mod compact;
pub mod error;
pub mod eval;
pub mod expand;
pub mod expr;
pub(crate) mod fast_hash;
pub mod limits;
pub mod normal;
pub mod number;
pub mod pi_field;
pub mod poly;
pub mod random;
pub mod simplify;
pub mod subs;
pub mod symbol;
pub mod tidy;
pub(crate) mod trig_values;

pub use calculus::{diff, dt};
pub use error::AlgebraError;
pub use eval::{eval_exact, eval_f64, EvalError};
pub use expand::expand;
pub use expr::{Expr, Func, Kind};
pub use normal::{equal, is_zero, normal_form, to_poly};
pub use number::Rational;
pub use poly::Poly;
pub use simplify::simplify;
pub use subs::subs;
pub use symbol::Symbol;
