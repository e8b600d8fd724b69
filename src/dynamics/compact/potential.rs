//! The potential energy `P` and the gravity vector `g(q) = ∂P/∂q` on the compact form (Spong et al.,
//! §7.3: `P = −Σ_i m_i gᵀ p_ci`, `g` the gravitational acceleration in frame 0; a payload is one more
//! term, `−m_L gᵀ p_cL`, at the last link).
//!
//! Gravity is carried into each link frame, `g_i = R_{i−1}^iᵀ g_{i−1}`, and the height of each origin
//! accumulated as a scalar, `e_i = gᵀ o_i = e_{i−1} + g_{i−1} · p_i` (`p_i = o_i` in frame `i − 1`),
//! so `gᵀ p_ci = e_i + g_i · r_i` needs no rotation `R_0^i` at all. `g_k` is then `∂P/∂q_k` by the
//! chain rule through the names ([`Compact::diff`]). Names: `gr{i}_{k}` for `g_i`, `eg{i}` for `e_i`.

use super::name_vec;
use crate::algebra::compact::Compact;
use crate::algebra::{to_poly, Poly, Symbol};
use crate::dynamics::kinematics::JointFrame;
use crate::dynamics::model::Robot;
use crate::dynamics::vec3::Vec3;

/// `P` and `g(q)`.
pub fn potential_and_gravity(
    robot: &Robot,
    joints: &[JointFrame],
    arena: &mut Compact,
) -> (Poly, Vec<Poly>) {
    let mut g_prev: Vec3<Poly> = Vec3(std::array::from_fn(|k| to_poly(&robot.gravity[k])));
    let mut e_prev = Poly::zero();
    let mut parts = Vec::with_capacity(robot.dof());
    for (idx, jf) in joints.iter().enumerate() {
        let i = idx + 1;
        let e = arena.name(e_prev.add(&g_prev.dot(&jf.origin)), &format!("eg{i}"));
        let g = name_vec(arena, jf.rot.tr_mul_vec(&g_prev), &format!("gr{i}"));
        let link = &robot.links[idx];
        let r = Vec3(std::array::from_fn(|k| to_poly(&link.com[k])));
        parts.push(to_poly(&link.mass).mul(&e.add(&g.dot(&r))).neg());
        if let Some(l) = robot.payload.as_ref().filter(|_| i == robot.dof()) {
            let r = Vec3(std::array::from_fn(|k| to_poly(&l.com[k])));
            parts.push(to_poly(&l.mass).mul(&e.add(&g.dot(&r))).neg());
        }
        g_prev = g;
        e_prev = e;
    }
    let p = Poly::sum(parts.iter());
    let g = (1..=robot.dof() as u32)
        .map(|k| arena.diff(&p, &Symbol::q(k)))
        .collect();
    (p, g)
}
