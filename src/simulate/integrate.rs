//! The integrators: explicit Euler and classical Runge–Kutta (RK4) at a fixed step, and the adaptive
//! embedded Runge–Kutta of Dormand and Prince, 5(4) (Hairer, Nørsett and Wanner, *Solving Ordinary
//! Differential Equations I*, §II.5, table 5.2), on the first-order system `y = (q, q̇)`,
//! `ẏ = (q̇, q̈(t, q, q̇))`.

use super::system::System;
use super::SimError;

/// `ẏ` at `(t, y)`.
fn f(sys: &mut System, t: f64, y: &[f64]) -> Result<Vec<f64>, SimError> {
    let n = sys.dof();
    let (q, qd) = y.split_at(n);
    let qdd = sys.accel(t, q, qd)?;
    let mut out = Vec::with_capacity(2 * n);
    out.extend_from_slice(qd);
    out.extend(qdd);
    Ok(out)
}

/// `y + Σ_k h a_k k_k`.
fn combine(y: &[f64], h: f64, terms: &[(f64, &[f64])]) -> Vec<f64> {
    let mut out = y.to_vec();
    for (a, k) in terms {
        if *a != 0.0 {
            for (o, x) in out.iter_mut().zip(k.iter()) {
                *o += h * a * x;
            }
        }
    }
    out
}

/// One explicit Euler step.
pub fn euler_step(sys: &mut System, t: f64, y: &[f64], h: f64) -> Result<Vec<f64>, SimError> {
    let k1 = f(sys, t, y)?;
    Ok(combine(y, h, &[(1.0, &k1)]))
}

/// One classical fourth-order Runge–Kutta step.
pub fn rk4_step(sys: &mut System, t: f64, y: &[f64], h: f64) -> Result<Vec<f64>, SimError> {
    let k1 = f(sys, t, y)?;
    let k2 = f(sys, t + h / 2.0, &combine(y, h, &[(0.5, &k1)]))?;
    let k3 = f(sys, t + h / 2.0, &combine(y, h, &[(0.5, &k2)]))?;
    let k4 = f(sys, t + h, &combine(y, h, &[(1.0, &k3)]))?;
    Ok(combine(
        y,
        h,
        &[
            (1.0 / 6.0, &k1),
            (1.0 / 3.0, &k2),
            (1.0 / 3.0, &k3),
            (1.0 / 6.0, &k4),
        ],
    ))
}

/// The Dormand–Prince nodes `c`, stages `a` and the fifth-order weights (the seventh row of `a`).
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [&[f64]; 7] = [
    &[],
    &[1.0 / 5.0],
    &[3.0 / 40.0, 9.0 / 40.0],
    &[44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0],
    &[
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
    ],
    &[
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
    ],
    &[
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order minus fourth-order weights: the local error estimate.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// A Dormand–Prince step's result.
pub struct Dopri {
    /// The fifth-order solution at `t + h`.
    pub y: Vec<f64>,
    /// `ẏ` at `t + h` (first stage of the next step: "first same as last").
    pub dy: Vec<f64>,
    /// The scaled error norm; the step is accepted when it is at most 1.
    pub err: f64,
}

/// One Dormand–Prince 5(4) step from `(t, y)` with `dy = ẏ(t, y)`, tolerances relative and
/// absolute `tol`.
pub fn dopri_step(
    sys: &mut System,
    t: f64,
    y: &[f64],
    dy: &[f64],
    h: f64,
    tol: f64,
) -> Result<Dopri, SimError> {
    let mut k: Vec<Vec<f64>> = vec![dy.to_vec()];
    let stage = |k: &[Vec<f64>], s: usize| -> Vec<f64> {
        let terms: Vec<(f64, &[f64])> = A[s]
            .iter()
            .zip(k)
            .map(|(a, kk)| (*a, kk.as_slice()))
            .collect();
        combine(y, h, &terms)
    };
    for s in 1..6 {
        let ys = stage(&k, s);
        k.push(f(sys, t + C[s] * h, &ys)?);
    }
    // The seventh stage is evaluated at the fifth-order solution itself.
    let y5 = stage(&k, 6);
    k.push(f(sys, t + h, &y5)?);
    let err_terms: Vec<(f64, &[f64])> = E
        .iter()
        .zip(&k)
        .map(|(e, kk)| (*e, kk.as_slice()))
        .collect();
    let e = combine(&vec![0.0; y.len()], h, &err_terms);
    let mut sum = 0.0;
    for i in 0..y.len() {
        let sc = tol + tol * y[i].abs().max(y5[i].abs());
        sum += (e[i] / sc).powi(2);
    }
    let err = (sum / y.len().max(1) as f64).sqrt();
    let dy = k.pop().unwrap_or_default();
    Ok(Dopri { y: y5, dy, err })
}

/// `ẏ` at `(t, y)`, for the first Dormand–Prince step.
pub fn derivative(sys: &mut System, t: f64, y: &[f64]) -> Result<Vec<f64>, SimError> {
    f(sys, t, y)
}
