//! symdyn: exact symbolic equations of motion for serial robot manipulators.
//!
//! Layers, bottom up: [`algebra`] (canonical expressions, the normal form and the zero test),
//! [`parse`] (the pest grammars for expressions and scenes), [`print`](mod@print) (text, ASCII and LaTeX),
//! [`dynamics`] (robots, Euler–Lagrange, Newton–Euler, proofs), [`report`] (derivations as text) and
//! [`repl`] (the interactive session, line in, answer out). The library does no I/O; the `symdyn`
//! binary is a thin shell over it.

// Matrix code follows the book's index notation (d_kj, c_ijk): index loops read closer to it.
#![allow(clippy::needless_range_loop)]

pub mod algebra;
pub mod allocator;
pub mod bench;
pub mod chains;
pub mod codegen;
pub mod dynamics;
pub mod identify;
pub mod numeric;
pub mod parallel;
pub mod parse;
pub mod print;
pub mod repl;
pub mod report;
pub mod sheet;
pub mod simulate;
#[cfg(test)]
mod test_support;
