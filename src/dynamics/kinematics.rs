//! Forward kinematics and velocity Jacobians, exact (Spong et al., ch. 3–4 and §7.2).
//!
//! From the DH table: the link transforms `A_i` (rotation `R_{i−1}^i`, origin `o_i` in frame `i−1`),
//! the rotations `R_0^i` and origins `o_i` in frame 0, the centres of mass `p_ci` in frame 0, the joint
//! axes in frame 0, and for each link the Jacobians of its centre of mass: `J_v,i` (column `j` is
//! `∂p_ci/∂q_j`, exact for either DH convention) and `J_ω,i` (column `j` is the axis of joint `j` times
//! its rate for a revolute `j ≤ i`, zero otherwise); for a payload, its centre of mass and `J_v,L`.

use super::model::{Convention, JointKind, Placement, Robot};
use super::placement;
use super::vec3::{Mat3, Vec3};
use crate::algebra::calculus::poly_diff;
use crate::algebra::{to_poly, Expr, Poly, Symbol};

/// One joint's local geometry, everything exact.
#[derive(Clone, Debug)]
pub struct JointFrame {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// `R_{i−1}^i`: the axes of frame `i` in frame `i−1`.
    pub rot: Mat3<Poly>,
    /// `o_i` in frame `i−1`.
    pub origin: Vec3<Poly>,
    /// The point of the joint axis where the joint acts, in frame `i−1`: `o_{i−1}` (zero) in standard DH,
    /// `a_{i−1} x_{i−1}` in modified DH, the placement's `xyz` for a placed joint.
    pub joint_point: Vec3<Poly>,
    /// The joint axis in frame `i` coordinates: `z_{i−1}` (standard), `z_i` (modified) or the
    /// placement's `axis`.
    pub axis_local: Vec3<Poly>,
    /// `∂θ_i/∂q_i` or `∂d_i/∂q_i`: a non-zero constant, 1 in every ordinary table.
    pub rate: Poly,
}

/// The columns of a 3×n Jacobian.
pub type Columns = Vec<Vec3<Poly>>;

/// The kinematics of a robot.
#[derive(Clone, Debug)]
pub struct Kinematics {
    /// Per joint `i` (index `i − 1`).
    pub joints: Vec<JointFrame>,
    /// `R_0^i` for `i = 0..=n` (index 0 is the identity).
    pub rot0: Vec<Mat3<Poly>>,
    /// `o_i` in frame 0 for `i = 0..=n`.
    pub origin0: Vec<Vec3<Poly>>,
    /// Centre of mass of link `i` in frame 0 (index `i − 1`).
    pub com0: Vec<Vec3<Poly>>,
    /// Axis of joint `i` in frame 0 (index `i − 1`).
    pub axis0: Vec<Vec3<Poly>>,
    /// `J_v,i`: columns `j = 1..=n` (index `[i−1][j−1]`).
    pub jv: Vec<Vec<Vec3<Poly>>>,
    /// `J_ω,i`: columns `j = 1..=n`.
    pub jw: Vec<Vec<Vec3<Poly>>>,
    /// Whether link `i` can rotate: some joint `j ≤ i` is revolute.
    pub rotates: Vec<bool>,
    /// The payload's centre of mass `p_cL` in frame 0 and its `J_v,L` (columns `j = 1..=n`), when
    /// the robot has a payload (it moves with link `n`, so its `J_ω` is `J_ω,n`).
    pub payload: Option<(Vec3<Poly>, Vec<Vec3<Poly>>)>,
}

fn p(e: &Expr) -> Poly {
    to_poly(e)
}

fn vec_of(e: &[Expr; 3]) -> Vec3<Poly> {
    Vec3(std::array::from_fn(|i| p(&e[i])))
}

/// Joint `i`'s local geometry (1-based) from its DH row in the robot's convention, or from its
/// placement ([`super::placement`]): the one seam through which every method reads the joints.
pub(crate) fn joint_frame(robot: &Robot, i: usize) -> JointFrame {
    let j = &robot.joints[i - 1];
    let q = Symbol::q(i as u32);
    if j.placement.is_some() || robot.convention == Convention::Placement {
        let rate = match j.kind {
            JointKind::Revolute => poly_diff(&p(&j.theta), &q),
            JointKind::Prismatic => poly_diff(&p(&j.d), &q),
        };
        // (A placement robot's joint without a placement is refused by `Robot::validate`; it reads
        // as a joint about z at the parent's origin.)
        let at_origin = Placement::about_z();
        let placement = j.placement.as_ref().unwrap_or(&at_origin);
        return placement::joint_frame(j.kind, placement, &j.theta, &j.d, rate);
    }
    // (The order of these conversions interns the atoms, which orders the terms of every `Poly`
    // downstream and so the generated code: keep it.)
    let (ct, st) = (p(&Expr::cos(&j.theta)), p(&Expr::sin(&j.theta)));
    let (ca, sa) = (p(&Expr::cos(&j.alpha)), p(&Expr::sin(&j.alpha)));
    let (a, d) = (p(&j.a), p(&j.d));
    let z = Poly::zero;
    let rate = match j.kind {
        JointKind::Revolute => poly_diff(&p(&j.theta), &q),
        JointKind::Prismatic => poly_diff(&d, &q),
    };
    match robot.convention {
        Convention::Standard => {
            let rot = Mat3([
                [ct.clone(), st.neg().mul(&ca), st.mul(&sa)],
                [st.clone(), ct.mul(&ca), ct.neg().mul(&sa)],
                [z(), sa.clone(), ca.clone()],
            ]);
            let axis_local = rot.tr_mul_vec(&Vec3::unit(2));
            JointFrame {
                kind: j.kind,
                origin: Vec3([a.mul(&ct), a.mul(&st), d]),
                rot,
                joint_point: Vec3::zero(),
                axis_local,
                rate,
            }
        }
        Convention::Modified => {
            let rot = Mat3([
                [ct.clone(), st.neg(), z()],
                [ca.mul(&st), ca.mul(&ct), sa.neg()],
                [sa.mul(&st), sa.mul(&ct), ca.clone()],
            ]);
            JointFrame {
                kind: j.kind,
                origin: Vec3([a.clone(), sa.neg().mul(&d), ca.mul(&d)]),
                rot,
                joint_point: Vec3([a, z(), z()]),
                axis_local: Vec3::unit(2),
                rate,
            }
        }
        Convention::Placement => unreachable!("handled above"),
    }
}

impl Kinematics {
    /// Computes the kinematics of a (validated) robot.
    pub fn new(robot: &Robot) -> Kinematics {
        let n = robot.dof();
        let joints: Vec<JointFrame> = (1..=n).map(|i| joint_frame(robot, i)).collect();
        let mut rot0 = vec![Mat3::identity()];
        let mut origin0 = vec![Vec3::zero()];
        for jf in &joints {
            let r_prev = rot0.last().expect("non-empty").clone();
            let o_prev = origin0.last().expect("non-empty").clone();
            origin0.push(o_prev.add(&r_prev.mul_vec(&jf.origin)));
            rot0.push(r_prev.mul(&jf.rot));
        }
        let com0: Vec<Vec3<Poly>> = (1..=n)
            .map(|i| origin0[i].add(&rot0[i].mul_vec(&vec_of(&robot.links[i - 1].com))))
            .collect();
        let axis0: Vec<Vec3<Poly>> = (1..=n)
            .map(|i| match robot.convention {
                Convention::Standard => rot0[i - 1].column(2),
                Convention::Modified => rot0[i].column(2),
                Convention::Placement => rot0[i].mul_vec(&joints[i - 1].axis_local),
            })
            .collect();
        let mut rotates = Vec::with_capacity(n);
        let mut any = false;
        for jf in &joints {
            any |= jf.kind == JointKind::Revolute;
            rotates.push(any);
        }
        let jacobian = |p: &Vec3<Poly>, upto: usize| -> Vec<Vec3<Poly>> {
            (1..=n)
                .map(|j| {
                    if j > upto {
                        return Vec3::zero();
                    }
                    let q = Symbol::q(j as u32);
                    Vec3(std::array::from_fn(|k| poly_diff(&p.0[k], &q)))
                })
                .collect()
        };
        let jv = (0..n).map(|i| jacobian(&com0[i], i + 1)).collect();
        let payload = robot.payload.as_ref().map(|l| {
            let p = origin0[n].add(&rot0[n].mul_vec(&vec_of(&l.com)));
            let jv = jacobian(&p, n);
            (p, jv)
        });
        let jw = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        if j <= i && joints[j].kind == JointKind::Revolute {
                            axis0[j].scale(&joints[j].rate)
                        } else {
                            Vec3::zero()
                        }
                    })
                    .collect()
            })
            .collect();
        Kinematics {
            joints,
            rot0,
            origin0,
            com0,
            axis0,
            jv,
            jw,
            rotates,
            payload,
        }
    }

    /// Link `i`'s Jacobians seen from its own frame (`i` 0-based): `R_iᵀ J_v,i` and `R_iᵀ J_ω,i`, the
    /// same polynomials as rotating [`Kinematics::jv`] and [`Kinematics::jw`], built without them.
    ///
    /// Column `j ≤ i` is `rate_j · a_j × (c_i − p_j)` for a revolute joint (`rate_j · a_j` for a
    /// prismatic one; its `J_ω` column is `rate_j · a_j` or zero), where `a_j` is joint `j`'s axis,
    /// `p_j` a point on it and `c_i` the centre of mass, all in frame `i`. Walking from link `i` back to
    /// the base with `Q_{m−1} = Q_m (R_{m−1}^m)ᵀ` (frame `m − 1`'s axes seen from frame `i`) and
    /// `u_{m−1} = u_m − Q_{m−1} o_m` (its origin), column `j` holds only the angles `q_j … q_i`: the
    /// world-frame columns hold every angle from `q_1` on, and the dot products of the inertia matrix
    /// cancel them again, which is where an inertia matrix built from them spends its time.
    pub fn local_jacobians(&self, i: usize, com: &Vec3<Poly>) -> (Columns, Columns) {
        let n = self.joints.len();
        // q[m], u[m] for m = 0..=i+1 (frame m of the book; frame i + 1 is link i's own).
        let last = i + 1;
        let mut q = vec![Mat3::identity(); last + 1];
        let mut u = vec![Vec3::zero(); last + 1];
        for m in (1..=last).rev() {
            let jf = &self.joints[m - 1];
            q[m - 1] = q[m].mul(&jf.rot.transpose());
            u[m - 1] = u[m].sub(&q[m - 1].mul_vec(&jf.origin));
        }
        let mut jv = vec![Vec3::zero(); n];
        let mut jw = vec![Vec3::zero(); n];
        for j in 1..=last {
            let jf = &self.joints[j - 1];
            let axis = q[j].mul_vec(&jf.axis_local).scale(&jf.rate);
            match jf.kind {
                JointKind::Prismatic => jv[j - 1] = axis,
                JointKind::Revolute => {
                    let point = q[j - 1].mul_vec(&jf.joint_point).add(&u[j - 1]);
                    jv[j - 1] = axis.cross(&com.sub(&point));
                    jw[j - 1] = axis;
                }
            }
        }
        (jv, jw)
    }

    /// The homogeneous transform `T_0^i` as a 4×4 matrix of expressions (`i = 0..=n`).
    pub fn transform(&self, i: usize) -> Vec<Vec<Expr>> {
        let r = &self.rot0[i];
        let o = &self.origin0[i];
        let mut rows: Vec<Vec<Expr>> = (0..3)
            .map(|k| {
                let mut row: Vec<Expr> = (0..3).map(|l| r.0[k][l].to_expr()).collect();
                row.push(o.0[k].to_expr());
                row
            })
            .collect();
        rows.push(vec![Expr::zero(), Expr::zero(), Expr::zero(), Expr::one()]);
        rows
    }
}

/// A 3×n matrix from its columns, as polynomials.
pub fn columns_to_poly_rows(cols: &[Vec3<Poly>]) -> Vec<Vec<Poly>> {
    (0..3)
        .map(|k| cols.iter().map(|c| c.0[k].clone()).collect())
        .collect()
}

/// A 3×n matrix from its columns, as expressions.
pub fn columns_to_rows(cols: &[Vec3<Poly>]) -> Vec<Vec<Expr>> {
    (0..3)
        .map(|k| cols.iter().map(|c| c.0[k].to_expr()).collect())
        .collect()
}

/// A 3×3 matrix as rows of expressions.
pub fn mat_to_rows(m: &Mat3<Poly>) -> Vec<Vec<Expr>> {
    m.0.iter()
        .map(|r| r.iter().map(Poly::to_expr).collect())
        .collect()
}
