//! General joint placements: a joint placed as URDF places it, not by a DH row.
//!
//! Joint `i`'s frame, before its motion, sits at a fixed transform from its parent link's frame
//! `i − 1`: a translation `xyz`, then a rotation `R = Rz(yaw) Ry(pitch) Rx(roll)` (URDF's `rpy`,
//! fixed axes x, then y, then z). The joint then turns by `θ_i` about, or slides by `d_i` along, its
//! `axis` `u` (an exact unit vector in that frame), and link frame `i` is where the motion leaves it:
//!
//! ```text
//! T_{i−1}^i = Trans(xyz) · Rot(rpy) · Rot(u, θ_i) · Trans(u d_i)
//! ```
//!
//! so `R_{i−1}^i = R · Rot(u, θ_i)` (Rodrigues: `Rot(u, θ) = cos θ I + sin θ [u]× + (1 − cos θ) u uᵀ`),
//! `o_i = xyz + R u d_i`, the joint axis passes through `xyz` and is `u` in frame `i` (a rotation about
//! `u` leaves `u` fixed). A placement joint keeps its motion in the DH fields `θ` and `d` of its
//! [`Joint`](super::Joint) (`θ = q_i` for a revolute joint, `d = q_i` for a prismatic one) with
//! `a = α = 0`, so everything downstream of [`JointFrame`] (both dynamics methods, the compact forms,
//! code generation) reads placement and DH joints alike.

use super::kinematics::JointFrame;
use super::model::{Convention, JointKind, Robot};
use super::vec3::{Mat3, Vec3};
use crate::algebra::{to_poly, Expr, Poly, Rational};
use thiserror::Error;

/// Where a joint sits in its parent link's frame and what it moves about or along.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The translation from the parent link's origin, in the parent link's frame (length).
    pub xyz: [Expr; 3],
    /// Roll, pitch and yaw (radians): `R = Rz(yaw) Ry(pitch) Rx(roll)`.
    pub rpy: [Expr; 3],
    /// The joint axis, an exact unit vector of rational entries, in the frame after `xyz` and `rpy`.
    pub axis: [Expr; 3],
    /// Fixed origins that come first, outermost first: URDF fixed joints merged away between the
    /// previous moving joint (or the base) and this one. Empty in a scene.
    pub before: Vec<Origin>,
}

/// A fixed transform `Trans(xyz) Rot(rpy)`, as URDF's `<origin>` states it.
#[derive(Clone, Debug, PartialEq)]
pub struct Origin {
    /// The translation (length).
    pub xyz: [Expr; 3],
    /// Roll, pitch and yaw (radians): `R = Rz(yaw) Ry(pitch) Rx(roll)`.
    pub rpy: [Expr; 3],
}

impl Origin {
    /// No translation, no rotation.
    pub fn identity() -> Origin {
        Origin {
            xyz: zero3(),
            rpy: zero3(),
        }
    }

    /// Its rotation and translation, exactly.
    pub fn transform(&self) -> ([[Expr; 3]; 3], [Expr; 3]) {
        (rpy_matrix(&self.rpy), self.xyz.clone())
    }
}

fn zero3() -> [Expr; 3] {
    [Expr::zero(), Expr::zero(), Expr::zero()]
}

/// `(R_a R_b, p_a + R_a p_b)`: the transform `b` within the transform `a`.
pub fn compose(
    a: &([[Expr; 3]; 3], [Expr; 3]),
    b: &([[Expr; 3]; 3], [Expr; 3]),
) -> ([[Expr; 3]; 3], [Expr; 3]) {
    let r = std::array::from_fn(|i| {
        std::array::from_fn(|j| Expr::sum((0..3).map(|k| &a.0[i][k] * &b.0[k][j])))
    });
    let rp = mat_vec(&a.0, &b.1);
    (r, std::array::from_fn(|k| &a.1[k] + &rp[k]))
}

impl Placement {
    /// At the parent's origin, unrotated, about `z`.
    pub fn about_z() -> Placement {
        Placement {
            xyz: zero3(),
            rpy: zero3(),
            axis: [Expr::zero(), Expr::zero(), Expr::one()],
            before: Vec::new(),
        }
    }

    /// The origins in order: [`Placement::before`], then the joint's own.
    pub fn origins(&self) -> impl Iterator<Item = Origin> + '_ {
        self.before.iter().cloned().chain(std::iter::once(Origin {
            xyz: self.xyz.clone(),
            rpy: self.rpy.clone(),
        }))
    }

    /// The whole fixed part, `(R, p)`: every origin composed, exactly.
    pub fn fixed_transform(&self) -> ([[Expr; 3]; 3], [Expr; 3]) {
        let identity = Origin::identity().transform();
        self.origins()
            .fold(identity, |acc, o| compose(&acc, &o.transform()))
    }
}

/// What is wrong with an axis.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum AxisError {
    /// The zero vector has no direction.
    #[error(
        "the axis [{0}] is the zero vector: a joint axis needs a direction, such as [0, 0, 1]"
    )]
    Zero(String),
    /// An entry is not a number.
    #[error("the axis [{0}] must hold numbers (such as [0, 0, 1] or [0, 3, 4])")]
    NotNumeric(String),
    /// A vector of rational length that is not normalised (in a model built by hand; the parsers
    /// normalise it).
    #[error("the axis [{0}] is not a unit vector: divide it by its length")]
    NotUnit(String),
    /// The length is irrational, so no exact unit vector has this direction with rational entries.
    #[error("the axis [{written}] has length sqrt({norm2}), which is not a rational number, so it cannot be normalised exactly: give a unit vector with rational entries (such as [0, 3/5, 4/5]), or one whose length is rational")]
    Irrational {
        /// The axis as written.
        written: String,
        /// Its squared length.
        norm2: String,
    },
}

fn written(v: &[Expr; 3]) -> String {
    v.iter().map(Expr::to_string).collect::<Vec<_>>().join(", ")
}

/// The unit vector along `v`, exactly: `[0, 0, -1]` stays, `[0, 3, 4]` becomes `[0, 3/5, 4/5]`; a
/// vector whose length is irrational (`[1, 1, 0]`) is refused.
pub fn normalise_axis(v: &[Expr; 3]) -> Result<[Expr; 3], AxisError> {
    let mut r = Vec::with_capacity(3);
    for e in v {
        match e.as_rational() {
            Some(x) => r.push(x.clone()),
            None => return Err(AxisError::NotNumeric(written(v))),
        }
    }
    let norm2 = r.iter().fold(Rational::zero(), |acc, x| &acc + &(x * x));
    if norm2.is_zero() {
        return Err(AxisError::Zero(written(v)));
    }
    let Some(norm) = norm2.sqrt_exact() else {
        return Err(AxisError::Irrational {
            written: written(v),
            norm2: norm2.to_string(),
        });
    };
    let inv = norm.recip().expect("a non-zero length");
    Ok(std::array::from_fn(|k| Expr::num(&r[k] * &inv)))
}

/// Whether `v` is a unit vector of rational numbers.
pub fn is_unit_axis(v: &[Expr; 3]) -> bool {
    v.iter().all(|e| e.as_rational().is_some()) && normalise_axis(v).is_ok_and(|u| u == *v)
}

/// `Rz(yaw) Ry(pitch) Rx(roll)` as exact expressions (row-major).
pub fn rpy_matrix(rpy: &[Expr; 3]) -> [[Expr; 3]; 3] {
    let (cr, sr) = (Expr::cos(&rpy[0]), Expr::sin(&rpy[0]));
    let (cp, sp) = (Expr::cos(&rpy[1]), Expr::sin(&rpy[1]));
    let (cy, sy) = (Expr::cos(&rpy[2]), Expr::sin(&rpy[2]));
    [
        [
            &cy * &cp,
            &(&(&cy * &sp) * &sr) - &(&sy * &cr),
            &(&(&cy * &sp) * &cr) + &(&sy * &sr),
        ],
        [
            &sy * &cp,
            &(&(&sy * &sp) * &sr) + &(&cy * &cr),
            &(&(&sy * &sp) * &cr) - &(&cy * &sr),
        ],
        [-&sp, &cp * &sr, &cp * &cr],
    ]
}

/// `Rot(u, θ)` from `cos θ`, `sin θ` (Rodrigues), for a unit `u`.
fn rotation_about(u: &Vec3<Poly>, c: &Poly, s: &Poly) -> Mat3<Poly> {
    let one_c = Poly::one().sub(c);
    let cross = [
        [Poly::zero(), u.0[2].neg(), u.0[1].clone()],
        [u.0[2].clone(), Poly::zero(), u.0[0].neg()],
        [u.0[1].neg(), u.0[0].clone(), Poly::zero()],
    ];
    Mat3(std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            let diag = if a == b { c.clone() } else { Poly::zero() };
            diag.add(&s.mul(&cross[a][b]))
                .add(&one_c.mul(&u.0[a].mul(&u.0[b])))
        })
    }))
}

/// Joint `i`'s local geometry from its placement and its motion `θ`, `d` (see the [module
/// docs](self)); `rate` is `∂θ/∂q_i` or `∂d/∂q_i`.
pub(crate) fn joint_frame(
    kind: JointKind,
    placement: &Placement,
    theta: &Expr,
    d: &Expr,
    rate: Poly,
) -> JointFrame {
    let p = |e: &Expr| to_poly(e);
    let (fixed, xyz) = placement.fixed_transform();
    let fixed = Mat3(std::array::from_fn(|r| {
        std::array::from_fn(|c| p(&fixed[r][c]))
    }));
    let u = Vec3(std::array::from_fn(|k| p(&placement.axis[k])));
    let xyz = Vec3(std::array::from_fn(|k| p(&xyz[k])));
    let turn = if theta.is_zero() {
        Mat3::identity()
    } else {
        rotation_about(&u, &p(&Expr::cos(theta)), &p(&Expr::sin(theta)))
    };
    let slide = fixed.mul_vec(&u).scale(&p(d));
    JointFrame {
        kind,
        rot: fixed.mul(&turn),
        origin: xyz.add(&slide),
        joint_point: xyz,
        axis_local: u,
        rate,
    }
}

/// The same robot with every joint placed ([`Convention::Placement`]): DH is one way of stating
/// placements. A modified-DH row `(α_{i−1}, a_{i−1}, d_i, θ_i)` is the placement `xyz = [a_{i−1}, 0,
/// 0]`, `rpy = [α_{i−1}, 0, 0]`, `axis = z` with the same `θ_i`, `d_i` and link data. A standard-DH row
/// puts its `Trans(x,a_i) Rot(x,α_i)` after the joint, so it becomes the placement of joint `i + 1`,
/// and link `i`'s data moves into the frame before it: `c' = [a_i, 0, 0] + Rx(α_i) c`,
/// `I' = Rx(α_i) I Rx(α_i)ᵀ`.
pub fn from_dh(robot: &Robot) -> Robot {
    let zero = Expr::zero;
    let place = |a: &Expr, alpha: &Expr| Placement {
        xyz: [a.clone(), zero(), zero()],
        rpy: [alpha.clone(), zero(), zero()],
        axis: [zero(), zero(), Expr::one()],
        before: Vec::new(),
    };
    let mut out = robot.clone();
    out.convention = Convention::Placement;
    match robot.convention {
        Convention::Placement => return out,
        Convention::Modified => {
            for j in &mut out.joints {
                j.placement = Some(place(&j.a, &j.alpha));
                j.a = zero();
                j.alpha = zero();
            }
        }
        Convention::Standard => {
            let (mut a_prev, mut alpha_prev) = (zero(), zero());
            for (j, l) in out.joints.iter_mut().zip(out.links.iter_mut()) {
                j.placement = Some(place(&a_prev, &alpha_prev));
                let r = rpy_matrix(&[j.alpha.clone(), zero(), zero()]);
                let rc = mat_vec(&r, &l.com);
                l.com = [&j.a + &rc[0], rc[1].clone(), rc[2].clone()];
                l.inertia = l.inertia.as_ref().map(|t| rotate_tensor(&r, t));
                a_prev = std::mem::replace(&mut j.a, zero());
                alpha_prev = std::mem::replace(&mut j.alpha, zero());
            }
            // The payload is given in DH frame n, as link n's data is: move it the same way.
            if let Some(l) = &mut out.payload {
                let r = rpy_matrix(&[alpha_prev.clone(), zero(), zero()]);
                let rc = mat_vec(&r, &l.com);
                l.com = [&a_prev + &rc[0], rc[1].clone(), rc[2].clone()];
                l.inertia = l.inertia.as_ref().map(|t| rotate_tensor(&r, t));
            }
        }
    }
    out
}

/// `R v`, exactly.
pub fn mat_vec(r: &[[Expr; 3]; 3], v: &[Expr; 3]) -> [Expr; 3] {
    std::array::from_fn(|a| Expr::sum((0..3).map(|b| &r[a][b] * &v[b])))
}

/// `R I Rᵀ`, exactly: a tensor given in a frame rotated by `R`, in the outer frame.
pub fn rotate_tensor(r: &[[Expr; 3]; 3], t: &[[Expr; 3]; 3]) -> [[Expr; 3]; 3] {
    std::array::from_fn(|a| {
        std::array::from_fn(|b| {
            Expr::sum((0..3).flat_map(|k| (0..3).map(move |l| &(&r[a][k] * &t[k][l]) * &r[b][l])))
        })
    })
}

/// `R = Rz(yaw) Ry(pitch) Rx(roll)` in `f64`, for the numeric cross-check.
pub fn rpy_matrix_f64(roll: f64, pitch: f64, yaw: f64) -> nalgebra::Matrix3<f64> {
    let (cr, sr) = (roll.cos(), roll.sin());
    let (cp, sp) = (pitch.cos(), pitch.sin());
    let (cy, sy) = (yaw.cos(), yaw.sin());
    nalgebra::Matrix3::new(
        cy * cp,
        cy * sp * sr - sy * cr,
        cy * sp * cr + sy * sr,
        sy * cp,
        sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr,
        -sp,
        cp * sr,
        cp * cr,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(a: i64, b: i64, c: i64) -> [Expr; 3] {
        [Expr::int(a), Expr::int(b), Expr::int(c)]
    }

    #[test]
    fn axes_normalise_exactly_or_are_refused() {
        assert_eq!(normalise_axis(&v(0, 0, -1)).unwrap(), v(0, 0, -1));
        let u = normalise_axis(&v(0, 3, 4)).unwrap();
        assert_eq!(u[1], Expr::frac(3, 5).unwrap());
        assert_eq!(u[2], Expr::frac(4, 5).unwrap());
        assert!(matches!(
            normalise_axis(&v(1, 1, 0)),
            Err(AxisError::Irrational { .. })
        ));
        assert!(matches!(
            normalise_axis(&v(0, 0, 0)),
            Err(AxisError::Zero(_))
        ));
        assert!(is_unit_axis(&v(0, -1, 0)));
        assert!(!is_unit_axis(&v(0, 2, 0)));
    }

    #[test]
    fn rpy_of_a_quarter_turn_about_x_is_exact() {
        let half_pi = Expr::pi().scale(&Rational::new(1, 2).unwrap());
        let r = rpy_matrix(&[half_pi, Expr::zero(), Expr::zero()]);
        assert_eq!(r[1][2], Expr::int(-1));
        assert_eq!(r[2][1], Expr::int(1));
        assert_eq!(r[1][1], Expr::zero());
    }
}
