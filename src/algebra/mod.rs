//! The algebra core: exact canonical expressions and the operations on them.
//!
//! Nothing here knows of robots. The only time-dependent symbols are the generalised coordinates
//! `q_i` and their derivatives, which the total time derivative needs.

pub mod error;
pub mod expr;
pub mod number;
pub mod symbol;
pub(crate) mod trig_values;

pub use error::AlgebraError;
pub use expr::{Expr, Func, Kind};
pub use number::Rational;
pub use symbol::Symbol;
