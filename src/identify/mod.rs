//! Identification: the regressor `Y` with `τ = Y π`, the base inertial parameters `β` (exact, with
//! their expressions in the geometry and Khalil's names) and the proofs `Y π = τ`, `Y_β β = Y π`.
//!
//! | concept | file |
//! |---|---|
//! | the standard parameters, their order and scene values | [`standard`] |
//! | the regressor in compact form, `Y π = τ` | [`regressor`] |
//! | exact Gauss–Jordan over ℚ | [`linalg`] |
//! | the base parameters, their grouping and proofs | [`base`] |
//! | the grouping coefficients from the joint axes (symbolic twists) | `grouping` |
//! | the regressor and base parameters as text and JSON | [`render`] |
//! | the f64 rank check and least-squares fit | [`fit`] |
//! | which special values of the geometry decide the count | [`special`] |
//!
//! The library does no I/O: the `symdyn regressor` and `symdyn identify` commands print what these
//! return.

pub mod base;
pub mod error;
pub mod fit;
mod grouping;
pub mod linalg;
pub mod regressor;
pub mod render;
pub mod special;
pub mod standard;

pub use base::{base_parameters, BaseOptions, BaseParam, BaseParameters, Fate};
pub use error::IdentifyError;
pub use regressor::{Gravity, Regressor, RegressorOptions};
pub use standard::{standard_params, Quantity, StandardParam};
