//! A numeric Euler–Lagrange: `τ_i = d/dt ∂L/∂q̇_i − ∂L/∂q_i` by central finite differences of the
//! Lagrangian `L = K − P`, the energies compiled to one tape ([`super::compile`]).
//!
//! With step `h` (absolute: coordinates in radians or metres, rates per second):
//! - `∂L/∂q_i ≈ [L(q + h e_i, q̇) − L(q − h e_i, q̇)] / 2h`;
//! - `p_i(q, q̇) = ∂L/∂q̇_i ≈ [L(q, q̇ + h e_i) − L(q, q̇ − h e_i)] / 2h` (exact up to round-off,
//!   since `L` is quadratic in `q̇`);
//! - `d/dt p_i ≈ [p_i(q(h), q̇(h)) − p_i(q(−h), q̇(−h))] / 2h` along the trajectory through the state
//!   with constant acceleration, `q(s) = q + s q̇ + s²/2 q̈`, `q̇(s) = q̇ + s q̈`.
//!
//! Both differences have truncation error `O(h²)`. Round-off is `O(u |L| / h)` for `∂L/∂q` and
//! `O(u |L| / h²)` for the nested difference (`u = 2⁻⁵³`), so the total error is smallest near
//! `h ≈ u^{1/4} ≈ 10⁻⁴` and grows on both sides: the textbook failure of finite differences that the
//! accuracy chart and `tests/failure_modes.rs` show. One `τ` costs `6n` evaluations of `L`.

use super::tape::{compile, Evaluator};
use super::NumericError;
use crate::algebra::{Poly, Symbol};
use std::collections::HashMap;

/// The Lagrangian `L = K − P` compiled and bound, differentiated numerically.
#[derive(Clone, Debug)]
pub struct FdLagrangian {
    n: usize,
    eval: Evaluator,
    zeros: Vec<f64>,
    scratch: [Vec<f64>; 2],
}

impl FdLagrangian {
    /// Compiles `K(q, q̇)` and `P(q)` of a robot with `n` joints and binds the parameters (failing with
    /// every missing one listed).
    pub fn new(
        k: &Poly,
        p: &Poly,
        n: usize,
        params: &HashMap<Symbol, f64>,
    ) -> Result<FdLagrangian, NumericError> {
        let eval = compile(&[k.clone(), p.clone()], n)?.bind(params)?;
        Ok(FdLagrangian {
            n,
            eval,
            zeros: vec![0.0; n],
            scratch: [vec![0.0; n], vec![0.0; n]],
        })
    }

    /// `L(q, q̇) = K − P`.
    pub fn lagrangian(&mut self, q: &[f64], qd: &[f64]) -> Result<f64, NumericError> {
        let out = self.eval.eval(q, qd, &self.zeros)?;
        Ok(out[0] - out[1])
    }

    /// `∂L/∂q̇_i` at `(q, q̇)` by a central difference with step `h`.
    fn momentum(&mut self, q: &[f64], qd: &[f64], i: usize, h: f64) -> Result<f64, NumericError> {
        let mut v = std::mem::take(&mut self.scratch[1]);
        v.copy_from_slice(qd);
        v[i] = qd[i] + h;
        let plus = self.lagrangian(q, &v);
        v[i] = qd[i] - h;
        let minus = self.lagrangian(q, &v);
        self.scratch[1] = v;
        Ok((plus? - minus?) / (2.0 * h))
    }

    /// `τ(q, q̇, q̈)` by central differences with step `h` (finite and positive).
    pub fn tau(
        &mut self,
        q: &[f64],
        qd: &[f64],
        qdd: &[f64],
        h: f64,
    ) -> Result<Vec<f64>, NumericError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(NumericError::InvalidStep { h });
        }
        let n = self.n;
        for (what, xs) in [("q", q), ("qd", qd), ("qdd", qdd)] {
            if xs.len() != n {
                return Err(NumericError::WrongLength {
                    what,
                    expected: n,
                    got: xs.len(),
                });
            }
        }
        let at = |s: f64| -> (Vec<f64>, Vec<f64>) {
            let q: Vec<f64> = (0..n)
                .map(|j| q[j] + s * qd[j] + 0.5 * s * s * qdd[j])
                .collect();
            let v: Vec<f64> = (0..n).map(|j| qd[j] + s * qdd[j]).collect();
            (q, v)
        };
        let ((qp, vp), (qm, vm)) = (at(h), at(-h));
        let mut tau = Vec::with_capacity(n);
        let mut shifted = std::mem::take(&mut self.scratch[0]);
        for i in 0..n {
            let dt = (self.momentum(&qp, &vp, i, h)? - self.momentum(&qm, &vm, i, h)?) / (2.0 * h);
            shifted.copy_from_slice(q);
            shifted[i] = q[i] + h;
            let plus = self.lagrangian(&shifted, qd)?;
            shifted[i] = q[i] - h;
            let minus = self.lagrangian(&shifted, qd)?;
            tau.push(dt - (plus - minus) / (2.0 * h));
        }
        self.scratch[0] = shifted;
        Ok(tau)
    }
}
