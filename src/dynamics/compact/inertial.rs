//! Newton–Euler in the inertial frame on the compact form: the recursion of
//! [`crate::dynamics::newton_euler`] (the one the expanded derivation runs) over the naming scalar
//! [`Named`], with its inputs from the rotations `R_0^i` named link by link (`R{i}_{rc}`).
//!
//! As in [`crate::dynamics::ne_symbolic::derive`], the tensor `R_0^i I_i R_0^iᵀ` is never formed: the
//! Euler term is `R_0^i (I_i (R_0^iᵀ α))` and `R_0^i (ω' × (I_i ω'))` with `ω' = R_0^iᵀ ω`.

use super::scalar::Named;
use super::{name_mat, name_vec};
use crate::algebra::compact::Compact;
use crate::algebra::{to_poly, Expr, Poly, Symbol};
use crate::dynamics::kinematics::JointFrame;
use crate::dynamics::model::{JointKind, Robot};
use crate::dynamics::newton_euler::{recurse_with, Body, Part, Step};
use crate::dynamics::scalar::Scalar;
use crate::dynamics::vec3::{Mat3, Vec3};
use std::cell::RefCell;
use std::rc::Rc;

fn wrap_vec(a: &Rc<RefCell<Compact>>, v: &Vec3<Poly>) -> Vec3<Named> {
    Vec3(std::array::from_fn(|k| Named::new(a, v.0[k].clone())))
}

fn wrap_mat(a: &Rc<RefCell<Compact>>, m: &Mat3<Poly>) -> Mat3<Named> {
    Mat3(std::array::from_fn(|r| {
        std::array::from_fn(|c| Named::new(a, m.0[r][c].clone()))
    }))
}

fn vec_of(e: &[Expr; 3]) -> Vec3<Poly> {
    Vec3(std::array::from_fn(|k| to_poly(&e[k])))
}

/// `τ` by Newton–Euler in the inertial frame, its intermediates added to `arena`.
pub fn tau(robot: &Robot, joints: &[JointFrame], arena: Compact) -> (Compact, Vec<Poly>) {
    let n = robot.dof();
    let mut arena = arena;
    // R_0^i, i = 0..=n.
    let mut rot0: Vec<Mat3<Poly>> = vec![Mat3::identity()];
    for (idx, jf) in joints.iter().enumerate() {
        let r = rot0[idx].mul(&jf.rot);
        rot0.push(name_mat(&mut arena, r, &format!("R{}", idx + 1)));
    }
    let mut rotates = Vec::with_capacity(n);
    let mut any = false;
    let mut axes = Vec::with_capacity(n);
    for (idx, jf) in joints.iter().enumerate() {
        any |= jf.kind == JointKind::Revolute;
        rotates.push(any);
        let z = rot0[idx + 1].mul_vec(&jf.axis_local);
        axes.push(name_vec(&mut arena, z, &format!("z{}", idx + 1)));
    }
    let a = Rc::new(RefCell::new(arena));
    let g0 = vec_of(&robot.gravity);
    let steps: Vec<Step<Named>> = (0..n)
        .map(|i| {
            let jf = &joints[i];
            let link = &robot.links[i];
            let (prev, here) = (&rot0[i], &rot0[i + 1]);
            let rel = jf.origin.sub(&jf.joint_point);
            let q = (i + 1) as u32;
            let inertia = link.inertia.as_ref().filter(|_| rotates[i]).map(|t| {
                Mat3(std::array::from_fn(|r| {
                    std::array::from_fn(|c| Named::new(&a, to_poly(&t[r][c])))
                }))
            });
            Step {
                revolute: jf.kind == JointKind::Revolute,
                rot_in: Mat3::identity(),
                axis: wrap_vec(&a, &axes[i]),
                s: wrap_vec(&a, &prev.mul_vec(&jf.joint_point)),
                r_joint_origin: wrap_vec(&a, &prev.mul_vec(&rel)),
                r_origin_com: wrap_vec(&a, &here.mul_vec(&vec_of(&link.com))),
                mass: Named::new(&a, to_poly(&link.mass)),
                inertia,
                gravity: wrap_vec(&a, &g0),
                qd: Named::new(&a, jf.rate.mul(&Poly::symbol(&Symbol::qd(q)))),
                qdd: Named::new(&a, jf.rate.mul(&Poly::symbol(&Symbol::qdd(q)))),
                rate: Named::new(&a, jf.rate.clone()),
                drive: robot.drive_term(i + 1).map(|p| Named::new(&a, p)),
                payload: robot.payload.as_ref().filter(|_| i + 1 == n).map(|l| Body {
                    mass: Named::new(&a, to_poly(&l.mass)),
                    r_origin_com: wrap_vec(&a, &here.mul_vec(&vec_of(&l.com))),
                    inertia: l.inertia.as_ref().filter(|_| rotates[i]).map(|t| {
                        Mat3(std::array::from_fn(|r| {
                            std::array::from_fn(|c| Named::new(&a, to_poly(&t[r][c])))
                        }))
                    }),
                }),
            }
        })
        .collect();
    let rots: Vec<Mat3<Named>> = rot0.iter().map(|r| wrap_mat(&a, r)).collect();
    let tau: Vec<Poly> = {
        let ne = recurse_with(
            &steps,
            Some(&|i, part, alpha: &Vec3<Named>, omega: &Vec3<Named>| {
                let (local, name) = match part {
                    Part::Link => (steps[i].inertia.as_ref()?, format!("jw{}", i + 1)),
                    Part::Payload => (
                        steps[i].payload.as_ref()?.inertia.as_ref()?,
                        "jwL".to_string(),
                    ),
                };
                let r = &rots[i + 1];
                let (alpha_i, omega_i) = (r.tr_mul_vec(alpha), r.tr_mul_vec(omega));
                let jw = Named::label(local.mul_vec(&omega_i), &|| name.clone());
                Some((
                    r.mul_vec(&local.mul_vec(&alpha_i)),
                    r.mul_vec(&omega_i.cross(&jw)),
                ))
            }),
        );
        ne.tau.into_iter().map(Named::into_value).collect()
    };
    drop(steps);
    drop(rots);
    let arena = Rc::try_unwrap(a)
        .map(RefCell::into_inner)
        .unwrap_or_else(|rc| rc.borrow().clone());
    (arena, tau)
}
