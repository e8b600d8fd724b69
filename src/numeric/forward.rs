//! The forward dynamics `q̈ = D(q)⁻¹ (u − C(q, q̇) q̇ − g(q))` (Spong et al., eq. 7.61 solved for q̈).
//!
//! `C q̇ + g` is the inverse dynamics at `q̈ = 0`, so one compiled tape gives both `D(q)` and it.
//! Before solving, the 2-norm condition number `κ(D) = σ_max / σ_min` is computed from the singular
//! values of `D` (nalgebra's SVD); above [`COND_LIMIT`] (or for a singular `D`, e.g. a massless chain)
//! the answer is refused with [`NumericError::Singular`]. The system is then solved by Cholesky
//! (`D` is symmetric positive definite for physical masses; a failed factorisation is reported as
//! [`NumericError::NotPositiveDefinite`]).

use super::tape::{compile, Evaluator};
use super::NumericError;
use crate::algebra::{Poly, Symbol};
use crate::dynamics::lagrange::Lagrange;
use nalgebra::{DMatrix, DVector};
use std::collections::HashMap;

/// The largest condition number of `D(q)` for which the forward dynamics is returned.
pub const COND_LIMIT: f64 = 1e12;

/// `κ(D) = σ_max / σ_min`, infinite when `D` is singular (or zero, or not finite).
pub fn condition_number(d: &DMatrix<f64>) -> f64 {
    if d.is_empty() || d.iter().any(|x| !x.is_finite()) {
        return f64::INFINITY;
    }
    let sv = d.clone().singular_values();
    let (max, min) = (sv.max(), sv.min());
    if max > 0.0 && min > 0.0 {
        max / min
    } else {
        f64::INFINITY
    }
}

/// Solves `D q̈ = rhs` after checking the condition number; returns `q̈` and `κ(D)`.
pub fn forward_dynamics(
    d: &DMatrix<f64>,
    rhs: &DVector<f64>,
) -> Result<(DVector<f64>, f64), NumericError> {
    let cond = condition_number(d);
    if cond.is_nan() || cond > COND_LIMIT {
        return Err(NumericError::Singular { cond });
    }
    let chol = d
        .clone()
        .cholesky()
        .ok_or(NumericError::NotPositiveDefinite { cond })?;
    Ok((chol.solve(rhs), cond))
}

/// A robot's compiled `D(q)` and `C(q, q̇) q̇ + g(q)`, with its parameters bound.
#[derive(Clone, Debug)]
pub struct Dynamics {
    n: usize,
    eval: Evaluator,
    zeros: Vec<f64>,
}

impl Dynamics {
    /// Compiles `D` and `τ` of the Euler–Lagrange derivation and binds the parameters (failing with
    /// every missing one listed).
    pub fn new(
        lagrange: &Lagrange,
        params: &HashMap<Symbol, f64>,
    ) -> Result<Dynamics, NumericError> {
        let n = lagrange.tau.len();
        let polys: Vec<Poly> = lagrange
            .d
            .iter()
            .flatten()
            .chain(lagrange.tau.iter())
            .cloned()
            .collect();
        let eval = compile(&polys, n)?.bind(params)?;
        Ok(Dynamics {
            n,
            eval,
            zeros: vec![0.0; n],
        })
    }

    /// `D(q)` and `h = C(q, q̇) q̇ + g(q)`.
    pub fn mass_and_bias(
        &mut self,
        q: &[f64],
        qd: &[f64],
    ) -> Result<(DMatrix<f64>, DVector<f64>), NumericError> {
        let n = self.n;
        let out = self.eval.eval(q, qd, &self.zeros)?;
        let d = DMatrix::from_row_slice(n, n, &out[..n * n]);
        let h = DVector::from_column_slice(&out[n * n..]);
        Ok((d, h))
    }

    /// `q̈ = D⁻¹ (u − C q̇ − g)` and the condition number of `D(q)`.
    pub fn qdd(
        &mut self,
        q: &[f64],
        qd: &[f64],
        u: &[f64],
    ) -> Result<(Vec<f64>, f64), NumericError> {
        if u.len() != self.n {
            return Err(NumericError::WrongLength {
                what: "u",
                expected: self.n,
                got: u.len(),
            });
        }
        let (d, h) = self.mass_and_bias(q, qd)?;
        solve(&d, &h, u)
    }
}

/// `q̈ = D⁻¹ (u − h)` and `κ(D)` from `D(q)` and `h = C q̇ + g` however computed, refusing a
/// non-finite `u − h` by name ([`forward_dynamics`] checks `D`).
pub fn solve(
    d: &DMatrix<f64>,
    h: &DVector<f64>,
    u: &[f64],
) -> Result<(Vec<f64>, f64), NumericError> {
    let rhs = DVector::from_column_slice(u) - h;
    if let Some((i, x)) = rhs.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(NumericError::NotFinite {
            what: format!("u{} − (C q̇ + g){}", i + 1, i + 1),
            value: *x,
        });
    }
    let (qdd, cond) = forward_dynamics(d, &rhs)?;
    Ok((qdd.iter().copied().collect(), cond))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_singular_and_solves_regular() {
        let d = DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 0.0]);
        let rhs = DVector::from_column_slice(&[1.0, 1.0]);
        let err = forward_dynamics(&d, &rhs).unwrap_err();
        assert_eq!(
            err,
            NumericError::Singular {
                cond: f64::INFINITY
            }
        );
        let d = DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 4.0]);
        let (x, cond) = forward_dynamics(&d, &rhs).unwrap();
        assert!((x[0] - 0.5).abs() < 1e-15 && (x[1] - 0.25).abs() < 1e-15);
        assert!((cond - 2.0).abs() < 1e-14);
        let d = DMatrix::from_row_slice(2, 2, &[-2.0, 0.0, 0.0, -4.0]);
        assert!(matches!(
            forward_dynamics(&d, &rhs),
            Err(NumericError::NotPositiveDefinite { .. })
        ));
    }
}
