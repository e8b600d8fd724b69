//! The Christoffel symbols and `C(q, q̇)` from `∂D/∂q` on the compact form (Spong et al., §7.4):
//! `c_ijk = ½ (∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)`, `c_kj = Σ_i c_ijk q̇_i`.
//!
//! The derivatives are taken by the chain rule through the names of `D` ([`Compact::diff`]), each name's
//! derivative once (`D1_2_q3` is `∂D1_2/∂q3`), for the upper triangle only (`∂D/∂q_i` is symmetric).
//! The symbols are named `c{i}_{j}_{k}` for `i ≤ j` (`c_ijk = c_jik`).

use crate::algebra::compact::Compact;
use crate::algebra::{Poly, Rational, Symbol};
use crate::dynamics::lagrange::christoffel_from;
pub use crate::dynamics::lagrange::coriolis_matrix as coriolis;

/// Whether no entry of `D` depends on a position `q_i` (then every Christoffel symbol vanishes).
pub fn is_constant(d: &[Vec<Poly>], arena: &Compact) -> bool {
    d.iter().flatten().all(|e| !arena.deps(e).has_position())
}

/// `c[i][j][k] = c_ijk` (0-based), symmetric in `i, j`.
pub fn christoffel(d: &[Vec<Poly>], arena: &mut Compact) -> Vec<Vec<Vec<Poly>>> {
    let n = d.len();
    // dd[i][a][b − a] = ∂d_ab/∂q_i for a ≤ b.
    let dd: Vec<Vec<Vec<Poly>>> = (0..n)
        .map(|i| {
            let q = Symbol::q(i as u32 + 1);
            (0..n)
                .map(|a| (a..n).map(|b| arena.diff(&d[a][b], &q)).collect())
                .collect()
        })
        .collect();
    christoffel_from(&dd, |i, j, k, v| {
        arena.name(v, &format!("c{}_{}_{}", i + 1, j + 1, k + 1))
    })
}

/// `τ_k = Σ_j d_kj q̈_j + Σ_{i ≤ j} (2 − δ_ij) c_ijk q̇_i q̇_j + g_k + f_k`, with `f_k` the joint's
/// friction term (`B q̇_k`, zero without one).
pub fn equations(
    d: &[Vec<Poly>],
    c: Option<&[Vec<Vec<Poly>>]>,
    g: &[Poly],
    friction: &[Poly],
) -> Vec<Poly> {
    let n = d.len();
    let qd: Vec<Poly> = (1..=n as u32)
        .map(|i| Poly::symbol(&Symbol::qd(i)))
        .collect();
    let qdd: Vec<Poly> = (1..=n as u32)
        .map(|i| Poly::symbol(&Symbol::qdd(i)))
        .collect();
    let two = Rational::int(2);
    (0..n)
        .map(|k| {
            let mut parts: Vec<Poly> = (0..n).map(|j| d[k][j].mul(&qdd[j])).collect();
            if let Some(c) = c {
                for i in 0..n {
                    for j in i..n {
                        let rates = qd[i].mul(&qd[j]);
                        let rates = if i == j { rates } else { rates.scale(&two) };
                        parts.push(c[i][j][k].mul(&rates));
                    }
                }
            }
            parts.push(g[k].clone());
            parts.extend(friction.get(k).cloned());
            Poly::sum(parts.iter())
        })
        .collect()
}
