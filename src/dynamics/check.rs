//! The proofs `symdyn check` prints: one method against another, and the identities of the dynamics.
//!
//! Each claim is decided by the exact zero test of the normal form, never by sampling:
//! - Euler–Lagrange and Newton–Euler (body-fixed and inertial) give identical `τ`;
//! - `D(q)` is symmetric;
//! - `Ḋ − 2C` is skew-symmetric (Spong et al., Property 7.1).

use super::derivation::Derivation;
use super::ne_symbolic::Frame;
use crate::algebra::calculus::poly_dt;
use crate::algebra::Poly;

/// One proved (or refuted) claim.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Claim {
    /// What is claimed.
    pub statement: String,
    /// Whether the zero test proved it.
    pub holds: bool,
    /// Where it fails (entries that are not zero), empty when it holds.
    pub failures: Vec<String>,
}

fn claim(statement: &str, failures: Vec<String>) -> Claim {
    Claim {
        statement: statement.to_string(),
        holds: failures.is_empty(),
        failures,
    }
}

/// Proves the claims for a derivation: Euler–Lagrange against Newton–Euler in both frames, `D`
/// symmetric, `Ḋ − 2C` skew-symmetric.
pub fn check(der: &Derivation) -> Vec<Claim> {
    check_frames(der, &[Frame::Body, Frame::Inertial])
}

/// [`check`] with Newton–Euler derived (and compared) only in the given frames.
pub fn check_frames(der: &Derivation, frames: &[Frame]) -> Vec<Claim> {
    let mut claims: Vec<Claim> = frames.iter().map(|&f| agreement(der, f)).collect();
    claims.extend(identities(der));
    claims
}

/// The claim that Euler–Lagrange and Newton–Euler in `frame` give identical equations.
pub fn agreement(der: &Derivation, frame: Frame) -> Claim {
    let el = der.lagrange();
    let n = der.robot().dof();
    {
        let ne = der.newton_euler(frame);
        let bad: Vec<String> = (0..n)
            .filter(|&k| !el.tau[k].sub(&ne.tau[k]).is_zero())
            .map(|k| format!("equation {}", k + 1))
            .collect();
        let what = format!(
            "Euler–Lagrange and Newton–Euler ({}) give identical equations",
            if frame == Frame::Body {
                "body-fixed frames"
            } else {
                "inertial frame"
            }
        );
        claim(&what, bad)
    }
}

/// The identities of the Euler–Lagrange quantities: `D(q)` symmetric, `Ḋ − 2C` skew-symmetric.
pub fn identities(der: &Derivation) -> Vec<Claim> {
    let el = der.lagrange();
    let n = der.robot().dof();
    let mut claims = Vec::new();
    let mut asym = Vec::new();
    for k in 0..n {
        for j in 0..k {
            if !el.d[k][j].sub(&el.d[j][k]).is_zero() {
                asym.push(format!("d{}{} ≠ d{}{}", k + 1, j + 1, j + 1, k + 1));
            }
        }
    }
    claims.push(claim("D(q) is symmetric", asym));
    let ddot: Vec<Vec<Poly>> =
        el.d.iter()
            .map(|r| r.iter().map(poly_dt).collect())
            .collect();
    let two = crate::algebra::Rational::int(2);
    let nmat: Vec<Vec<Poly>> = (0..n)
        .map(|k| {
            (0..n)
                .map(|j| ddot[k][j].sub(&el.c[k][j].scale(&two)))
                .collect()
        })
        .collect();
    let mut skew = Vec::new();
    for k in 0..n {
        for j in 0..=k {
            if !nmat[k][j].add(&nmat[j][k]).is_zero() {
                skew.push(format!("N{}{} + N{}{} ≠ 0", k + 1, j + 1, j + 1, k + 1));
            }
        }
    }
    claims.push(claim("Ḋ − 2C is skew-symmetric", skew));
    claims
}
