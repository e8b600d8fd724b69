//! An independent numeric inverse dynamics in `f64` with nalgebra, straight from the scene.
//!
//! It shares no code with the symbolic derivations: it evaluates the DH entries to numbers and runs
//! Craig's outward/inward Newton–Euler iterations (*Introduction to Robotics*, §6.5) on *joint frames*
//! (the frame in which joint `i` rotates about or slides along its own z axis), with gravity entered
//! as an upward acceleration of the base. A standard-DH row becomes a joint frame followed by the fixed
//! `Trans(x,a) Rot(x,α)`; a modified-DH row is a fixed `Rot(x,α) Trans(x,a)` followed by the joint; a
//! placed joint (URDF) is a fixed `Trans(xyz) Rot(rpy)` followed by the joint about its own axis
//! (nalgebra's axis-angle rotation, not the symbolic Rodrigues matrix). A payload is merged into the
//! last link here, as one rigid body (total mass, the mass-weighted centre of mass, and the
//! parallel-axis theorem for the inertia), where the symbolic methods keep it a second body. The tests
//! hold the symbolic results to it.

use super::model::{Convention, JointKind, Robot};
use super::placement::rpy_matrix_f64;
use crate::algebra::{diff, eval_f64, EvalError, Expr, Symbol};
use nalgebra::{Matrix3, Rotation3, Unit, Vector3};
use std::collections::HashMap;
use thiserror::Error;

/// Why the numeric inverse dynamics has no answer.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum NumericError {
    /// A parameter without a value, or an algebraic failure in a DH entry.
    #[error(transparent)]
    Eval(#[from] EvalError),
    /// A state vector with the wrong number of entries.
    #[error("{what} has {got} entries, the robot has {expected} joints")]
    StateLength {
        /// `q`, `q̇` or `q̈`.
        what: &'static str,
        /// The number of joints.
        expected: usize,
        /// The number of entries given.
        got: usize,
    },
}

fn rot_x(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

fn rot_z(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// One rigid body of two, each `(mass, centre of mass, inertia about it)` in the same frame: the masses
/// add, the centre of mass is their weighted mean, and each inertia moves to it by the parallel-axis
/// theorem, `I + m (|d|² 1 − d dᵀ)`.
fn merge(
    a: (f64, Vector3<f64>, Matrix3<f64>),
    b: (f64, Vector3<f64>, Matrix3<f64>),
) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let m = a.0 + b.0;
    if m == 0.0 {
        return (0.0, a.1, a.2 + b.2);
    }
    let c = (a.1 * a.0 + b.1 * b.0) / m;
    let shift = |(mi, ci, ii): (f64, Vector3<f64>, Matrix3<f64>)| {
        let d = ci - c;
        ii + (Matrix3::identity() * d.dot(&d) - d * d.transpose()) * mi
    };
    (m, c, shift(a) + shift(b))
}

/// `τ = ID(q, q̇, q̈)` for the robot with the parameters valued by `params`.
pub fn inverse_dynamics(
    robot: &Robot,
    params: &HashMap<Symbol, f64>,
    q: &[f64],
    qd: &[f64],
    qdd: &[f64],
) -> Result<Vec<f64>, NumericError> {
    let n = robot.dof();
    for (what, v) in [("q", q), ("q̇", qd), ("q̈", qdd)] {
        if v.len() != n {
            return Err(NumericError::StateLength {
                what,
                expected: n,
                got: v.len(),
            });
        }
    }
    let mut vals = params.clone();
    for i in 0..n {
        vals.insert(Symbol::q(i as u32 + 1), q[i]);
    }
    let ev = |e: &Expr| eval_f64(e, &vals);
    let vec3 = |e: &[Expr; 3]| -> Result<Vector3<f64>, EvalError> {
        Ok(Vector3::new(ev(&e[0])?, ev(&e[1])?, ev(&e[2])?))
    };
    // Per joint frame: fixed rotation/translation from the previous joint frame's *body* attachment,
    // the joint motion, then the fixed part after the joint.
    struct J {
        revolute: bool,
        axis: Vector3<f64>, // the joint axis in joint frame i
        r: Matrix3<f64>,    // R_{i-1}^{i} between joint frames
        p: Vector3<f64>,    // origin of joint frame i in joint frame i-1
        pc: Vector3<f64>,   // centre of mass in joint frame i
        inertia: Matrix3<f64>,
        mass: f64,
        rate: f64,
    }
    let mut joints: Vec<J> = Vec::with_capacity(n);
    // After-joint fixed transform of the previous joint (standard DH), applied before the next joint.
    let (mut post_r, mut post_p) = (Matrix3::identity(), Vector3::zeros());
    for (i, j) in robot.joints.iter().enumerate() {
        let qi = Symbol::q(i as u32 + 1);
        let (a, alpha, d, theta) = (ev(&j.a)?, ev(&j.alpha)?, ev(&j.d)?, ev(&j.theta)?);
        let var = match j.kind {
            JointKind::Revolute => &j.theta,
            JointKind::Prismatic => &j.d,
        };
        let rate = eval_f64(&diff(var, &qi), &vals)?;
        let (mut joint_r, mut joint_p, mut axis) =
            (rot_z(theta), Vector3::new(0.0, 0.0, d), Vector3::z());
        let body = |link: &crate::dynamics::Link| -> Result<_, EvalError> {
            let inertia = match &link.inertia {
                Some(t) => Matrix3::from_fn(|r, c| ev(&t[r][c]).unwrap_or(f64::NAN)),
                None => Matrix3::zeros(),
            };
            if inertia.iter().any(|x| x.is_nan()) {
                // Surface the missing symbols with the proper error.
                for e in link.inertia.iter().flatten().flatten() {
                    ev(e)?;
                }
            }
            Ok((ev(&link.mass)?, vec3(&link.com)?, inertia))
        };
        let (mut mass, mut com, mut inertia) = body(&robot.links[i])?;
        if let Some(l) = robot.payload.as_ref().filter(|_| i + 1 == n) {
            (mass, com, inertia) = merge((mass, com, inertia), body(l)?);
        }
        let (pre_r, pre_p, after_r, after_p) = match (&j.placement, robot.convention) {
            (Some(pl), _) => {
                let u = vec3(&pl.axis)?;
                joint_r = *Rotation3::from_axis_angle(&Unit::new_normalize(u), theta).matrix();
                joint_p = u * d;
                axis = u;
                let (mut fr, mut fp) = (post_r, post_p);
                for o in pl.origins() {
                    let [roll, pitch, yaw] = [ev(&o.rpy[0])?, ev(&o.rpy[1])?, ev(&o.rpy[2])?];
                    fp += fr * vec3(&o.xyz)?;
                    fr *= rpy_matrix_f64(roll, pitch, yaw);
                }
                (fr, fp, Matrix3::identity(), Vector3::zeros())
            }
            (None, Convention::Placement) => {
                (post_r, post_p, Matrix3::identity(), Vector3::zeros())
            }
            (None, Convention::Standard) => {
                (post_r, post_p, rot_x(alpha), Vector3::new(a, 0.0, 0.0))
            }
            (None, Convention::Modified) => {
                let fr = post_r * rot_x(alpha);
                let fp = post_p + post_r * Vector3::new(a, 0.0, 0.0);
                (fr, fp, Matrix3::identity(), Vector3::zeros())
            }
        };
        // Joint frame i = pre ∘ Rot(axis,θ) Trans(axis,d), measured from joint frame i−1.
        let r = pre_r * joint_r;
        let p = pre_p + pre_r * joint_p;
        // Body frame i = joint frame i ∘ after: express the link's data in the joint frame.
        let pc = after_p + after_r * com;
        let inertia_j = after_r * inertia * after_r.transpose();
        joints.push(J {
            revolute: j.kind == JointKind::Revolute,
            axis,
            r,
            p,
            pc,
            inertia: inertia_j,
            mass,
            rate,
        });
        post_r = after_r;
        post_p = after_p;
    }
    let g0 = vec3(&robot.gravity)?;
    let (mut w, mut wd, mut vd) = (Vector3::zeros(), Vector3::zeros(), -g0);
    let mut forces = Vec::with_capacity(n);
    let mut torques = Vec::with_capacity(n);
    for (i, j) in joints.iter().enumerate() {
        let z = j.axis;
        let rt = j.r.transpose();
        let (rate_d, rate_dd) = (qd[i] * j.rate, qdd[i] * j.rate);
        let vd_new;
        let (w_new, wd_new);
        if j.revolute {
            w_new = rt * w + z * rate_d;
            wd_new = rt * wd + (rt * w).cross(&(z * rate_d)) + z * rate_dd;
            vd_new = rt * (wd.cross(&j.p) + w.cross(&w.cross(&j.p)) + vd);
        } else {
            w_new = rt * w;
            wd_new = rt * wd;
            vd_new = rt * (wd.cross(&j.p) + w.cross(&w.cross(&j.p)) + vd)
                + (w_new * 2.0).cross(&(z * rate_d))
                + z * rate_dd;
        }
        let vdc = wd_new.cross(&j.pc) + w_new.cross(&w_new.cross(&j.pc)) + vd_new;
        forces.push(vdc * j.mass);
        torques.push(j.inertia * wd_new + w_new.cross(&(j.inertia * w_new)));
        w = w_new;
        wd = wd_new;
        vd = vd_new;
    }
    let mut tau = vec![0.0; n];
    let (mut f_next, mut n_next) = (Vector3::zeros(), Vector3::zeros());
    for i in (0..n).rev() {
        let j = &joints[i];
        let (r_next, p_next) = match joints.get(i + 1) {
            Some(nx) => (nx.r, nx.p),
            None => (Matrix3::identity(), Vector3::zeros()),
        };
        let f = r_next * f_next + forces[i];
        let m = torques[i]
            + r_next * n_next
            + j.pc.cross(&forces[i])
            + p_next.cross(&(r_next * f_next));
        tau[i] = if j.revolute {
            m.dot(&j.axis)
        } else {
            f.dot(&j.axis)
        } * j.rate;
        f_next = f;
        n_next = m;
    }
    // The drives (Spong §7.5): r² J_m q̈_i + B q̇_i.
    for (i, t) in tau.iter_mut().enumerate() {
        let d = robot.drive(i + 1);
        if !d.is_none() {
            let sign = crate::algebra::eval::sign(qd[i]);
            *t += ev(&d.rotor)? * qdd[i] + ev(&d.viscous)? * qd[i] + ev(&d.coulomb)? * sign;
        }
    }
    Ok(tau)
}
