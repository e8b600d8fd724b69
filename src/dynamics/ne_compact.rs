//! The compact ("customised symbolic") Newton–Euler: the recursion of [`super::newton_euler`] in
//! body-fixed frames, whose result is a *program* of named intermediate variables rather than one
//! expanded polynomial per joint (the form of Khalil and Kleinfinger's customised Newton–Euler, as in
//! OpenSYMORO).
//!
//! Each line of the program is `name = value`, the value an exact canonical [`Poly`] in the scene's
//! symbols, `sin`/`cos` atoms and *earlier* names; the program ends with `τ_k`. The fully expanded `τ`
//! swells exponentially with the number of joints; every value here stays small, so the derivation
//! is linear in the number of joints.
//!
//! # Why a dedicated recursion
//! The generic recursion of [`super::newton_euler`] has no place where a quantity is complete, and
//! its inputs ([`super::ne_symbolic::steps`]) take gravity from `R_0^i`, the very product that swells.
//! So this file runs its own body-frame recursion over `Vec3<Poly>`/`Mat3<Poly>` (the same little
//! linear algebra), with the joint frames built locally from the DH row, and *names* each component of
//! each book quantity when it is complete:
//!
//! | name          | quantity (link `i`, component `k` = 1, 2, 3 for x, y, z)                     |
//! |---------------|-------------------------------------------------------------------------------|
//! | `w{i}_{k}`    | `ω_i`                                                                         |
//! | `wd{i}_{k}`   | `α_i = ω̇_i`                                                                   |
//! | `U{i}_{rc}`   | `U_i = S(α_i) + S(ω_i)²`, so that `α × r + ω × (ω × r) = U r`                 |
//! | `aj{i}_{k}`   | the acceleration where joint `i` acts, less `g_i` (with `2 ω × b ḋ + b d̈`)    |
//! | `ae{i}_{k}`   | `a_e,i − g_i` (only for `i < n`)                                              |
//! | `ac{i}_{k}`   | `a_c,i − g_i`                                                                 |
//! | `fc{i}_{k}`   | `R_i^{i+1} f_{i+1}`: the force of link `i + 1` in frame `i`                   |
//! | `f{i}_{k}`    | `f_i`                                                                         |
//! | `jw{i}_{k}`   | `I_i ω_i`                                                                     |
//! | `n{i}_{k}`    | `n_i`                                                                         |
//! | `tau{i}`      | `τ_i` (an output, always listed)                                              |
//! | `acL_{k}`     | `a_c,L − g_n`, the payload's centre of mass (with a payload)                  |
//! | `jwL_{k}`     | `I_L ω_n`, the payload's angular momentum (with a payload and its inertia)    |
//!
//! Gravity enters as an upward acceleration of the base, `a_e,0 = −g_0`, so every acceleration carries
//! `−g_i` and `f_i = R f_{i+1} + m_i (a_c,i − g_i)` needs no separate `g_i` (Luh, Walker and Paul).
//!
//! # Rules
//! - A value becomes a name only when it is non-trivial: `0`, a constant, an atom or `−atom` are
//!   propagated inline, so structural zeros (a zero axis component, a link that never rotates, the
//!   moments before the first revolute joint) vanish from the program.
//! - Names are hash-consed by canonical form: a value equal to an earlier one (or to its negative)
//!   reuses that name.
//! - A name that a scene symbol or input already uses gets a trailing `_`.
//! - Lines that no `τ_k` needs (the moment of link 1 about its x and y axes, …) are dropped at the end.
//!
//! Substituting the names back gives exactly `Derivation::newton_euler(Frame::Body).tau`
//! ([`CompactProgram::expand`]; the tests prove it with the exact zero test).

use super::compact::{arena_for, name_mat, name_vec, skew};
use super::kinematics::{joint_frame, JointFrame};
use super::model::{JointKind, ModelError, Robot};
use super::vec3::{Mat3, Vec3};
use crate::algebra::compact::{eval::eval, Compact};
use crate::algebra::{atom, to_poly, EvalError, Expr, Poly, Rational, Symbol};
use std::collections::HashMap;

/// One line of the program: `symbol = value`.
#[derive(Clone, Debug, PartialEq)]
pub struct Intermediate {
    /// The fresh parameter symbol that names the value (`w3_2`).
    pub symbol: Symbol,
    /// The value, in the scene's symbols and earlier names.
    pub value: Poly,
}

/// The compact Newton–Euler of a robot: intermediates in order, then `τ`.
#[derive(Clone, Debug, PartialEq)]
pub struct CompactProgram {
    /// The named intermediates, each defined from earlier ones only.
    pub intermediates: Vec<Intermediate>,
    /// `τ_k`, in the scene's symbols and the names (index `k − 1`).
    pub tau: Vec<Poly>,
}

/// Which joint rates the recursion keeps: all of them for `τ(q, q̇, q̈)`, no accelerations for
/// `h(q, q̇) = C(q, q̇) q̇ + g(q)`, neither for `g(q)`. A rate set to zero vanishes structurally.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// `q̇` and `q̈`.
    Full,
    /// `q̇` only: `h(q, q̇)`.
    NoAcceleration,
    /// Neither: `g(q)`.
    Static,
}

/// Arithmetic operations of a program or of expanded polynomials, counted term by term without
/// sharing: a sum of `t` terms costs `t − 1` additions (a subtraction counts as one), a monomial
/// `c x₁^e₁ ⋯ x_k^e_k` costs `Σ e − 1` multiplications plus one for a coefficient other than `±1`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Multiplications.
    pub mul: usize,
    /// Additions and subtractions.
    pub add: usize,
}

impl OpCount {
    /// The operations of one polynomial.
    pub fn of(p: &Poly) -> OpCount {
        let mut c = OpCount {
            mul: 0,
            add: p.len().saturating_sub(1),
        };
        for (m, coeff) in p.terms() {
            let degree: i32 = m.factors().iter().map(|&(_, e)| e.abs()).sum();
            c.mul += (degree.max(1) - 1) as usize;
            let unit = coeff.abs() == Rational::one();
            if !unit && degree > 0 {
                c.mul += 1;
            }
        }
        c
    }

    /// The operations of several polynomials.
    pub fn of_all<'a, I: IntoIterator<Item = &'a Poly>>(ps: I) -> OpCount {
        ps.into_iter().fold(OpCount::default(), |acc, p| {
            let c = OpCount::of(p);
            OpCount {
                mul: acc.mul + c.mul,
                add: acc.add + c.add,
            }
        })
    }
}

fn mat_add(a: &Mat3<Poly>, b: &Mat3<Poly>) -> Mat3<Poly> {
    Mat3(std::array::from_fn(|r| {
        std::array::from_fn(|c| a.0[r][c].add(&b.0[r][c]))
    }))
}

fn vec_of(e: &[Expr; 3]) -> Vec3<Poly> {
    Vec3(std::array::from_fn(|k| to_poly(&e[k])))
}

/// What the forward recursion knows of link `i` when it is done, in frame `i`.
#[derive(Clone, Debug)]
pub struct LinkMotion {
    /// `ω_i` (named `w{i}_k`).
    pub w: Vec3<Poly>,
    /// `α_i` (named `wd{i}_k`).
    pub wd: Vec3<Poly>,
    /// `U_i = S(α_i) + S(ω_i)²` (named `U{i}_rc`).
    pub u: Mat3<Poly>,
    /// The acceleration, less gravity, where joint `i` acts (named `aj{i}_k`).
    pub aj: Vec3<Poly>,
    /// `r_{J,i}`: from the joint point to `o_i`.
    pub r_jo: Vec3<Poly>,
}

impl LinkMotion {
    /// `a_e,i − g_i`: the acceleration of `o_i`, less gravity.
    pub fn origin_accel(&self) -> Vec3<Poly> {
        self.aj.add(&self.u.mul_vec(&self.r_jo))
    }
}

/// The forward recursion of the compact Newton–Euler, with gravity as an upward acceleration of the
/// base: `ω_i`, `α_i`, `U_i` and the joint point's acceleration named link by link into `arena`;
/// `done` is called for each link as soon as its motion is named (so what it names comes next in the
/// arena). The one forward pass of [`tau_into`] and of the regressor ([`crate::identify`]). Returns
/// which links rotate (some joint up to them is revolute) and the named `a_e,i − g_i` of every link
/// but the last (`ae{i}_k`).
pub fn forward(
    robot: &Robot,
    joints: &[JointFrame],
    arena: &mut Compact,
    motion: Motion,
    done: &mut dyn FnMut(&mut Compact, usize, &LinkMotion),
) -> (Vec<bool>, Vec<Vec3<Poly>>) {
    let n = joints.len();
    let two = Poly::int(2);
    let rate = |k: u32, order: u8| rate_of(motion, k, order);
    let (mut w_prev, mut wd_prev) = (Vec3::<Poly>::zero(), Vec3::<Poly>::zero());
    let mut ae_prev = vec_of(&robot.gravity).scale(&Poly::int(-1));
    let mut u_prev = Mat3::<Poly>::zero();
    let mut rotates = Vec::with_capacity(n);
    let mut origins = Vec::with_capacity(n);
    let mut any_revolute = false;
    for (idx, jf) in joints.iter().enumerate() {
        let i = idx + 1;
        any_revolute |= jf.kind == JointKind::Revolute;
        rotates.push(any_revolute);
        let rt = jf.rot.transpose();
        let (qd, qdd) = (
            jf.rate.mul(&rate(i as u32, 1)),
            jf.rate.mul(&rate(i as u32, 2)),
        );
        let w0 = rt.mul_vec(&w_prev);
        let wd0 = rt.mul_vec(&wd_prev);
        let (w, wd) = if jf.kind == JointKind::Revolute {
            let w = name_vec(arena, w0.add(&jf.axis_local.scale(&qd)), &format!("w{i}"));
            let wd = wd0
                .add(&jf.axis_local.scale(&qdd))
                .add(&w.cross(&jf.axis_local.scale(&qd)));
            (w, name_vec(arena, wd, &format!("wd{i}")))
        } else {
            (
                name_vec(arena, w0, &format!("w{i}")),
                name_vec(arena, wd0, &format!("wd{i}")),
            )
        };
        // The joint point's acceleration: a_e,i−1 + U_{i−1} s, rotated into frame i.
        let mut aj = if jf.joint_point.is_exact_zero() {
            rt.mul_vec(&ae_prev)
        } else {
            rt.mul_vec(&ae_prev.add(&u_prev.mul_vec(&jf.joint_point)))
        };
        if jf.kind != JointKind::Revolute {
            aj = aj
                .add(&w.cross(&jf.axis_local.scale(&qd)).scale(&two))
                .add(&jf.axis_local.scale(&qdd));
        }
        let aj = name_vec(arena, aj, &format!("aj{i}"));
        let s2 = skew(&w);
        let u = name_mat(arena, mat_add(&skew(&wd), &s2.mul(&s2)), &format!("U{i}"));
        let r_jo = rt.mul_vec(&jf.origin.sub(&jf.joint_point));
        let m = LinkMotion { w, wd, u, aj, r_jo };
        done(arena, idx, &m);
        // The next link needs a_e,i.
        if i < n {
            ae_prev = name_vec(arena, m.origin_accel(), &format!("ae{i}"));
            origins.push(ae_prev.clone());
        }
        w_prev = m.w;
        wd_prev = m.wd;
        u_prev = m.u;
    }
    (rotates, origins)
}

/// The joint rate `q̇_k` (order 1) or `q̈_k` (order 2) as `motion` keeps it (zero otherwise).
fn rate_of(motion: Motion, k: u32, order: u8) -> Poly {
    let keep = match motion {
        Motion::Full => true,
        Motion::NoAcceleration => order == 1,
        Motion::Static => false,
    };
    if keep {
        Poly::symbol(&Symbol::Coord { index: k, order })
    } else {
        Poly::zero()
    }
}

/// Runs the compact recursion of a validated robot into `arena` and returns `τ` (see the
/// [module docs](self)); `joints` are the robot's local joint frames.
pub fn tau_into(
    robot: &Robot,
    joints: &[JointFrame],
    arena: &mut Compact,
    motion: Motion,
) -> Vec<Poly> {
    let n = robot.dof();
    let rate = |k: u32, order: u8| rate_of(motion, k, order);

    // Forward: ω, α, U, the accelerations less gravity; a_c,i and a_e,i named as each link is done.
    let (mut omega, mut alpha, mut a_c) = (Vec::new(), Vec::new(), Vec::new());
    let mut a_payload = None;
    let (rotates, _) = forward(robot, joints, arena, motion, &mut |arena, idx, m| {
        let i = idx + 1;
        let link = &robot.links[idx];
        let r_jc = m.r_jo.add(&vec_of(&link.com));
        a_c.push(name_vec(
            arena,
            m.aj.add(&m.u.mul_vec(&r_jc)),
            &format!("ac{i}"),
        ));
        // (a_e,i for i < n is named by `forward` right after this.)
        if i == n {
            if let Some(l) = &robot.payload {
                let r_jl = m.r_jo.add(&vec_of(&l.com));
                a_payload = Some(name_vec(arena, m.aj.add(&m.u.mul_vec(&r_jl)), "acL"));
            }
        }
        omega.push(m.w.clone());
        alpha.push(m.wd.clone());
    });

    // Backward: f, n, τ.
    let mut tau = vec![Poly::zero(); n];
    let (mut f_next, mut n_next) = (Vec3::<Poly>::zero(), Vec3::<Poly>::zero());
    for idx in (0..n).rev() {
        let i = idx + 1;
        let jf = &joints[idx];
        let link = &robot.links[idx];
        let (f_here, n_here, s_next) = match joints.get(idx + 1) {
            Some(next) => (
                name_vec(arena, next.rot.mul_vec(&f_next), &format!("fc{i}")),
                next.rot.mul_vec(&n_next),
                next.joint_point.clone(),
            ),
            None => (Vec3::zero(), Vec3::zero(), Vec3::zero()),
        };
        let mass = to_poly(&link.mass);
        // The payload on the last link: its force m_L (a_c,L − g_n).
        let carried = robot
            .payload
            .as_ref()
            .zip(a_payload.as_ref())
            .filter(|_| idx + 1 == n)
            .map(|(l, a)| (l, a.scale(&to_poly(&l.mass))));
        let mut fi = f_here.add(&a_c[idx].scale(&mass));
        if let Some((_, force)) = &carried {
            fi = fi.add(force);
        }
        let fi = name_vec(arena, fi, &format!("f{i}"));
        let moment = if rotates[idx] {
            let com = vec_of(&link.com);
            let rt = jf.rot.transpose();
            let r_jc = rt.mul_vec(&jf.origin.sub(&jf.joint_point)).add(&com);
            let mut ni = n_here
                .sub(&fi.cross(&r_jc))
                .add(&f_here.cross(&com.sub(&s_next)));
            if let Some(t) = &link.inertia {
                let inertia = Mat3(std::array::from_fn(|r| {
                    std::array::from_fn(|c| to_poly(&t[r][c]))
                }));
                let jw = name_vec(arena, inertia.mul_vec(&omega[idx]), &format!("jw{i}"));
                ni = ni
                    .add(&inertia.mul_vec(&alpha[idx]))
                    .add(&omega[idx].cross(&jw));
            }
            if let Some((l, force)) = &carried {
                // f_i holds the payload's force, taken about c_i above: move it to c_L.
                ni = ni.add(&force.cross(&com.sub(&vec_of(&l.com))));
                if let Some(t) = &l.inertia {
                    let inertia = Mat3(std::array::from_fn(|r| {
                        std::array::from_fn(|c| to_poly(&t[r][c]))
                    }));
                    let jw = name_vec(arena, inertia.mul_vec(&omega[idx]), "jwL");
                    ni = ni
                        .add(&inertia.mul_vec(&alpha[idx]))
                        .add(&omega[idx].cross(&jw));
                }
            }
            let ni = name_vec(arena, ni, &format!("n{i}"));
            n_next = ni.clone();
            Some(ni)
        } else {
            None
        };
        tau[idx] = if jf.kind == JointKind::Revolute {
            moment.map_or_else(Poly::zero, |m| m.dot(&jf.axis_local))
        } else {
            fi.dot(&jf.axis_local)
        }
        .mul(&jf.rate);
        // The drive (Spong §7.5): r² J_m q̈_i + B q̇_i, with the motion's rates.
        let drive = robot.drive(idx + 1);
        let i = idx as u32 + 1;
        if !drive.rotor.is_zero() {
            tau[idx] = tau[idx].add(&to_poly(&drive.rotor).mul(&rate(i, 2)));
        }
        if motion != Motion::Static {
            tau[idx] = tau[idx].add(&drive.friction(i));
        }
        f_next = fi;
    }
    tau
}

impl CompactProgram {
    /// The compact Newton–Euler program of a robot, in body-fixed frames.
    pub fn derive(robot: &Robot) -> Result<CompactProgram, ModelError> {
        robot.validate()?;
        let joints: Vec<JointFrame> = (1..=robot.dof()).map(|i| joint_frame(robot, i)).collect();
        let mut arena = arena_for(robot);
        let tau = tau_into(robot, &joints, &mut arena, Motion::Full);
        Ok(CompactProgram::from_arena(&arena, tau))
    }

    /// The compact Newton–Euler program of a robot in the inertial frame: the recursion of
    /// [`super::newton_euler`] over named intermediates ([`super::compact::inertial`]).
    pub fn derive_inertial(robot: &Robot) -> Result<CompactProgram, ModelError> {
        robot.validate()?;
        let joints: Vec<JointFrame> = (1..=robot.dof()).map(|i| joint_frame(robot, i)).collect();
        let (arena, tau) = super::compact::inertial::tau(robot, &joints, arena_for(robot));
        Ok(CompactProgram::from_arena(&arena, tau))
    }

    /// The lines of `arena` that `tau` needs, in order, and `tau`.
    pub fn from_arena(arena: &Compact, tau: Vec<Poly>) -> CompactProgram {
        let intermediates = arena
            .live(tau.iter())
            .into_iter()
            .map(|k| {
                let d = &arena.defs()[k];
                Intermediate {
                    symbol: d.symbol.clone(),
                    value: d.value.clone(),
                }
            })
            .collect();
        CompactProgram { intermediates, tau }
    }

    /// The program's lines as an arena again (each line defined from the earlier ones).
    fn arena(&self) -> Compact {
        let mut arena = Compact::new();
        for line in &self.intermediates {
            arena.define(line.symbol.clone(), line.value.clone());
        }
        arena
    }

    /// `τ` with every name substituted back, recursively: the fully expanded Newton–Euler `τ`. Swells
    /// exponentially with the number of joints, as the expanded form does.
    pub fn expand(&self) -> Vec<Poly> {
        let arena = self.arena();
        let mut ex = arena.expander(usize::MAX);
        self.tau
            .iter()
            .map(|t| ex.expand(t).expect("no budget"))
            .collect()
    }

    /// `τ` in `f64`, evaluating the program line by line with the symbols valued by `values` (scene
    /// parameters and `q`, `q̇`, `q̈`).
    pub fn eval_f64(&self, values: &HashMap<Symbol, f64>) -> Result<Vec<f64>, EvalError> {
        let arena = self.arena();
        let outputs: Vec<&Poly> = self.tau.iter().collect();
        let mut missing = None;
        let got = eval(&arena, &outputs, &mut |id| {
            let v = leaf_f64(id, values);
            if v.is_none() && missing.is_none() {
                missing = Some(id);
            }
            v
        });
        got.map_err(|_| EvalError::Unbound(missing.and_then(atom::symbol_of).into_iter().collect()))
    }

    /// The operations of the program: every intermediate and every `τ_k`.
    pub fn op_count(&self) -> OpCount {
        OpCount::of_all(
            self.intermediates
                .iter()
                .map(|l| &l.value)
                .chain(self.tau.iter()),
        )
    }
}

/// The `f64` value of a leaf atom: a symbol from `values`, `sin`/`cos` of a valued symbol, π.
fn leaf_f64(id: atom::AtomId, values: &HashMap<Symbol, f64>) -> Option<f64> {
    use crate::algebra::atom::Class;
    match atom::class(id) {
        Class::Param | Class::Coord => values.get(&atom::symbol_of(id)?).copied(),
        Class::Sin | Class::Cos if atom::symbol_of(id).is_some() => {
            let x = values.get(&atom::symbol_of(id)?)?;
            Some(if atom::class(id) == Class::Sin {
                x.sin()
            } else {
                x.cos()
            })
        }
        _ => crate::algebra::eval_f64(&atom::to_expr(id), values).ok(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn operations_are_counted_term_by_term() {
        for (s, mul, add) in [
            ("x", 0, 0),
            ("-x + y", 0, 1),
            ("2*x^2*y + z - 3", 3, 2),
            ("x*sin(q1)*qd1", 2, 0),
        ] {
            assert_eq!(OpCount::of(&p(s)), OpCount { mul, add }, "{s}");
        }
    }
}
