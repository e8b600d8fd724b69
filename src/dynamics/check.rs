//! The proofs `symdyn check` prints: one method against another, and the identities of the dynamics.
//!
//! Each claim is decided by the exact zero test of the normal form, never by sampling:
//! - Euler–Lagrange and Newton–Euler (body-fixed and inertial) give identical `τ`;
//! - `D(q)` is symmetric;
//! - `Ḋ − 2C` is skew-symmetric (Spong et al., Property 7.1).

use super::derivation::Derivation;
use super::ne_symbolic::Frame;
use crate::algebra::calculus::poly_dt;
use crate::algebra::Rational;

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
            // The normal form is canonical, so `a − b = 0` exactly when the two are equal term by term.
            .filter(|&k| el.tau[k] != ne.tau[k])
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
            if el.d[k][j] != el.d[j][k] {
                asym.push(format!("d{}{} ≠ d{}{}", k + 1, j + 1, j + 1, k + 1));
            }
        }
    }
    claims.push(claim("D(q) is symmetric", asym));
    // N = Ḋ − 2C is skew-symmetric when N_kj + N_jk = 0 for k ≥ j, that is
    // Ḋ_kj + Ḋ_jk = 2 (C_kj + C_jk). Where d_kj and d_jk are the same polynomial (always, when D is
    // symmetric) the left side is 2 Ḋ_kj, so the test is Ḋ_kj = C_kj + C_jk: one time derivative per
    // pair instead of two, and no matrix N formed.
    let two = Rational::int(2);
    let mut skew = Vec::new();
    for k in 0..n {
        for j in 0..=k {
            let c_sum = el.c[k][j].add(&el.c[j][k]);
            let holds = if el.d[k][j] == el.d[j][k] {
                poly_dt(&el.d[k][j]) == c_sum
            } else {
                poly_dt(&el.d[k][j]).add(&poly_dt(&el.d[j][k])) == c_sum.scale(&two)
            };
            if !holds {
                skew.push(format!("N{}{} + N{}{} ≠ 0", k + 1, j + 1, j + 1, k + 1));
            }
        }
    }
    claims.push(claim("Ḋ − 2C is skew-symmetric", skew));
    claims
}
