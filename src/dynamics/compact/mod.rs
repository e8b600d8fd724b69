//! Every quantity of the dynamics in compact form: named, hash-consed, canonical intermediates in one
//! arena ([`crate::algebra::compact::Compact`]), growing about linearly (τ) or quadratically (D) with
//! the number of joints where the expanded forms swell exponentially.
//!
//! | quantity | how | file |
//! |---|---|---|
//! | `τ` by Newton–Euler (body frames) | the customised recursion of Khalil and Kleinfinger | [`crate::dynamics::ne_compact`] |
//! | `D(q)` | composite rigid bodies | [`crba`] |
//! | `P`, `g(q) = ∂P/∂q` | gravity carried link to link, the chain rule through the names | [`potential`] |
//! | `c_ijk`, `C(q, q̇)` | `∂D/∂q` by the chain rule through the names | [`christoffel`] |
//! | `τ` by Euler–Lagrange | `D q̈ + C q̇ + g` | [`christoffel::equations`] |
//! | `τ` by Newton–Euler (inertial frame) | the generic recursion over a naming scalar | [`inertial`], [`scalar`] |
//!
//! The Euler–Lagrange side never uses the Newton–Euler recursion (composite bodies are its own
//! algorithm), so proving `τ_EL = τ_NE` ([`crate::dynamics::check`]) still checks one method against
//! another. Expanded (by [`crate::algebra::compact::Expander`]) every quantity equals the one of
//! [`crate::dynamics::lagrange`] exactly; the tests prove it on the examples and random chains.

pub mod christoffel;
pub mod crba;
pub mod inertial;
pub mod potential;
pub mod scalar;

use super::kinematics::JointFrame;
use super::model::Robot;
use super::ne_compact::{self, Motion};
use super::vec3::{Mat3, Vec3};
use crate::algebra::compact::Compact;
use crate::algebra::Poly;

/// The compact dynamics of one robot, every quantity over one arena.
#[derive(Clone, Debug)]
pub struct CompactDynamics {
    /// The named intermediates of every quantity below.
    pub arena: Compact,
    /// `τ_k` by Newton–Euler in body-fixed frames (index `k − 1`).
    pub tau_ne: Vec<Poly>,
    /// `D(q)`, symmetric.
    pub d: Vec<Vec<Poly>>,
    /// Whether `D` is constant (no entry depends on a position): then every `c_ijk` is zero.
    pub d_constant: bool,
    /// `c[i][j][k] = c_ijk`, symmetric in `i, j` (all zero when `D` is constant).
    pub christoffel: Vec<Vec<Vec<Poly>>>,
    /// `C(q, q̇)`.
    pub c: Vec<Vec<Poly>>,
    /// The potential energy `P`.
    pub p: Poly,
    /// `g(q)`.
    pub g: Vec<Poly>,
    /// `τ_k` by Euler–Lagrange, `Σ_j d_kj q̈_j + Σ_ij c_ijk q̇_i q̇_j + g_k`.
    pub tau: Vec<Poly>,
}

impl CompactDynamics {
    /// Derives every quantity of a validated robot with its local joint frames.
    pub fn derive(robot: &Robot, joints: &[JointFrame]) -> CompactDynamics {
        let n = robot.dof();
        // Euler–Lagrange first, so its names are its own in listings; Newton–Euler then reuses any
        // equal value by hash-consing.
        let mut arena = arena_for(robot);
        let d = crba::mass_matrix(robot, joints, &mut arena);
        let (p, g) = potential::potential_and_gravity(robot, joints, &mut arena);
        // g_k and P named, so that listings and equations can refer to them.
        let g: Vec<Poly> = g
            .into_iter()
            .enumerate()
            .map(|(k, gk)| arena.name(gk, &format!("g{}", k + 1)))
            .collect();
        let p = arena.name(p, "P");
        let d_constant = christoffel::is_constant(&d, &arena);
        let christoffel = if d_constant {
            vec![vec![vec![Poly::zero(); n]; n]; n]
        } else {
            christoffel::christoffel(&d, &mut arena)
        };
        let c = christoffel::coriolis(&christoffel);
        let friction: Vec<Poly> = (1..=robot.dof())
            .map(|k| robot.drive(k).friction(k as u32))
            .collect();
        let tau =
            christoffel::equations(&d, (!d_constant).then_some(&christoffel[..]), &g, &friction);
        let tau_ne = ne_compact::tau_into(robot, joints, &mut arena, Motion::Full);
        CompactDynamics {
            arena,
            tau_ne,
            d,
            d_constant,
            christoffel,
            c,
            p,
            g,
            tau,
        }
    }

    /// A copy of the arena with `τ` by Newton–Euler in the inertial frame added, and that `τ` (built on
    /// demand: only the proofs and listings of the inertial frame need it).
    pub fn with_inertial(&self, robot: &Robot, joints: &[JointFrame]) -> (Compact, Vec<Poly>) {
        inertial::tau(robot, joints, self.arena.clone())
    }

    /// The non-zero Christoffel symbols `(i, j, k, c_ijk)`, 1-based, in index order (zero in compact
    /// form: a symbol whose names cancel only when expanded is listed).
    pub fn nonzero_christoffel(&self) -> Vec<(usize, usize, usize, &Poly)> {
        let n = self.d.len();
        let mut out = Vec::new();
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let c = &self.christoffel[i][j][k];
                    if !c.is_zero() {
                        out.push((i + 1, j + 1, k + 1, c));
                    }
                }
            }
        }
        out
    }
}

/// A new arena with every symbol of the robot and its input names reserved, so no intermediate is
/// named like them.
pub fn arena_for(robot: &Robot) -> Compact {
    let mut arena = Compact::new();
    let exprs = robot.expressions();
    let names: Vec<String> = exprs
        .into_iter()
        .flat_map(|e| e.symbols())
        .filter_map(|s| s.param_name().map(str::to_string))
        .collect();
    arena.reserve(names);
    arena.reserve(robot.inputs.iter().cloned());
    arena
}

/// Names the components `{base}_1 … {base}_3`.
pub fn name_vec(arena: &mut Compact, v: Vec3<Poly>, base: &str) -> Vec3<Poly> {
    let [x, y, z] = v.0;
    Vec3([
        arena.name(x, &format!("{base}_1")),
        arena.name(y, &format!("{base}_2")),
        arena.name(z, &format!("{base}_3")),
    ])
}

/// Names the entries `{base}_{rc}`.
pub fn name_mat(arena: &mut Compact, m: Mat3<Poly>, base: &str) -> Mat3<Poly> {
    let mut out = Mat3::zero();
    for (r, row) in m.0.into_iter().enumerate() {
        for (c, v) in row.into_iter().enumerate() {
            out.0[r][c] = arena.name(v, &format!("{base}_{}{}", r + 1, c + 1));
        }
    }
    out
}

/// Names the upper triangle of a symmetric matrix (`{base}_{rc}`, `r ≤ c`) and mirrors it.
pub fn name_sym(arena: &mut Compact, m: Mat3<Poly>, base: &str) -> Mat3<Poly> {
    let mut out = Mat3::zero();
    for r in 0..3 {
        for c in r..3 {
            let v = arena.name(m.0[r][c].clone(), &format!("{base}_{}{}", r + 1, c + 1));
            out.0[c][r] = v.clone();
            out.0[r][c] = v;
        }
    }
    out
}

/// `S(v)`, the matrix of `v × ·`.
pub fn skew(v: &Vec3<Poly>) -> Mat3<Poly> {
    let [x, y, z] = &v.0;
    Mat3([
        [Poly::zero(), z.neg(), y.clone()],
        [z.clone(), Poly::zero(), x.neg()],
        [y.neg(), x.clone(), Poly::zero()],
    ])
}
