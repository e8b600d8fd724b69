//! The regressor `Y(q, q̇, q̈)` with `τ = Y π`, in compact form, and the proof of `Y π = τ`.
//!
//! τ is linear in the standard parameters π ([`super::standard`]). The forward pass of the body-frame
//! Newton–Euler recursion (ω_i, α_i, `U_i = S(α_i) + S(ω_i)²`, the acceleration `a_i` of the origin
//! `o_i` less gravity) does not depend on π. Each standard parameter of link `j` alone produces the
//! wrench about `o_j`, in frame `j` (Khalil and Dombre, *Modeling, Identification and Control of
//! Robots*, §9.3):
//!
//! - an inertia entry `J`: `F = 0`, `N = J α + ω × (J ω)`;
//! - a first moment `MS`: `F = U MS`, `N = MS × a`;
//! - the mass `M`: `F = a`, `N = 0`.
//!
//! Carried back frame by frame (`f' = R f`, `n' = R n + p × f'`), its projection on the axis of each
//! joint `i ≤ j` (the moment about the joint's point for a revolute joint, the force for a prismatic
//! one) is the entry `Y[i][(j, k)]`. A rotor inertia adds `q̈_j` to row `j` only. Every component is
//! named in one [`Compact`] arena, as the compact Newton–Euler names its own, so entries stay short.
//!
//! The scene's own π (parallel axes) then gives the claim `Σ_k Y_ik π_k = τ_i`, τ from the compact
//! Newton–Euler of [`crate::dynamics::ne_compact`] over the same arena: an independent recursion (it
//! works with the centre of mass and the inertia about it).

use super::error::IdentifyError;
use super::standard::{inertia_entry, scene_values, standard_params, Quantity, StandardParam};
use crate::algebra::compact::identity::{prove, Outcome, ProofOptions};
use crate::algebra::compact::Compact;
use crate::algebra::{Expr, Poly, Symbol};
use crate::dynamics::compact::{arena_for, name_vec};
use crate::dynamics::kinematics::{joint_frame, JointFrame};
use crate::dynamics::ne_compact::{self, tau_into, Motion};
use crate::dynamics::vec3::{Mat3, Vec3};
use crate::dynamics::{JointKind, Robot};

/// The names of the gravity components when gravity is an input (`--gravity-input`).
pub const GRAVITY_INPUT: [&str; 3] = ["gx", "gy", "gz"];

/// How gravity enters the regressor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gravity {
    /// The scene's gravity vector (usually fixed along the base's z axis).
    Scene,
    /// An input vector `[gx, gy, gz]` in frame 0, a variable like the state (generated regressor
    /// code that takes g as an argument): a larger count of base parameters.
    Input,
}

/// What the standard parameter vector holds beyond the ten inertial parameters per link.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RegressorOptions {
    /// Append each joint's rotor inertia `Iaj` after link `j`'s ten parameters (`τ_j += Ia_j q̈_j`).
    pub rotors: bool,
    /// How gravity enters.
    pub gravity: Gravity,
}

impl Default for RegressorOptions {
    fn default() -> RegressorOptions {
        RegressorOptions {
            rotors: false,
            gravity: Gravity::Scene,
        }
    }
}

impl RegressorOptions {
    /// With the rotor inertias (`with_rotors`), so the columns `Iaj` are appended.
    pub fn with_rotors(mut self, rotors: bool) -> RegressorOptions {
        self.rotors = rotors;
        self
    }

    /// With gravity as an input vector.
    pub fn with_gravity(mut self, gravity: Gravity) -> RegressorOptions {
        self.gravity = gravity;
        self
    }
}

/// The regressor of one robot: `τ = Y π` over one arena of named intermediates.
#[derive(Clone, Debug)]
pub struct Regressor {
    /// The robot's name.
    pub robot: String,
    /// The robot as used (with gravity replaced by `[gx, gy, gz]` for [`Gravity::Input`]).
    pub model: Robot,
    /// The options it was built with.
    pub options: RegressorOptions,
    /// The standard parameters, the columns of `Y`.
    pub params: Vec<StandardParam>,
    /// The named intermediates of `Y` and `τ`.
    pub arena: Compact,
    /// `Y`, `n` rows of one entry per standard parameter.
    pub y: Vec<Vec<Poly>>,
    /// The scene's τ by the compact Newton–Euler (plus `Ia_j q̈_j` with rotors), over the arena.
    pub tau: Vec<Poly>,
    /// The scene's values of π.
    pub pi: Vec<Poly>,
}

impl Regressor {
    /// Builds the regressor of a robot.
    pub fn build(robot: &Robot, options: RegressorOptions) -> Result<Regressor, IdentifyError> {
        robot.validate()?;
        let mut model = robot.clone();
        if options.gravity == Gravity::Input {
            let used: Vec<Symbol> = used_symbols(robot);
            for name in GRAVITY_INPUT {
                if used.contains(&Symbol::new(name)) {
                    return Err(IdentifyError::NameTaken(name.to_string()));
                }
            }
            model.gravity = GRAVITY_INPUT.map(Expr::symbol);
        }
        let n = model.dof();
        let joints: Vec<JointFrame> = (1..=n).map(|i| joint_frame(&model, i)).collect();
        let mut arena = arena_for(&model);
        let params = standard_params(&model, options.rotors);
        let y = columns(&model, &joints, &mut arena, &params);
        let mut tau = tau_into(&model, &joints, &mut arena, Motion::Full);
        if options.rotors {
            // τ holds the scene's rotors already; the others enter as the symbols Iaj.
            for (j, t) in tau.iter_mut().enumerate() {
                if !model.drive(j + 1).rotor.is_zero() {
                    continue;
                }
                let ia = StandardParam {
                    link: j + 1,
                    quantity: Quantity::Ia,
                };
                *t = t.add(
                    &Poly::symbol(&ia.symbol()).mul(&Poly::symbol(&Symbol::qdd(j as u32 + 1))),
                );
            }
        }
        let pi = scene_values(&model, &params);
        Ok(Regressor {
            robot: robot.name.clone(),
            model,
            options,
            params,
            arena,
            y,
            tau,
            pi,
        })
    }

    /// The number of joints (rows).
    pub fn dof(&self) -> usize {
        self.y.len()
    }

    /// Whether column `k` is structurally zero (every entry the zero polynomial).
    pub fn zero_column(&self, k: usize) -> bool {
        self.y.iter().all(|row| row[k].is_zero())
    }

    /// `Σ_k Y_ik v_k` for each row `i`.
    pub fn times(&self, v: &[Poly]) -> Vec<Poly> {
        self.y
            .iter()
            .map(|row| {
                row.iter()
                    .zip(v)
                    .filter(|(y, _)| !y.is_zero())
                    .fold(Poly::zero(), |acc, (y, p)| acc.add(&y.mul(p)))
            })
            .collect()
    }

    /// Proves `Y π = τ` row by row for the scene's π (exact within the budget, else randomized).
    pub fn prove_tau(&self, opts: &ProofOptions) -> Vec<Outcome> {
        let lhs = self.times(&self.pi);
        let claims: Vec<(&Poly, &Poly)> = lhs.iter().zip(&self.tau).collect();
        prove(&self.arena, &claims, opts)
    }
}

/// Every symbol a robot states.
fn used_symbols(robot: &Robot) -> Vec<Symbol> {
    let mut exprs: Vec<&Expr> = robot.gravity.iter().collect();
    for j in &robot.joints {
        exprs.extend([&j.a, &j.alpha, &j.d, &j.theta]);
    }
    for l in robot.links.iter().chain(&robot.payload) {
        exprs.extend(l.exprs());
    }
    exprs.into_iter().flat_map(|e| e.symbols()).collect()
}

/// The kinematic quantities of link `i` that the wrenches need, in frame `i`.
struct LinkMotion {
    w: Vec3<Poly>,
    wd: Vec3<Poly>,
    u: Mat3<Poly>,
    /// The acceleration of `o_i`, less gravity.
    a: Vec3<Poly>,
}

/// The forward pass: ω, α, U and the origin's acceleration of every link, by the compact
/// Newton–Euler's own forward recursion ([`ne_compact::forward`], the same names, so the arena
/// shares them with `τ`).
fn forward(robot: &Robot, joints: &[JointFrame], arena: &mut Compact) -> Vec<LinkMotion> {
    let n = joints.len();
    let mut out = Vec::with_capacity(n);
    let (_, origins) =
        ne_compact::forward(robot, joints, arena, Motion::Full, &mut |arena, idx, m| {
            // a_e,i is named by the recursion right after this for i < n; the last link's here.
            let a = if idx + 1 == n {
                name_vec(arena, m.origin_accel(), &format!("ae{n}"))
            } else {
                Vec3::zero()
            };
            out.push(LinkMotion {
                w: m.w.clone(),
                wd: m.wd.clone(),
                u: m.u.clone(),
                a,
            });
        });
    for (m, a) in out.iter_mut().zip(origins) {
        m.a = a;
    }
    out
}

/// The wrench `(F, N)` about `o_j`, in frame `j`, of one standard parameter of link `j`.
fn wrench(m: &LinkMotion, q: Quantity) -> (Vec3<Poly>, Vec3<Poly>) {
    if let Some((a, b)) = inertia_entry(q) {
        let mut j = Mat3::<Poly>::zero();
        j.0[a][b] = Poly::one();
        j.0[b][a] = Poly::one();
        let n = j.mul_vec(&m.wd).add(&m.w.cross(&j.mul_vec(&m.w)));
        return (Vec3::zero(), n);
    }
    match q {
        Quantity::Mx | Quantity::My | Quantity::Mz => {
            let k = q as usize - Quantity::Mx as usize;
            let ms = Vec3::<Poly>::unit(k);
            (m.u.mul_vec(&ms), ms.cross(&m.a))
        }
        _ => (m.a.clone(), Vec3::zero()),
    }
}

/// The entries of `Y`, column by column.
fn columns(
    robot: &Robot,
    joints: &[JointFrame],
    arena: &mut Compact,
    params: &[StandardParam],
) -> Vec<Vec<Poly>> {
    let n = joints.len();
    let motion = forward(robot, joints, arena);
    let mut y = vec![vec![Poly::zero(); params.len()]; n];
    for (k, p) in params.iter().enumerate() {
        let j = p.link;
        if p.quantity == Quantity::Ia {
            y[j - 1][k] = Poly::symbol(&Symbol::qdd(j as u32));
            continue;
        }
        if p.quantity == Quantity::Fv {
            y[j - 1][k] = Poly::symbol(&Symbol::qd(j as u32));
            continue;
        }
        if p.quantity == Quantity::Fc {
            let sgn = crate::algebra::Expr::sgn(&crate::algebra::Expr::sym(Symbol::qd(j as u32)));
            y[j - 1][k] = crate::algebra::to_poly(&sgn);
            continue;
        }
        let (mut f, mut nm) = wrench(&motion[j - 1], p.quantity);
        let base = p.name();
        for i in (1..=j).rev() {
            let jf = &joints[i - 1];
            if f.is_exact_zero() && nm.is_exact_zero() {
                break;
            }
            let rt = jf.rot.transpose();
            let r_jo = rt.mul_vec(&jf.origin.sub(&jf.joint_point));
            y[i - 1][k] = match jf.kind {
                JointKind::Revolute => nm.add(&r_jo.cross(&f)).dot(&jf.axis_local),
                JointKind::Prismatic => f.dot(&jf.axis_local),
            }
            .mul(&jf.rate);
            if i > 1 {
                let fr = name_vec(arena, jf.rot.mul_vec(&f), &format!("{base}f{}", i - 1));
                let nr = jf.rot.mul_vec(&nm).add(&jf.origin.cross(&fr));
                nm = name_vec(arena, nr, &format!("{base}n{}", i - 1));
                f = fr;
            }
        }
    }
    y
}
