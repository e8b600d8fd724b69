//! The Euler–Lagrange equations (Spong, Hutchinson and Vidyasagar, *Robot Modeling and Control*, §7.3–7.4).
//!
//! - `D(q) = Σ_i m_i J_v,iᵀ J_v,i + J_ω,iᵀ R_i I_i R_iᵀ J_ω,i` (the rotational term only for links that
//!   rotate);
//! - Christoffel symbols `c_ijk = ½ (∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)` (none computed when `D` is
//!   constant);
//! - `C(q, q̇)` with `c_kj = Σ_i c_ijk q̇_i`;
//! - `P = −Σ_i m_i gᵀ p_ci` with `g` the gravity vector in frame 0, and `g_k = ∂P/∂q_k`;
//! - a payload (a rigid body fixed to link `n`) is one more body in both sums: `m_L J_v,Lᵀ J_v,L +
//!   J_ω,nᵀ R_n I_L R_nᵀ J_ω,n` in `D` and `−m_L gᵀ p_cL` in `P`;
//! - the equations `Σ_j d_kj q̈_j + Σ_ij c_ijk q̇_i q̇_j + g_k = τ_k`;
//! - a joint's drive (§7.5): the reflected rotor inertia `r² J_m` on the diagonal of `D`, and viscous
//!   friction `B q̇_k` added to equation `k`.
//!
//! Indices in the API are 0-based (`d[k][j]` is `d_{k+1, j+1}`); printers add one.

use super::compact::CompactDynamics;
use super::facts::Fact;
use super::kinematics::{Columns, JointFrame, Kinematics};
use super::model::Robot;
use super::vec3::{Mat3, Vec3};
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::calculus::poly_diff;
use crate::algebra::poly::Mono;
use crate::algebra::{to_poly, Poly, Rational, Symbol};
use crate::parallel::{self, WORTH_SHARING};
use std::sync::Arc;

/// Every quantity of the Euler–Lagrange derivation. Derived in stages, each usable as soon as it
/// exists ([`MassMatrix`], then [`christoffel_symbols`], then [`Motion`] and [`coriolis_matrix`]),
/// and assembled with `K` ([`Lagrange::assemble`]); the large stages are shared, not copied.
#[derive(Clone, Debug)]
pub struct Lagrange {
    /// `D(q)`, symmetric.
    pub d: Arc<Vec<Vec<Poly>>>,
    /// Whether `D` is constant (then every Christoffel symbol is zero and was not computed).
    pub d_constant: bool,
    /// `c[i][j][k] = c_ijk`, symmetric in `i, j`.
    pub christoffel: Arc<Christoffel>,
    /// `C(q, q̇)`.
    pub c: Arc<Vec<Vec<Poly>>>,
    /// The potential energy `P`.
    pub p: Poly,
    /// `g(q) = ∂P/∂q`.
    pub g: Vec<Poly>,
    /// The kinetic energy `K = ½ q̇ᵀ D q̇`.
    pub k: Poly,
    /// The left side of equation `k`: `Σ_j d_kj q̈_j + Σ_ij c_ijk q̇_i q̇_j + g_k`.
    pub tau: Arc<Vec<Poly>>,
    /// The structural facts used.
    pub facts: Vec<Fact>,
}

/// The Christoffel symbols `c[i][j][k] = c_ijk` (0-based), symmetric in `i, j`.
pub type Christoffel = Vec<Vec<Vec<Poly>>>;

/// The first stage: `D(q)` and whether it is constant.
#[derive(Clone, Debug)]
pub struct MassMatrix {
    /// `D(q)`, symmetric.
    pub d: Arc<Vec<Vec<Poly>>>,
    /// Whether no entry depends on a joint position.
    pub constant: bool,
}

/// The third stage: the potential and gravity (the left sides of the equations, [`left_sides`], are a
/// stage of their own).
#[derive(Clone, Debug)]
pub struct Motion {
    /// The potential energy `P`.
    pub p: Poly,
    /// `g(q) = ∂P/∂q`.
    pub g: Vec<Poly>,
}

fn is_constant(p: &Poly) -> bool {
    use crate::algebra::atom::{class, Class};
    p.atoms().iter().all(|&id| match class(id) {
        Class::Coord => false,
        Class::Sin | Class::Cos => {
            crate::algebra::atom::symbol_of(id).is_none_or(|s| !s.is_coord())
        }
        Class::Other => false,
        _ => true,
    })
}

/// A link's inertia tensor in its own frame and the columns of `R_iᵀ J_ω,i`.
type LinkInertia = (Mat3<Poly>, Columns);

fn quad(u: &Vec3<Poly>, m: &Mat3<Poly>, v: &Vec3<Poly>) -> Poly {
    u.dot(&m.mul_vec(v))
}

/// A tensor given as expressions, as polynomials.
fn tensor_poly(t: &[[crate::algebra::Expr; 3]; 3]) -> Mat3<Poly> {
    Mat3(std::array::from_fn(|r| {
        std::array::from_fn(|c| to_poly(&t[r][c]))
    }))
}

impl MassMatrix {
    /// `D(q) = Σ_i m_i J_v,iᵀ J_v,i + J_ω,iᵀ R_i I_i R_iᵀ J_ω,i` (+ payload, + reflected rotors).
    ///
    /// Both terms are taken in link `i`'s own frame ([`Kinematics::local_jacobians`]):
    /// `J_v,iᵀ J_v,i = (R_iᵀ J_v,i)ᵀ (R_iᵀ J_v,i)` and `(R_iᵀ J_ω,i)ᵀ I_i (R_iᵀ J_ω,i)`, where the tensor
    /// is given. Column `j` there holds only `q_j … q_i`, so the products never build, and cancel, the
    /// base's angles that `D` does not depend on, and the large expanded `R_i I_i R_iᵀ` is never
    /// formed. The polynomials are the same.
    pub fn derive(robot: &Robot, kin: &Kinematics) -> MassMatrix {
        Self::by_jacobians(robot, kin, local_jacobians(robot, kin))
    }

    /// `D(q)` by the faster route for this robot: the Jacobians' products ([`MassMatrix::derive`])
    /// or composite rigid bodies expanded ([`MassMatrix::from_composite_bodies`], from `compact`'s
    /// `D` when given); see [`by_composite_bodies`]. The same polynomials either way.
    pub fn new(
        robot: &Robot,
        kin: &Kinematics,
        joints: &[JointFrame],
        compact: Option<&CompactDynamics>,
    ) -> MassMatrix {
        // The compact dynamics' D, derived already, is expanded ([`by_composite_bodies`]), and so is a
        // large numeric robot's without counting.
        if compact.is_some() || composite_at_once(robot) {
            return Self::from_composite_bodies(robot, joints, compact);
        }
        // The products are counted link by link from the last, whose columns are the largest,
        // and a count past the threshold decides at once: the Jacobians of the links before it
        // are not built for nothing (the Franka Panda's last link alone passes it).
        let n = robot.dof();
        let numeric = robot.links.iter().all(|l| l.mass.as_rational().is_some());
        let mut local: Vec<(Columns, Columns)> = Vec::with_capacity(n);
        let mut products = 0;
        for i in (0..n).rev() {
            let link = local_jacobian(robot, kin, i);
            products += (0..n)
                .flat_map(|k| (k..n).map(move |j| (k, j)))
                .map(|(k, j)| term_products(std::slice::from_ref(&link), k, j))
                .sum::<usize>();
            local.push(link);
            if by_composite_bodies(products, numeric, false) {
                return Self::from_composite_bodies(robot, joints, compact);
            }
        }
        local.reverse();
        Self::by_jacobians(robot, kin, local)
    }

    /// [`MassMatrix::derive`] from each link's local Jacobians.
    fn by_jacobians(robot: &Robot, kin: &Kinematics, local: Vec<(Columns, Columns)>) -> MassMatrix {
        let n = robot.dof();
        let rotational: Vec<Option<LinkInertia>> = (0..n)
            .map(|i| {
                let tensor = robot.links[i].inertia.as_ref()?;
                if !kin.rotates[i] {
                    return None;
                }
                Some((tensor_poly(tensor), local[i].1.clone()))
            })
            .collect();
        let masses: Vec<Poly> = robot.links.iter().map(|l| to_poly(&l.mass)).collect();
        // The payload: its mass, J_v,L and, when link n rotates, its tensor with link n's axes, all
        // in link n's frame (it moves with link n).
        let payload = robot.payload.as_ref().map(|l| {
            let com = Vec3(std::array::from_fn(|k| to_poly(&l.com[k])));
            let jv = kin.local_jacobians(n - 1, &com).0;
            let rot = l
                .inertia
                .as_ref()
                .filter(|_| kin.rotates[n - 1])
                .map(|t| (tensor_poly(t), local[n - 1].1.clone()));
            (to_poly(&l.mass), jv, rot)
        });
        let rotors: Vec<Poly> = (1..=n).map(|k| to_poly(&robot.drive(k).rotor)).collect();
        // d_kj for k ≤ j, one entry per item, on several threads for a large robot (the entries of
        // the Franka Panda take about 9 ms on one), unless a factor holds a surd or an opaque atom,
        // whose products may intern new atoms (whose ids would then depend on the schedule).
        let pairs: Vec<(usize, usize)> = (0..n).flat_map(|k| (k..n).map(move |j| (k, j))).collect();
        let mut inputs: Vec<&Poly> = masses.iter().chain(&rotors).collect();
        for (v, w) in &local {
            inputs.extend(columns(v).chain(columns(w)));
        }
        for (t, _) in rotational.iter().flatten() {
            inputs.extend(tensor(t));
        }
        if let Some((mass, jv, rot)) = &payload {
            inputs.push(mass);
            inputs.extend(columns(jv));
            if let Some((t, _)) = rot {
                inputs.extend(tensor(t));
            }
        }
        let interns = inputs.into_iter().any(may_intern);
        let weight = |&(k, j): &(usize, usize)| -> usize {
            if interns {
                return 0;
            }
            term_products(&local, k, j) * PRODUCT_WORK
        };
        let entries = parallel::map(&pairs, weight, WORTH_SHARING, |&(k, j)| {
            let mut parts = Vec::new();
            for i in 0..n {
                let (jk, jj) = (&local[i].0[k], &local[i].0[j]);
                if !masses[i].is_zero() && !jk.is_exact_zero() && !jj.is_exact_zero() {
                    parts.push(masses[i].mul(&jk.dot(jj)));
                }
                if let Some((local, axes)) = &rotational[i] {
                    let (wk, wj) = (&axes[k], &axes[j]);
                    if !wk.is_exact_zero() && !wj.is_exact_zero() {
                        parts.push(quad(wk, local, wj));
                    }
                }
            }
            if let Some((mass, jv, rot)) = &payload {
                let (jk, jj) = (&jv[k], &jv[j]);
                if !jk.is_exact_zero() && !jj.is_exact_zero() {
                    parts.push(mass.mul(&jk.dot(jj)));
                }
                if let Some((local, axes)) = rot {
                    let (wk, wj) = (&axes[k], &axes[j]);
                    if !wk.is_exact_zero() && !wj.is_exact_zero() {
                        parts.push(quad(wk, local, wj));
                    }
                }
            }
            if j == k && !rotors[k].is_zero() {
                // The motor's rotor, reflected through its gear (Spong §7.5): a constant.
                parts.push(rotors[k].clone());
            }
            Poly::sum(&parts)
        });
        Self::mirrored(n, pairs.into_iter().zip(entries))
    }

    /// `D` from its upper triangle `((k, j), d_kj)`, `k ≤ j`, and whether it is constant.
    fn mirrored(n: usize, upper: impl IntoIterator<Item = ((usize, usize), Poly)>) -> MassMatrix {
        let mut d = vec![vec![Poly::zero(); n]; n];
        for ((k, j), entry) in upper {
            d[j][k] = entry.clone();
            d[k][j] = entry;
        }
        let constant = d.iter().flatten().all(is_constant);
        MassMatrix {
            d: Arc::new(d),
            constant,
        }
    }

    /// `D(q)` by composite rigid bodies ([`super::compact::crba`]), expanded: the same polynomials
    /// as [`MassMatrix::derive`] (both are the canonical form of the same matrix), from the compact
    /// `D` of `compact` when it is derived already, else from a composite-body `D` of its own.
    ///
    /// For a large robot this is several times faster than the Jacobians' products: each link's
    /// inertia is moved down the chain once as a composite body, where the Jacobian route multiplies
    /// every pair of columns of every link (measured on one thread: the Franka Panda's 9.6 ms
    /// against 1.8 ms, the numeric PUMA 560's 1.2 against 0.43, a generic 7-joint chain's 25.5
    /// against 8.0). For a smaller or symbolic robot its fixed costs lose ([`by_composite_bodies`]).
    pub fn from_composite_bodies(
        robot: &Robot,
        joints: &[JointFrame],
        compact: Option<&CompactDynamics>,
    ) -> MassMatrix {
        let n = robot.dof();
        let own;
        let (arena, d) = match compact {
            Some(cd) => (&cd.arena, &cd.d),
            None => {
                let mut arena = super::compact::arena_for(robot);
                let d = super::compact::crba::mass_matrix(robot, joints, &mut arena);
                own = (arena, d);
                (&own.0, &own.1)
            }
        };
        // Every entry at once: the entries share their composite bodies' names, each expanded
        // once, on several threads for a large robot.
        let places: Vec<(usize, usize)> =
            (0..n).flat_map(|k| (k..n).map(move |j| (k, j))).collect();
        let compact: Vec<&Poly> = places.iter().map(|&(k, j)| &d[k][j]).collect();
        let upper = places.into_iter().zip(arena.expand_all(&compact));
        Self::mirrored(n, upper)
    }
}

/// Whether [`MassMatrix::from_composite_bodies`] is the faster route to the expanded `D` of a robot
/// whose Jacobian route multiplies about `products` pairs of terms: always when the compact
/// dynamics are derived already (their `D` is then expanded, not derived again); else from
/// [`COMPOSITE_FROM`] products on, or from [`COMPOSITE_FROM_NUMERIC`] when every mass is a number
/// (a numeric mass and tensor multiply every product's coefficient, where a symbolic one only joins
/// its monomial, so each product of the Jacobian route costs more). The route decides nothing but
/// the time: both give the same polynomials.
///
/// Measured, whole `derive` processes on two threads (the Jacobian route shares its entries between
/// them, the composite bodies then ran on one; their expansion is shared too now,
/// [`Compact::expand_all`](crate::algebra::compact::Compact::expand_all)): the Franka Panda 21.7 → 18.1 ms (57 741 products), the
/// UR5 10.1 → 9.6 (9 132, numeric), the numeric PUMA 560 7.3 → 6.9 (7 397); on one thread, a
/// generic 6-joint chain 6.9 → 3.5 ms for `D` alone (61 160). Kept on the Jacobians: the all-symbolic
/// PUMA 560 (17 786; 13.7 against 14.0 ms), a 5-joint chain (14 610; a tie on one thread) and the
/// Stanford arm (4 768; 8.4 against 8.6 ms).
pub fn by_composite_bodies(products: usize, numeric_masses: bool, compact_derived: bool) -> bool {
    compact_derived
        || products >= COMPOSITE_FROM
        || (numeric_masses && products >= COMPOSITE_FROM_NUMERIC)
}

/// Whether `D` goes by composite bodies without the Jacobian route's products counted (which needs
/// the kinematics): a robot of [`COMPOSITE_JOINTS`] joints or more whose masses are all numbers.
/// The count would say so too for each such robot measured (the numeric PUMA 560 7 397 products,
/// the UR5 9 132, the Franka Panda 57 741, against [`COMPOSITE_FROM_NUMERIC`]), and the route
/// decides nothing but the time; so the kinematics, which `D` then does not need, can be derived
/// beside it ([`crate::dynamics::Derivation::mass_matrix`]).
pub fn composite_at_once(robot: &Robot) -> bool {
    robot.dof() >= COMPOSITE_JOINTS && robot.links.iter().all(|l| l.mass.as_rational().is_some())
}

/// The joints from which [`composite_at_once`] holds for a numeric robot.
pub const COMPOSITE_JOINTS: usize = 6;

/// The term products of the Jacobian route from which composite bodies are faster.
pub const COMPOSITE_FROM: usize = 40_000;

/// [`COMPOSITE_FROM`] for a robot whose masses are numbers.
pub const COMPOSITE_FROM_NUMERIC: usize = 5_000;

/// The products of terms the Jacobian route multiplies for `d_kj`: over the links, the terms of
/// column `k` of `R_iᵀ J_v,i` times those of column `j`.
fn term_products(local: &[(Columns, Columns)], k: usize, j: usize) -> usize {
    let size = |v: &Vec3<Poly>| v.0.iter().map(Poly::len).sum::<usize>();
    local.iter().map(|(v, _)| size(&v[k]) * size(&v[j])).sum()
}

/// Link `i`'s `(R_iᵀ J_v,i, R_iᵀ J_ω,i)` at its centre of mass ([`Kinematics::local_jacobians`]).
fn local_jacobian(robot: &Robot, kin: &Kinematics, i: usize) -> (Columns, Columns) {
    let com = Vec3(std::array::from_fn(|k| to_poly(&robot.links[i].com[k])));
    kin.local_jacobians(i, &com)
}

/// Each link's `(R_iᵀ J_v,i, R_iᵀ J_ω,i)` at its centre of mass ([`local_jacobian`]).
fn local_jacobians(robot: &Robot, kin: &Kinematics) -> Vec<(Columns, Columns)> {
    (0..robot.dof())
        .map(|i| local_jacobian(robot, kin, i))
        .collect()
}

/// The entries of the columns of a Jacobian.
fn columns(c: &Columns) -> impl Iterator<Item = &Poly> {
    c.iter().flat_map(|v| v.0.iter())
}

/// The entries of a tensor.
fn tensor(t: &Mat3<Poly>) -> impl Iterator<Item = &Poly> {
    t.0.iter().flatten()
}

/// Whether a product with `p` may intern a new atom: `p` holds a surd (`√2 √3` is `√6`) or an
/// opaque atom.
fn may_intern(p: &Poly) -> bool {
    p.terms()
        .iter()
        .flat_map(|(m, _)| m.factors())
        .any(|&(id, _)| matches!(atom::class(id), Class::Other | Class::Sqrt))
}

/// The second stage: `c_ijk = ½ (∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)`, all zero (and not computed)
/// when `D` is constant.
pub fn christoffel_symbols(mass: &MassMatrix) -> Christoffel {
    let d = &mass.d;
    let n = d.len();
    if mass.constant {
        return vec![vec![vec![Poly::zero(); n]; n]; n];
    }
    let qs: Vec<Symbol> = (1..=n as u32).map(Symbol::q).collect();
    // ∂D/∂q_i, for the upper triangle only (D is symmetric, so is each ∂D/∂q_i):
    // `dd[i][a][b - a]` is ∂d_ab/∂q_i for a ≤ b. On several threads for a large D, unless D holds
    // an opaque atom (`Class::Other`), whose derivative may intern new atoms.
    let opaque = d
        .iter()
        .enumerate()
        .flat_map(|(a, row)| &row[a..])
        .any(|e| {
            e.terms()
                .iter()
                .flat_map(|(m, _)| m.factors())
                .any(|&(id, _)| atom::class(id) == Class::Other)
        });
    // One (q_i, d_ab) per item, heaviest first: an entry's cost depends on its size and on how much
    // of it holds q_i (none of D holds q_1), so whole rows of derivatives would leave a thread idle.
    let items: Vec<(usize, usize, usize)> = (0..n)
        .flat_map(|i| (0..n).flat_map(move |a| (a..n).map(move |b| (i, a, b))))
        .collect();
    let weight = |&(_, a, b): &(usize, usize, usize)| {
        if opaque {
            0
        } else {
            DIFF_WORK * d[a][b].len()
        }
    };
    let mut derivatives = parallel::map(&items, weight, WORTH_SHARING, |&(i, a, b)| {
        poly_diff(&d[a][b], &qs[i])
    })
    .into_iter();
    let dd: Vec<Vec<Vec<Poly>>> = (0..n)
        .map(|_| {
            (0..n)
                .map(|a| {
                    (a..n)
                        .map(|_| derivatives.next().expect("one per item"))
                        .collect()
                })
                .collect()
        })
        .collect();
    christoffel_expanded(&dd)
}

/// The work of a stage per term it reads, in the units of [`parallel::map`] (about 3 ns; measured
/// on the all-symbolic PUMA 560: a derivative about 150 ns a term of `D`, a sum or a product by
/// `q̇`, `q̈` about 100 ns a term).
const DIFF_WORK: usize = 50;
/// The work of an entry of `D` per product of terms of two Jacobian columns.
const PRODUCT_WORK: usize = 10;
const SUM_WORK: usize = 30;

/// The terms of some polynomials.
fn terms(polys: &[Poly]) -> usize {
    polys.iter().map(Poly::len).sum()
}

/// `c_ijk = ½ (∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)` from `dd[i][a][b − a] = ∂d_ab/∂q_i` (`a ≤ b`,
/// the upper triangle: each `∂D/∂q_i` is symmetric), however the derivatives were taken (expanded
/// here, through names in [`super::compact`]). Each symbol with `i ≤ j` (0-based) goes through
/// `keep` (which may name it) and is given to both `c_ijk` and `c_jik`.
pub fn christoffel_from(
    dd: &[Vec<Vec<Poly>>],
    mut keep: impl FnMut(usize, usize, usize, Poly) -> Poly,
) -> Christoffel {
    let n = dd.len();
    let mut christoffel = vec![vec![vec![Poly::zero(); n]; n]; n];
    for ((i, j), row, _) in symbol_rows(dd, false) {
        for (k, c) in row.into_iter().enumerate() {
            let c = keep(i, j, k, c);
            christoffel[j][i][k] = c.clone();
            christoffel[i][j][k] = c;
        }
    }
    christoffel
}

/// The expanded Christoffel symbols from `dd` as in [`christoffel_from`], each `c_jik` a copy of
/// `c_ijk` made on the thread that derived it (copying them one after another took a millisecond
/// of the Franka Panda's derivation).
fn christoffel_expanded(dd: &[Vec<Vec<Poly>>]) -> Christoffel {
    let n = dd.len();
    let mut christoffel = vec![vec![vec![Poly::zero(); n]; n]; n];
    for ((i, j), row, twin) in symbol_rows(dd, true) {
        christoffel[i][j] = row;
        if let Some(twin) = twin {
            christoffel[j][i] = twin;
        }
    }
    christoffel
}

/// The rows `(c_ij1 … c_ijn)` for `i ≤ j` from `dd` (see [`christoffel_from`]), one `(i, j)` per
/// item on several threads when there is enough to add, in order; with `twins`, a copy of each row
/// with `i < j`, for `c_ji·`.
#[allow(clippy::type_complexity)]
fn symbol_rows(
    dd: &[Vec<Vec<Poly>>],
    twins: bool,
) -> Vec<((usize, usize), Vec<Poly>, Option<Vec<Poly>>)> {
    let n = dd.len();
    let at = |i: usize, a: usize, b: usize| -> &Poly {
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        &dd[i][a][b - a]
    };
    let half = Rational::new(1, 2).expect("non-zero");
    let pairs: Vec<(usize, usize)> = (0..n).flat_map(|i| (i..n).map(move |j| (i, j))).collect();
    let weight = |&(i, j): &(usize, usize)| {
        SUM_WORK
            * (0..n)
                .map(|k| at(i, k, j).len() + at(j, k, i).len() + at(k, i, j).len())
                .sum::<usize>()
    };
    parallel::map(&pairs, weight, WORTH_SHARING, |&(i, j)| {
        let row: Vec<Poly> = (0..n)
            .map(|k| at(i, k, j).add(at(j, k, i)).sub(at(k, i, j)).scale(&half))
            .collect();
        let twin = (twins && i != j).then(|| row.clone());
        ((i, j), row, twin)
    })
}

/// `C(q, q̇)`: `c_kj = Σ_i c_ijk q̇_i` (expanded, or over the names of a compact arena).
pub fn coriolis_matrix(christoffel: &[Vec<Vec<Poly>>]) -> Vec<Vec<Poly>> {
    let n = christoffel.len();
    let qds: Vec<Poly> = (1..=n as u32)
        .map(|i| Poly::symbol(&Symbol::qd(i)))
        .collect();
    let rows: Vec<usize> = (0..n).collect();
    let weight = |&k: &usize| {
        SUM_WORK
            * (0..n)
                .map(|j| (0..n).map(|i| christoffel[i][j][k].len()).sum::<usize>())
                .sum::<usize>()
    };
    parallel::map(&rows, weight, WORTH_SHARING, |&k| {
        (0..n)
            .map(|j| {
                let parts: Vec<Poly> = (0..n).map(|i| christoffel[i][j][k].mul(&qds[i])).collect();
                Poly::sum(&parts)
            })
            .collect()
    })
}

impl Motion {
    /// `P = −Σ_i m_i gᵀ p_ci` (+ payload) and `g_k = ∂P/∂q_k`.
    pub fn derive(robot: &Robot, kin: &Kinematics) -> Motion {
        let n = robot.dof();
        let qs: Vec<Symbol> = (1..=n as u32).map(Symbol::q).collect();
        let gravity: Vec3<Poly> = Vec3(std::array::from_fn(|k| to_poly(&robot.gravity[k])));
        let mut p_parts: Vec<Poly> = (0..n)
            .map(|i| {
                to_poly(&robot.links[i].mass)
                    .mul(&gravity.dot(&kin.com0[i]))
                    .neg()
            })
            .collect();
        if let Some((l, (com0, _))) = robot.payload.as_ref().zip(kin.payload.as_ref()) {
            p_parts.push(to_poly(&l.mass).mul(&gravity.dot(com0)).neg());
        }
        let p = Poly::sum(&p_parts);
        let g: Vec<Poly> = qs.iter().map(|q| poly_diff(&p, q)).collect();
        Motion { p, g }
    }
}

/// What `τ_k` sums, each part a coefficient and the rates or accelerations it multiplies:
/// `d_kj · q̈_j`, `(2 − δ_ij) c_ijk · q̇_i q̇_j` for `i ≤ j` (`c_ijk = c_jik`), `g_k`, and the drive's
/// friction. Only the coefficients of `i < j` are new (doubled); the rest are borrowed.
pub type SideParts<'a> = Vec<(std::borrow::Cow<'a, Poly>, Vec<(AtomId, i32)>)>;

/// The parts of `τ_k` ([`SideParts`]), the zero ones left out. Their products sum to `τ_k`; none
/// of `D`, the Christoffel symbols or `g` holds a `q̇` or `q̈` (they are functions of `q`), so those
/// products share no monomial and the sum only merges. The friction of a drive (`friction`, with
/// `q̇_k` in it) comes last, with nothing to multiply.
pub fn side_parts<'a>(
    k: usize,
    d: &'a [Vec<Poly>],
    christoffel: &'a Christoffel,
    g: &'a [Poly],
    friction: Option<&'a Poly>,
) -> SideParts<'a> {
    use std::borrow::Cow;
    let n = d.len();
    let qd = |i: usize| atom::sym(&Symbol::qd(i as u32 + 1));
    let two = Rational::int(2);
    let mut parts: SideParts = (0..n)
        .filter(|&j| !d[k][j].is_zero())
        .map(|j| {
            let qdd = atom::sym(&Symbol::qdd(j as u32 + 1));
            (Cow::Borrowed(&d[k][j]), vec![(qdd, 1)])
        })
        .collect();
    for i in 0..n {
        for j in i..n {
            let c = &christoffel[i][j][k];
            if c.is_zero() {
                continue;
            }
            parts.push(if i == j {
                (Cow::Borrowed(c), vec![(qd(i), 2)])
            } else {
                (Cow::Owned(c.scale(&two)), vec![(qd(i), 1), (qd(j), 1)])
            });
        }
    }
    parts.extend(
        std::iter::once(&g[k])
            .chain(friction)
            .filter(|p| !p.is_zero())
            .map(|p| (Cow::Borrowed(p), Vec::new())),
    );
    parts
}

/// The product of some atoms' powers (distinct atoms), as a polynomial.
fn monomial(mut factors: Vec<(AtomId, i32)>) -> Poly {
    factors.sort_unstable();
    Poly::term(Mono::from_sorted(factors), Rational::one())
}

/// The left sides `τ_k = Σ_j d_kj q̈_j + Σ_ij c_ijk q̇_i q̇_j + g_k` (+ the drive's friction), one
/// row per item on several threads for a large robot: the sum of each row's [`side_parts`]
/// multiplied out.
pub fn left_sides(
    robot: &Robot,
    mass: &MassMatrix,
    christoffel: &Christoffel,
    g: &[Poly],
) -> Vec<Poly> {
    let n = robot.dof();
    let d = &mass.d;
    // The drive's friction is built here first: its atoms are interned on this thread.
    let friction: Vec<Option<Poly>> = (0..n)
        .map(|k| {
            let drive = robot.drive(k + 1);
            (!drive.is_none()).then(|| drive.friction(k as u32 + 1))
        })
        .collect();
    // The rate and acceleration atoms, likewise.
    for i in 1..=n as u32 {
        atom::sym(&Symbol::qd(i));
        atom::sym(&Symbol::qdd(i));
    }
    let rows: Vec<usize> = (0..n).collect();
    let weight = |&k: &usize| {
        SUM_WORK
            * (terms(&d[k])
                + (0..n)
                    .flat_map(|i| (i..n).map(move |j| (i, j)))
                    .map(|(i, j)| christoffel[i][j][k].len())
                    .sum::<usize>())
    };
    parallel::map(&rows, weight, WORTH_SHARING, |&k| {
        multiplied_out(&side_parts(k, d, christoffel, g, friction[k].as_ref()))
    })
}

/// The sum of some [`SideParts`]' products, `τ_k` for the parts of `τ_k`.
pub fn multiplied_out(parts: &SideParts) -> Poly {
    let products: Vec<Poly> = parts
        .iter()
        .map(|(c, by)| c.mul(&monomial(by.clone())))
        .collect();
    Poly::sum(&products)
}

impl Lagrange {
    /// Derives the Euler–Lagrange quantities from the robot and its kinematics, stage by stage.
    pub fn derive(robot: &Robot, kin: &Kinematics) -> Lagrange {
        let mass = MassMatrix::derive(robot, kin);
        let christoffel = Arc::new(christoffel_symbols(&mass));
        let motion = Motion::derive(robot, kin);
        let tau = Arc::new(left_sides(robot, &mass, &christoffel, &motion.g));
        let coriolis = Arc::new(coriolis_matrix(&christoffel));
        Lagrange::assemble(&mass, &christoffel, &motion, &tau, &coriolis)
    }

    /// The quantities from the stages, with `K = ½ q̇ᵀ D q̇` computed here; the stages are shared,
    /// not copied.
    pub fn assemble(
        mass: &MassMatrix,
        christoffel: &Arc<Christoffel>,
        motion: &Motion,
        tau: &Arc<Vec<Poly>>,
        coriolis: &Arc<Vec<Vec<Poly>>>,
    ) -> Lagrange {
        let d = &mass.d;
        let n = d.len();
        let qds: Vec<Poly> = (1..=n as u32)
            .map(|i| Poly::symbol(&Symbol::qd(i)))
            .collect();
        let mut facts = Vec::new();
        if mass.constant {
            facts.push(Fact::ConstantMassMatrix);
        }
        // K = ½ Σ_a d_aa q̇_a² + Σ_{a<b} d_ab q̇_a q̇_b (D is symmetric).
        let half = Rational::new(1, 2).expect("non-zero");
        let k_parts: Vec<Poly> = (0..n)
            .flat_map(|a| {
                let qds = &qds;
                let half = &half;
                (a..n).map(move |b| {
                    let rates = qds[a].mul(&qds[b]);
                    let part = d[a][b].mul(&rates);
                    if a == b {
                        part.scale(half)
                    } else {
                        part
                    }
                })
            })
            .collect();
        let k = Poly::sum(&k_parts);
        Lagrange {
            d: Arc::clone(&mass.d),
            d_constant: mass.constant,
            christoffel: Arc::clone(christoffel),
            c: Arc::clone(coriolis),
            p: motion.p.clone(),
            g: motion.g.clone(),
            k,
            tau: Arc::clone(tau),
            facts,
        }
    }

    /// The non-zero Christoffel symbols `(i, j, k, c_ijk)`, 1-based, in index order.
    pub fn nonzero_christoffel(&self) -> Vec<(usize, usize, usize, &Poly)> {
        nonzero_christoffel(&self.christoffel)
    }
}

/// The non-zero Christoffel symbols `(i, j, k, c_ijk)`, 1-based, in index order.
pub fn nonzero_christoffel(christoffel: &Christoffel) -> Vec<(usize, usize, usize, &Poly)> {
    let mut out = Vec::new();
    for (i, plane) in christoffel.iter().enumerate() {
        for (j, row) in plane.iter().enumerate() {
            for (k, c) in row.iter().enumerate() {
                if !c.is_zero() {
                    out.push((i + 1, j + 1, k + 1, c));
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::Derivation;

    /// `D` by composite rigid bodies, expanded, is the Jacobian route's `D` polynomial for
    /// polynomial (and the same `constant`), from a composite-body `D` of its own and from the
    /// compact dynamics' `D`: on every example (a payload, geared drives, both conventions, URDF
    /// input, numeric and symbolic parameters) and on random chains of up to five joints. Either
    /// route may be taken ([`by_composite_bodies`]); the derivation is the same.
    #[test]
    fn composite_bodies_give_the_jacobians_mass_matrix() {
        let robots = crate::test_support::example_robots(5, 7);
        let mut varying = 0;
        for robot in robots {
            let name = robot.name.clone();
            let der = Derivation::new(robot).unwrap();
            let by_jacobians = MassMatrix::derive(der.robot(), der.kinematics());
            let own = MassMatrix::from_composite_bodies(der.robot(), der.joints(), None);
            let from_compact =
                MassMatrix::from_composite_bodies(der.robot(), der.joints(), Some(der.compact()));
            for composite in [own, from_compact] {
                assert_eq!(composite.d, by_jacobians.d, "{name}");
                assert_eq!(composite.constant, by_jacobians.constant, "{name}");
            }
            varying += usize::from(!by_jacobians.constant);
        }
        assert!(varying > 10, "{varying} robots with a D that depends on q");
    }

    /// The route is the Jacobians' for a small or symbolic robot and composite bodies' for a large
    /// or numeric one, or whenever the compact dynamics are there to expand.
    #[test]
    fn the_route_to_d_follows_its_measured_costs() {
        assert!(
            !by_composite_bodies(4_768, false, false),
            "the Stanford arm"
        );
        assert!(
            !by_composite_bodies(17_786, false, false),
            "the symbolic PUMA 560"
        );
        assert!(by_composite_bodies(57_741, true, false), "the Franka Panda");
        assert!(by_composite_bodies(61_160, false, false), "a 6-joint chain");
        assert!(
            by_composite_bodies(7_397, true, false),
            "the numeric PUMA 560"
        );
        assert!(!by_composite_bodies(93, true, false), "a numeric SCARA arm");
        assert!(
            by_composite_bodies(93, false, true),
            "expanded from the compact D"
        );
    }
}
