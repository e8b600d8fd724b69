//! `D(q)` by the composite-rigid-body algorithm, in body-fixed frames, on the compact form
//! (Walker and Orin 1982; Featherstone, *Rigid Body Dynamics Algorithms*, §6.2, in 3-vector form).
//!
//! The composite body `C_i` is links `i..n` held rigid. In frame `i`, about the origin `o_i`, it has
//! mass `M_i`, first moment `h_i = Σ m (p − o_i)` and rotational inertia `J_i`, built from the tip:
//! - link `i` alone: `m_i`, `m_i r_i`, `I_i + m_i (|r_i|² 1 − r_i r_iᵀ)` (`r_i` its centre of mass),
//!   and the same of the payload added to link `n`'s;
//! - plus `C_{i+1}` seen from frame `i` (`R = R_i^{i+1}`, `p = o_{i+1}` in frame `i`, `h' = R h_{i+1}`):
//!   `M_{i+1}`, `h' + M_{i+1} p`, `R J_{i+1} Rᵀ − S(h') S(p) − S(p) S(h') − M_{i+1} S(p)²`.
//!
//! Column `j` of `D` is the generalised force of a unit `q̈_j` with `q̇ = 0` and no gravity: `C_j`
//! turns about (or slides along) the axis `b_j` of joint `j` at rate `ρ_j` (the joint's constant rate),
//! so the wrench it needs is, about `o_j` in frame `j` (`r_J` from `o_j` to the joint's point):
//! - revolute, `α = ρ_j b_j`: `F = α × (h_j − M_j r_J)`, `N = J_j α − h_j × (α × r_J)`;
//! - prismatic, `a = ρ_j b_j`: `F = M_j a`, `N = h_j × a`.
//!
//! It is carried down the chain (`F ← R F`, `N ← R N + p × R F`, from frame `k` to `k − 1`) and
//! projected on each joint `i ≤ j`: `d_ij = ρ_i b_i · (N − r_J,i × F)` (revolute) or `ρ_i b_i · F`
//! (prismatic). Only the upper triangle is computed; `D` is symmetric.
//!
//! Names: `Mc{i}`, `hc{i}_{k}`, `Jc{i}_{rc}` for the composite bodies, `FD{j}_{k}_{c}` and
//! `ND{j}_{k}_{c}` for the wrench of column `j` in frame `k`, `D{i}_{j}` for the entries.

use super::{name_sym, name_vec, skew};
use crate::algebra::compact::Compact;
use crate::algebra::{to_poly, Poly};
use crate::dynamics::kinematics::JointFrame;
use crate::dynamics::model::{JointKind, Robot};
use crate::dynamics::vec3::{Mat3, Vec3};

/// One link's composite body, in its own frame about its origin.
struct Composite {
    mass: Poly,
    first: Vec3<Poly>,
    inertia: Mat3<Poly>,
}

/// The link's own mass, first moment and inertia about its frame's origin (the parallel-axis theorem),
/// with the payload's added for the last link (about the origin they simply add: no division).
fn own(robot: &Robot, i: usize) -> Composite {
    let mut c = body(&robot.links[i]);
    if let Some(l) = robot.payload.as_ref().filter(|_| i + 1 == robot.dof()) {
        let p = body(l);
        c = Composite {
            mass: c.mass.add(&p.mass),
            first: c.first.add(&p.first),
            inertia: c.inertia.add(&p.inertia),
        };
    }
    c
}

/// One body's mass, first moment and inertia about its frame's origin.
fn body(link: &crate::dynamics::Link) -> Composite {
    let m = to_poly(&link.mass);
    let r = Vec3(std::array::from_fn(|k| to_poly(&link.com[k])));
    let s = skew(&r);
    // I + m (|r|² 1 − r rᵀ) = I − m S(r)².
    let shift = s.mul(&s).scale(&m.neg());
    let inertia = match &link.inertia {
        Some(t) => Mat3(std::array::from_fn(|a| {
            std::array::from_fn(|b| to_poly(&t[a][b]))
        }))
        .add(&shift),
        None => shift,
    };
    Composite {
        first: r.scale(&m),
        mass: m,
        inertia,
    }
}

/// The upper triangle of `D(q)` mirrored, by composite rigid bodies (see the [module docs](self)).
/// `joints` are the robot's local joint frames.
pub fn mass_matrix(robot: &Robot, joints: &[JointFrame], arena: &mut Compact) -> Vec<Vec<Poly>> {
    let n = robot.dof();
    // Composite bodies, tip to base.
    let mut comp: Vec<Option<Composite>> = (0..n).map(|_| None).collect();
    for i in (0..n).rev() {
        let mut c = own(robot, i);
        if let Some(child) = comp.get(i + 1).and_then(Option::as_ref) {
            let jf = &joints[i + 1];
            let (rot, p) = (&jf.rot, &jf.origin);
            let h = rot.mul_vec(&child.first);
            let sp = skew(p);
            let sh = skew(&h);
            let j = rot.mul(&child.inertia).mul(&rot.transpose());
            let shift = sh
                .mul(&sp)
                .add(&sp.mul(&sh))
                .add(&sp.mul(&sp).scale(&child.mass));
            c.inertia = c.inertia.add(&j);
            c.inertia = Mat3(std::array::from_fn(|a| {
                std::array::from_fn(|b| c.inertia.0[a][b].sub(&shift.0[a][b]))
            }));
            c.first = c.first.add(&h).add(&p.scale(&child.mass));
            c.mass = c.mass.add(&child.mass);
        }
        let k = i + 1;
        c.mass = arena.name(c.mass, &format!("Mc{k}"));
        c.first = name_vec(arena, c.first, &format!("hc{k}"));
        c.inertia = name_sym(arena, c.inertia, &format!("Jc{k}"));
        comp[i] = Some(c);
    }
    let comp: Vec<Composite> = comp.into_iter().map(|c| c.expect("every link")).collect();
    // `r_J` of each joint, in its own frame: from o_i to the joint's point.
    let r_joint: Vec<Vec3<Poly>> = joints
        .iter()
        .map(|jf| jf.rot.tr_mul_vec(&jf.joint_point.sub(&jf.origin)))
        .collect();
    let project = |i: usize, f: &Vec3<Poly>, nm: &Vec3<Poly>| -> Poly {
        let jf = &joints[i];
        match jf.kind {
            JointKind::Revolute => jf.axis_local.dot(&nm.sub(&r_joint[i].cross(f))),
            JointKind::Prismatic => jf.axis_local.dot(f),
        }
        .mul(&jf.rate)
    };
    let mut d = vec![vec![Poly::zero(); n]; n];
    for j in 0..n {
        let jf = &joints[j];
        let c = &comp[j];
        let axis = jf.axis_local.scale(&jf.rate);
        let (mut f, mut nm) = match jf.kind {
            JointKind::Revolute => (
                axis.cross(&c.first.sub(&r_joint[j].scale(&c.mass))),
                c.inertia
                    .mul_vec(&axis)
                    .sub(&c.first.cross(&axis.cross(&r_joint[j]))),
            ),
            JointKind::Prismatic => (axis.scale(&c.mass), c.first.cross(&axis)),
        };
        let col = j + 1;
        f = name_vec(arena, f, &format!("FD{col}_{col}"));
        nm = name_vec(arena, nm, &format!("ND{col}_{col}"));
        // The motor's rotor, reflected through its gear (Spong §7.5), on the diagonal.
        let rotor = to_poly(&robot.drive(col).rotor);
        d[j][j] = arena.name(project(j, &f, &nm).add(&rotor), &format!("D{col}_{col}"));
        for k in (1..=j).rev() {
            // From frame k to frame k − 1 (0-based: joint k's frame carries it to link k − 1).
            let jk = &joints[k];
            let rf = jk.rot.mul_vec(&f);
            nm = jk.rot.mul_vec(&nm).add(&jk.origin.cross(&rf));
            f = name_vec(arena, rf, &format!("FD{col}_{k}"));
            nm = name_vec(arena, nm, &format!("ND{col}_{k}"));
            let entry = arena.name(project(k - 1, &f, &nm), &format!("D{k}_{col}"));
            d[k - 1][j] = entry.clone();
            d[j][k - 1] = entry;
        }
    }
    d
}
