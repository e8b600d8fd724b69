//! Deterministic work sharing for the display layer: [`map`] applies a pure function to many items
//! on a few threads and returns the results in the items' order, so the text printed from them is the
//! same on any number of threads.
//!
//! What may run here: printing polynomials ([`super::poly`]) and tidying into the house style
//! ([`crate::algebra::tidy`]). Tidying may intern new atoms, from several threads at once; atom ids
//! then differ from run to run, but they are only an internal order (see
//! [`crate::algebra::atom`]): tidying works on canonical expressions, ordered structurally, and visits
//! its candidates in that order (never by id or hash), so each result is the same expression
//! whichever thread computes it and whenever.

pub use crate::parallel::{map, set_threads, threads};
