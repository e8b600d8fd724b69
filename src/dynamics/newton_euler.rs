//! The recursive Newton–Euler formulation (Spong, Hutchinson and Vidyasagar, *Robot Modeling and
//! Control*, §7.5), generic over the scalar.
//!
//! Forward recursion, `i = 1..n`, with `ω_0 = α_0 = a_e,0 = 0` and every vector of step `i` in the
//! working frame of link `i` (frame `i` for the body-fixed variant, frame 0 for the inertial one):
//! - `ω_i = ω_{i−1} + b_i q̇_i` and `α_i = α_{i−1} + b_i q̈_i + ω_i × b_i q̇_i` for a revolute joint
//!   (`ω_i = ω_{i−1}`, `α_i = α_{i−1}` for a prismatic one), with `ω_{i−1}, α_{i−1}` rotated into the
//!   working frame and `b_i` the joint axis;
//! - `a_c,i = a_J + α_i × r_{J,ci} + ω_i × (ω_i × r_{J,ci})`, the same for `a_e,i` with `r_{J,i}`, plus
//!   `2 ω_i × b_i ḋ_i + b_i d̈_i` for a prismatic joint, where `J` is the point where joint `i` acts
//!   (`o_{i−1}` in standard DH, so `r_{J,ci} = r_{i−1,ci}` as in Spong) and
//!   `a_J = a_e,i−1 + α_{i−1} × s_i + ω_{i−1} × (ω_{i−1} × s_i)` with `s_i` from `o_{i−1}` to `J`;
//! - `g_i`: gravity in the working frame.
//!
//! Backward recursion, `i = n..1`, with `f_{n+1} = n_{n+1} = 0`:
//! - `f_i = R f_{i+1} + m_i (a_c,i − g_i)`;
//! - `n_i = R n_{i+1} − f_i × r_{J,ci} + (R f_{i+1}) × (r_{i,ci} − s_{i+1}) + I_i α_i + ω_i × (I_i ω_i)`;
//! - the actuated force or torque: `τ_i = f_iᵀ b_i` (prismatic) or `n_iᵀ b_i` (revolute).
//!
//! A payload (a second rigid body `L` fixed to the last link, [`Body`]) adds `m_L (a_c,L − g_n)` to
//! `f_n` and its moment about the joint point, `−m_L (a_c,L − g_n) × r_{J,cL} + I_L α_n + ω_n × (I_L ω_n)`,
//! to `n_n`, with `a_c,L` the acceleration of its centre of mass as for `a_c,n`.
//!
//! Moments are computed only from the first revolute joint on: before it, no joint needs them.

use super::scalar::Scalar;
use super::vec3::{Mat3, Vec3};

/// What step `i` of the recursion needs, everything in the working frame of link `i`.
#[derive(Clone, Debug)]
pub struct Step<S> {
    /// Whether the joint is revolute.
    pub revolute: bool,
    /// Rotates vectors of the previous working frame into this one (`R_{i−1}^iᵀ`, or the identity in
    /// the inertial frame).
    pub rot_in: Mat3<S>,
    /// The joint axis `b_i`.
    pub axis: Vec3<S>,
    /// `s_i`: from `o_{i−1}` to the joint point `J`.
    pub s: Vec3<S>,
    /// `r_{J,i}`: from the joint point to `o_i`.
    pub r_joint_origin: Vec3<S>,
    /// `r_{i,ci}`: from `o_i` to the centre of mass.
    pub r_origin_com: Vec3<S>,
    /// `m_i`.
    pub mass: S,
    /// `I_i` about the centre of mass, or `None` when it is not needed or not given.
    pub inertia: Option<Mat3<S>>,
    /// `g_i`.
    pub gravity: Vec3<S>,
    /// The joint rate (`q̇_i` times the joint's constant rate).
    pub qd: S,
    /// The joint acceleration.
    pub qdd: S,
    /// The joint's constant rate `∂θ_i/∂q_i` or `∂d_i/∂q_i`.
    pub rate: S,
    /// The drive's term `r² J_m q̈_i + B q̇_i` added to `τ_i` (Spong §7.5), `None` without a drive.
    pub drive: Option<S>,
    /// A second rigid body fixed to link `i` (the payload of the last link), `None`: none.
    pub payload: Option<Body<S>>,
}

/// A rigid body fixed to a link besides the link itself, in the link's working frame.
#[derive(Clone, Debug)]
pub struct Body<S> {
    /// `m_L`.
    pub mass: S,
    /// `r_{i,cL}`: from `o_i` to its centre of mass.
    pub r_origin_com: Vec3<S>,
    /// `I_L` about its centre of mass, or `None` when it is not needed or not given.
    pub inertia: Option<Mat3<S>>,
}

/// Which body of a link an Euler term is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// The link itself.
    Link,
    /// The payload fixed to it ([`Step::payload`]).
    Payload,
}

/// Every intermediate quantity of one Newton–Euler run, per link (index `i − 1`).
#[derive(Clone, Debug)]
pub struct NewtonEuler<S> {
    /// `ω_i`.
    pub omega: Vec<Vec3<S>>,
    /// `α_i`.
    pub alpha: Vec<Vec3<S>>,
    /// `a_c,i`.
    pub a_c: Vec<Vec3<S>>,
    /// `a_e,i`.
    pub a_e: Vec<Vec3<S>>,
    /// `g_i`.
    pub g: Vec<Vec3<S>>,
    /// `a_c,L`, the acceleration of the payload's centre of mass, when there is a payload.
    pub a_payload: Option<Vec3<S>>,
    /// `f_i`.
    pub f: Vec<Vec3<S>>,
    /// `n_i`, `None` where no revolute joint precedes and moments were not needed.
    pub n: Vec<Option<Vec3<S>>>,
    /// The actuated forces/torques `τ_i`.
    pub tau: Vec<S>,
}

/// Runs both recursions.
pub fn recurse<S: Scalar>(steps: &[Step<S>]) -> NewtonEuler<S> {
    run(steps, &book_euler(steps), Moment::Book, &|| false)
        .expect("a recursion never stopped runs to the end")
}

/// The Euler term with [`Step::inertia`] (or the payload's [`Body::inertia`]).
fn book_euler<'a, S: Scalar>(steps: &'a [Step<S>]) -> Box<EulerTerm<'a, S>> {
    Box::new(move |i, part, alpha, omega| {
        let inertia = match part {
            Part::Link => steps[i].inertia.as_ref()?,
            Part::Payload => steps[i].payload.as_ref()?.inertia.as_ref()?,
        };
        Some((inertia.mul_vec(alpha), omega.cross(&inertia.mul_vec(omega))))
    })
}

/// How the moment `n_i` is grouped.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Moment {
    /// As in the book: `n_{i+1} − f_i × r_{J,ci} + f_{i+1} × (r_{i,ci} − s_{i+1})` (rotated).
    Book,
    /// With `f_i = f_{i+1} + m_i (a_c,i − g_i)` substituted:
    /// `n_{i+1} − f_{i+1} × (r_{J,i} + s_{i+1}) − m_i (a_c,i − g_i) × r_{J,ci}`. The same value, with
    /// one cross product of the large accumulated force instead of two.
    Split,
}

/// The two parts `(I_i α_i, ω_i × (I_i ω_i))` of the Euler term of link `i` (0-based) or of its
/// payload, from `i`, the part, `α_i` and `ω_i`; `None` when the body has no inertia term.
pub type EulerTerm<'a, S> =
    dyn Fn(usize, Part, &Vec3<S>, &Vec3<S>) -> Option<(Vec3<S>, Vec3<S>)> + 'a;

/// Runs both recursions for exact scalars, with the Euler term of each link given by `euler` (`None`:
/// with [`Step::inertia`]), so a caller can evaluate it in whatever frame is cheapest. The moment is
/// grouped as `n_{i+1} − f_{i+1} × (r_{J,i} + s_{i+1}) − m_i (a_c,i − g_i) × r_{J,ci}` (all rotated
/// into frame `i`), the book's `n_i` with `f_i = f_{i+1} + m_i (a_c,i − g_i)` substituted: the same
/// polynomials as [`recurse`], with one cross product of the large accumulated force instead of two.
pub fn recurse_with<S: Scalar>(
    steps: &[Step<S>],
    euler: Option<&EulerTerm<'_, S>>,
) -> NewtonEuler<S> {
    recurse_until(steps, euler, &|| false).expect("a recursion never stopped runs to the end")
}

/// [`recurse_with`], given up (`None`) as soon as `stop` says so, asked before each link of either
/// recursion: for a thread that derives ahead what may turn out not to be needed.
pub fn recurse_until<S: Scalar>(
    steps: &[Step<S>],
    euler: Option<&EulerTerm<'_, S>>,
    stop: &dyn Fn() -> bool,
) -> Option<NewtonEuler<S>> {
    match euler {
        Some(e) => run(steps, e, Moment::Split, stop),
        None => run(steps, &book_euler(steps), Moment::Split, stop),
    }
}

/// Both recursions, `None` once `stop` says so (asked before each link; a closure that never
/// stops costs nothing once inlined).
fn run<S: Scalar, F: Fn() -> bool + ?Sized>(
    steps: &[Step<S>],
    euler: &EulerTerm<'_, S>,
    moment: Moment,
    stop: &F,
) -> Option<NewtonEuler<S>> {
    let n = steps.len();
    let (mut omega, mut alpha, mut a_c, mut a_e, mut g) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    let (mut w_prev, mut al_prev, mut ae_prev) =
        (Vec3::<S>::zero(), Vec3::<S>::zero(), Vec3::<S>::zero());
    let mut a_payload = None;
    let two = S::from_rational(&crate::algebra::Rational::int(2));
    for (idx, st) in steps.iter().enumerate() {
        if stop() {
            return None;
        }
        let i = idx + 1;
        let w0 = st.rot_in.mul_vec(&w_prev);
        let al0 = st.rot_in.mul_vec(&al_prev);
        let ae0 = st.rot_in.mul_vec(&ae_prev);
        let a_j = if st.s.is_exact_zero() {
            ae0
        } else {
            ae0.add(&al0.cross(&st.s)).add(&w0.cross(&w0.cross(&st.s)))
        };
        let (w, al) = if st.revolute {
            let w = w0.add(&st.axis.scale(&st.qd));
            let al = al0
                .add(&st.axis.scale(&st.qdd))
                .add(&w.cross(&st.axis.scale(&st.qd)));
            (w, al)
        } else {
            (w0, al0)
        };
        let w = S::label(w, &|| format!("w{i}"));
        let al = S::label(al, &|| format!("wd{i}"));
        let accel = |r: &Vec3<S>| {
            let mut a = a_j.add(&al.cross(r)).add(&w.cross(&w.cross(r)));
            if !st.revolute {
                a = a
                    .add(&w.cross(&st.axis.scale(&st.qd)).scale(&two))
                    .add(&st.axis.scale(&st.qdd));
            }
            a
        };
        let r_jc = st.r_joint_origin.add(&st.r_origin_com);
        a_c.push(S::label(accel(&r_jc), &|| format!("ac{i}")));
        if let Some(b) = &st.payload {
            let r_jl = st.r_joint_origin.add(&b.r_origin_com);
            a_payload = Some(S::label(accel(&r_jl), &|| "acL".to_string()));
        }
        let ae = S::label(accel(&st.r_joint_origin), &|| format!("ae{i}"));
        a_e.push(ae.clone());
        g.push(st.gravity.clone());
        w_prev = w.clone();
        al_prev = al.clone();
        ae_prev = ae;
        omega.push(w);
        alpha.push(al);
    }
    let first_revolute = steps.iter().position(|s| s.revolute);
    let mut f = vec![Vec3::zero(); n];
    let mut moments: Vec<Option<Vec3<S>>> = vec![None; n];
    let mut tau = vec![S::zero(); n];
    let zero = Vec3::<S>::zero();
    for i in (0..n).rev() {
        if stop() {
            return None;
        }
        let st = &steps[i];
        // Quantities of link i+1 rotated into the working frame of link i.
        // (f and the moments of link i+1 are read in place: no copy of the large accumulated
        // vectors; a link without a moment has none above it either, so its moment is zero.)
        let (f_here, n_here, s_next) = match steps.get(i + 1) {
            Some(next) => (
                next.rot_in.tr_mul_vec(&f[i + 1]),
                next.rot_in
                    .tr_mul_vec(moments[i + 1].as_ref().unwrap_or(&zero)),
                next.rot_in.tr_mul_vec(&next.s),
            ),
            None => (Vec3::zero(), Vec3::zero(), Vec3::zero()),
        };
        let own = a_c[i].sub(&g[i]).scale(&st.mass);
        // The payload's force m_L (a_c,L − g_i) and its lever from the joint point.
        let carried = st.payload.as_ref().zip(a_payload.as_ref()).map(|(b, a)| {
            let force = a.sub(&g[i]).scale(&b.mass);
            (force, st.r_joint_origin.add(&b.r_origin_com), b)
        });
        let fi = match &carried {
            Some((force, ..)) => f_here.add(&own).add(force),
            None => f_here.add(&own),
        };
        let fi = S::label(fi, &|| format!("f{}", i + 1));
        if first_revolute.is_some_and(|r| i >= r) {
            let r_jc = st.r_joint_origin.add(&st.r_origin_com);
            let mut ni = match moment {
                Moment::Book => n_here
                    .sub(&fi.cross(&r_jc))
                    .add(&f_here.cross(&st.r_origin_com.sub(&s_next))),
                Moment::Split => n_here
                    .sub(&f_here.cross(&st.r_joint_origin.add(&s_next)))
                    .sub(&own.cross(&r_jc)),
            };
            if let Some((i_alpha, gyro)) = euler(i, Part::Link, &alpha[i], &omega[i]) {
                ni = ni.add(&i_alpha).add(&gyro);
            }
            if let Some((force, r_jl, body)) = &carried {
                // Book: f_i already holds the payload's force, taken about c_i; move it to c_L.
                ni = match moment {
                    Moment::Book => ni.add(&force.cross(&st.r_origin_com.sub(&body.r_origin_com))),
                    Moment::Split => ni.sub(&force.cross(r_jl)),
                };
                if let Some((i_alpha, gyro)) = euler(i, Part::Payload, &alpha[i], &omega[i]) {
                    ni = ni.add(&i_alpha).add(&gyro);
                }
            }
            moments[i] = Some(S::label(ni, &|| format!("n{}", i + 1)));
        }
        tau[i] = if st.revolute {
            moments[i]
                .as_ref()
                .map_or_else(S::zero, |m| m.dot(&st.axis))
        } else {
            fi.dot(&st.axis)
        }
        .mul(&st.rate);
        if let Some(d) = &st.drive {
            tau[i] = tau[i].add(d);
        }
        f[i] = fi;
    }
    Some(NewtonEuler {
        omega,
        alpha,
        a_c,
        a_e,
        g,
        a_payload,
        f,
        n: moments,
        tau,
    })
}
