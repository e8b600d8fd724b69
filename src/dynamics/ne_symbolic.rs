//! The inputs of the Newton–Euler recursion, built exactly from the kinematics, in body-fixed frames or
//! in the inertial frame (the two variants of the worked solution, results (9)–(11) and (12)).

use super::kinematics::Kinematics;
use super::model::{JointKind, Robot};
use super::newton_euler::{recurse_until, Body, NewtonEuler, Part, Step};
use super::vec3::{Mat3, Vec3};
use crate::algebra::{to_poly, Poly, Symbol};

/// The frame the Newton–Euler quantities are written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Frame {
    /// Each link's quantities in its own frame `i`.
    Body,
    /// Everything in the inertial frame 0.
    Inertial,
}

impl Frame {
    /// `body` or `inertial`.
    pub fn name(self) -> &'static str {
        match self {
            Frame::Body => "body",
            Frame::Inertial => "inertial",
        }
    }
}

fn mat(t: &[[crate::algebra::Expr; 3]; 3]) -> Mat3<Poly> {
    Mat3(std::array::from_fn(|r| {
        std::array::from_fn(|c| to_poly(&t[r][c]))
    }))
}

/// The recursion's steps for `robot` in `frame`.
pub fn steps(robot: &Robot, kin: &Kinematics, frame: Frame) -> Vec<Step<Poly>> {
    build(robot, kin, frame, true)
}

/// The steps; with `rotate_inertia` false, [`Step::inertia`] stays in the link's own frame even in
/// the inertial variant (for [`derive`], which rotates the Euler term instead of the tensor).
fn build(robot: &Robot, kin: &Kinematics, frame: Frame, rotate_inertia: bool) -> Vec<Step<Poly>> {
    let g0 = Vec3(std::array::from_fn(|k| to_poly(&robot.gravity[k])));
    (0..robot.dof())
        .map(|i| {
            let jf = &kin.joints[i];
            let link = &robot.links[i];
            let com = Vec3(std::array::from_fn(|k| to_poly(&link.com[k])));
            let inertia = link.inertia.as_ref().filter(|_| kin.rotates[i]).map(mat);
            let q = (i + 1) as u32;
            let qd = jf.rate.mul(&Poly::symbol(&Symbol::qd(q)));
            let qdd = jf.rate.mul(&Poly::symbol(&Symbol::qdd(q)));
            let rel = jf.origin.sub(&jf.joint_point);
            // The payload rides on the last link: its data in frame n, moved as the link's is.
            let payload = robot
                .payload
                .as_ref()
                .filter(|_| i + 1 == robot.dof())
                .map(|l| {
                    let com = Vec3(std::array::from_fn(|k| to_poly(&l.com[k])));
                    let inertia = l.inertia.as_ref().filter(|_| kin.rotates[i]).map(mat);
                    (to_poly(&l.mass), com, inertia)
                });
            let (rot_in, axis, s, r_joint_origin, r_origin_com, inertia, gravity) = match frame {
                Frame::Body => {
                    let rt = jf.rot.transpose();
                    let s = rt.mul_vec(&jf.joint_point);
                    let r = rt.mul_vec(&rel);
                    let g = kin.rot0[i + 1].tr_mul_vec(&g0);
                    (rt, jf.axis_local.clone(), s, r, com, inertia, g)
                }
                Frame::Inertial => {
                    let prev = &kin.rot0[i];
                    let here = &kin.rot0[i + 1];
                    let inertia = if rotate_inertia {
                        inertia.map(|t| here.mul(&t).mul(&here.transpose()))
                    } else {
                        inertia
                    };
                    (
                        Mat3::identity(),
                        kin.axis0[i].clone(),
                        prev.mul_vec(&jf.joint_point),
                        prev.mul_vec(&rel),
                        here.mul_vec(&com),
                        inertia,
                        g0.clone(),
                    )
                }
            };
            let payload = payload.map(|(mass, com, tensor)| match frame {
                Frame::Body => Body {
                    mass,
                    r_origin_com: com,
                    inertia: tensor,
                },
                Frame::Inertial => {
                    let here = &kin.rot0[i + 1];
                    Body {
                        mass,
                        r_origin_com: here.mul_vec(&com),
                        inertia: if rotate_inertia {
                            tensor.map(|t| here.mul(&t).mul(&here.transpose()))
                        } else {
                            tensor
                        },
                    }
                }
            });
            Step {
                revolute: jf.kind == JointKind::Revolute,
                rot_in,
                axis,
                s,
                r_joint_origin,
                r_origin_com,
                mass: to_poly(&link.mass),
                inertia,
                gravity,
                qd,
                qdd,
                rate: jf.rate.clone(),
                drive: robot.drive_term(i + 1),
                payload,
            }
        })
        .collect()
}

/// The exact Newton–Euler quantities of `robot` in `frame`.
///
/// In the inertial frame the tensor of link `i` is `I⁰_i = R_0^i I_i R_0^iᵀ`, whose expanded entries
/// are far larger than the vectors they multiply. The Euler term is evaluated as
/// `I⁰_i α = R_0^i (I_i (R_0^iᵀ α))` and `ω × (I⁰_i ω) = R_0^i (ω' × (I_i ω'))` with `ω' = R_0^iᵀ ω`
/// (a rotation preserves the cross product): the same polynomials, since the normal form is
/// canonical, without ever expanding `I⁰_i`.
pub fn derive(robot: &Robot, kin: &Kinematics, frame: Frame) -> NewtonEuler<Poly> {
    derive_until(robot, kin, frame, &|| false).expect("a derivation never stopped runs to the end")
}

/// [`derive()`], given up (`None`) as soon as `stop` says so, asked before each link of either
/// recursion ([`recurse_until`]).
pub fn derive_until(
    robot: &Robot,
    kin: &Kinematics,
    frame: Frame,
    stop: &dyn Fn() -> bool,
) -> Option<NewtonEuler<Poly>> {
    match frame {
        Frame::Body => recurse_until(&steps(robot, kin, frame), None, stop),
        Frame::Inertial => {
            let steps = build(robot, kin, frame, false);
            recurse_until(
                &steps,
                Some(&|i, part, alpha, omega| {
                    let local = match part {
                        Part::Link => steps[i].inertia.as_ref()?,
                        Part::Payload => steps[i].payload.as_ref()?.inertia.as_ref()?,
                    };
                    let r = &kin.rot0[i + 1];
                    let (alpha_i, omega_i) = (r.tr_mul_vec(alpha), r.tr_mul_vec(omega));
                    Some((
                        r.mul_vec(&local.mul_vec(&alpha_i)),
                        r.mul_vec(&omega_i.cross(&local.mul_vec(&omega_i))),
                    ))
                }),
                stop,
            )
        }
    }
}
