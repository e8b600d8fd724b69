//! The grouping coefficients as expressions in the geometry, from the joint axes: Khalil's grouping
//! rules derived symbolically, for any convention and any symbolic twist.
//!
//! Interpolating the coefficients at random geometry ([`super::base`]) works while they are
//! polynomials of low degree in a few lengths. With a symbolic twist they hold its sine and cosine to
//! a degree that grows along the chain, and in standard DH they are not even polynomials (`−tan α_j`:
//! the axis of joint `j` is `(0, sin α_j, cos α_j)` in frame `j`). This module derives them from
//! the mechanics instead (Khalil and Dombre, *Modeling, Identification and Control of Robots*,
//! §12.4; Mayeda, Yoshida and Osuka, 1990):
//!
//! - **Joint `j ≥ 2` revolute**, axis `u` through the point `A` (both in frame `j`): three bodies of
//!   link `j` are invariant under the joint's rotation and their kinetic energy does not hold `q̇_j`:
//!   a unit mass at `A`, a massless unit first moment along `u` at `A`, and the inertia `E − u uᵀ`. Each
//!   moves the same whether fixed to link `j` or to link `j − 1`, so its standard parameters in frame
//!   `j` give the same column of `Y` as its parameters carried into frame `j − 1` (the transform at
//!   `q_j = 0`): three linear relations between the columns of links `j` and `j − 1`.
//! - **Joint `j ≥ 2` prismatic**: the six massless inertias `E_ab` do not feel the translation.
//! - **Link 1** turns about (or slides along) a fixed axis: its columns depend on its parameters only
//!   through the inertia about the axis `uᵀ J_A u` (plus the rotor `Ia1`), the first moment about the
//!   axis `u × (h − m A)` when gravity is not along the axis, and the friction coefficients.
//! - **Links 2, 3, … of parallel revolute axes from the base** turn in a plane: each acts only
//!   through `uᵀ J_A u`, `u × (h − m A)` and its mass, and the unit mass at `A` is the part that the
//!   link before carries (as above). A dependent column is solved as a combination of the link's
//!   pivots and that carried part.
//!
//! The elimination fixes which columns are dependent. Link by link, the relations are solved for the
//! dependent columns of that link, the dependent columns of the link before replaced by what they
//! were found to be. Each solve divides by the determinant of a small block, a product of sines,
//! cosines and lengths (anything else is refused). The coefficients are therefore Laurent
//! polynomials: `cos α_2 / sin α_2`, written over one denominator monomial. They are proved like any
//! others, with the denominators cleared ([`super::base`]).
//!
//! Where these relations are not all of them (other special geometry with a symbolic twist: a
//! prismatic joint along or across the axis before it, parallel axes further out) the count of
//! dependent columns differs, or a determinant is no monomial, and this module says so; the count
//! and the grouping are still exact.

use super::regressor::Regressor;
use super::standard::{Quantity, StandardParam};
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::poly::Mono;
use crate::algebra::{subs, to_poly, Expr, Poly, Rational, Symbol};
use crate::dynamics::kinematics::joint_frame;
use crate::dynamics::vec3::{Mat3, Vec3};
use crate::dynamics::JointKind;
use std::collections::{BTreeMap, HashMap};

/// A body's standard parameters about its frame's origin: inertia tensor, first moment, mass.
#[derive(Clone, Debug)]
struct Body {
    j: Mat3<Poly>,
    h: Vec3<Poly>,
    m: Poly,
}

impl Body {
    /// The body of one unit standard parameter.
    fn unit(q: Quantity) -> Option<Body> {
        let mut b = Body {
            j: Mat3::zero(),
            h: Vec3::zero(),
            m: Poly::zero(),
        };
        match q {
            Quantity::Mx => b.h.0[0] = Poly::one(),
            Quantity::My => b.h.0[1] = Poly::one(),
            Quantity::Mz => b.h.0[2] = Poly::one(),
            Quantity::M => b.m = Poly::one(),
            _ => {
                let (r, c) = super::standard::inertia_entry(q)?;
                b.j.0[r][c] = Poly::one();
                b.j.0[c][r] = Poly::one();
            }
        }
        Some(b)
    }

    /// The value of standard parameter `q` of this body (`None` for a joint's own parameters).
    fn param(&self, q: Quantity) -> Option<Poly> {
        Some(match q {
            Quantity::Mx => self.h.0[0].clone(),
            Quantity::My => self.h.0[1].clone(),
            Quantity::Mz => self.h.0[2].clone(),
            Quantity::M => self.m.clone(),
            _ => {
                let (r, c) = super::standard::inertia_entry(q)?;
                self.j.0[r][c].clone()
            }
        })
    }

    /// The inertia about the point `a` (same frame): `J + [h]×[a]× + [a]×[h]× − m [a]×²`.
    fn inertia_about(&self, a: &Vec3<Poly>) -> Mat3<Poly> {
        let (sh, sa) = (skew(&self.h), skew(a));
        let sa2 = sa.mul(&sa);
        self.j
            .add(&sh.mul(&sa).add(&sa.mul(&sh)))
            .add(&sa2.scale(&self.m.neg()))
    }

    /// The same body in the frame before: axes `r`, origin `p` of this frame there.
    /// `J' = R J Rᵀ − [Rh]×[p]× − [p]×[Rh]× − m [p]×²`, `h' = R h + m p`.
    fn carried(&self, r: &Mat3<Poly>, p: &Vec3<Poly>) -> Body {
        let rh = r.mul_vec(&self.h);
        let (srh, sp) = (skew(&rh), skew(p));
        let rjr = r.mul(&self.j).mul(&r.transpose());
        let cross = srh.mul(&sp).add(&sp.mul(&srh));
        let j = rjr
            .add(&cross.scale(&Poly::int(-1)))
            .add(&sp.mul(&sp).scale(&self.m.neg()));
        Body {
            j,
            h: rh.add(&p.scale(&self.m)),
            m: self.m.clone(),
        }
    }
}

fn skew(v: &Vec3<Poly>) -> Mat3<Poly> {
    let [x, y, z] = &v.0;
    Mat3([
        [Poly::zero(), z.neg(), y.clone()],
        [z.clone(), Poly::zero(), x.neg()],
        [y.neg(), x.clone(), Poly::zero()],
    ])
}

/// One joint's geometry at `q_j = 0`: the axes `rot` and origin `origin` of frame `j` in frame
/// `j − 1`, the joint axis `u` and a point `a` of it in frame `j`.
struct JointAtZero {
    kind: JointKind,
    rot: Mat3<Poly>,
    origin: Vec3<Poly>,
    u: Vec3<Poly>,
    a: Vec3<Poly>,
    rate: Poly,
}

fn joint_at_zero(reg: &Regressor, j: usize) -> Result<JointAtZero, String> {
    let mut model = reg.model.clone();
    let zero: HashMap<Symbol, Expr> = [(Symbol::q(j as u32), Expr::int(0))].into();
    let joint = &mut model.joints[j - 1];
    let at = |e: &Expr| subs(e, &zero).map_err(|e| e.to_string());
    joint.theta = at(&joint.theta)?;
    joint.d = at(&joint.d)?;
    // The rate `∂θ_j/∂q_j` comes from the original joint.
    let rate = joint_frame(&reg.model, j).rate;
    let jf = joint_frame(&model, j);
    let a = jf.rot.tr_mul_vec(&jf.joint_point.sub(&jf.origin));
    Ok(JointAtZero {
        kind: jf.kind,
        rot: jf.rot,
        origin: jf.origin,
        u: jf.axis_local,
        a,
        rate,
    })
}

/// `p / x` when the atom `x` (a length or a cosine) divides every term.
fn divide_atom(p: &Poly, x: AtomId) -> Option<Poly> {
    if !p.terms().iter().all(|(m, _)| m.exponent(x) >= 1) {
        return None;
    }
    Some(Poly::from_terms(
        p.terms().iter().map(|(m, c)| (lower(m, x, 1), c.clone())),
    ))
}

/// The monomial `m` with the exponent of `x` lowered by `k`.
fn lower(m: &Mono, x: AtomId, k: i32) -> Mono {
    if k == 0 {
        return m.clone();
    }
    let mut f: Vec<(AtomId, i32)> = m.factors().to_vec();
    match f.binary_search_by_key(&x, |(a, _)| *a) {
        Ok(i) => {
            f[i].1 -= k;
            if f[i].1 == 0 {
                f.remove(i);
            }
        }
        Err(i) => f.insert(i, (x, -k)),
    }
    Mono::from_sorted(f)
}

/// `p / sin y` (as functions) for the sine atom `s` of `y`, when it divides: `p = A + s B` with `A`
/// free of `s` divides exactly when `1 − cos² y` divides `A` (then `p / s = s A/(1 − c²) + B`).
fn divide_sin(p: &Poly, s: AtomId) -> Option<Poly> {
    let c = atom::partner(s);
    // A as a polynomial in c: degree → coefficient.
    let mut a: BTreeMap<i32, Vec<(Mono, Rational)>> = BTreeMap::new();
    let mut b: Vec<(Mono, Rational)> = Vec::new();
    for (m, k) in p.terms() {
        match m.exponent(s) {
            0 => {
                let e = m.exponent(c);
                if e < 0 {
                    return None;
                }
                a.entry(e).or_default().push((lower(m, c, e), k.clone()));
            }
            1 => b.push((lower(m, s, 1), k.clone())),
            _ => return None,
        }
    }
    let coeff = |k: i32| Poly::from_terms(a.get(&k).cloned().unwrap_or_default());
    let top = a.keys().next_back().copied().unwrap_or(0);
    // A = (1 − c²) Q: a_k = q_k − q_{k−2}, so q_{k−2} = q_k − a_k from the top.
    let mut q: BTreeMap<i32, Poly> = BTreeMap::new();
    let get = |q: &BTreeMap<i32, Poly>, k: i32| q.get(&k).cloned().unwrap_or_else(Poly::zero);
    for k in (2..=top).rev() {
        let v = get(&q, k).sub(&coeff(k));
        q.insert(k - 2, v);
    }
    if get(&q, 1).sub(&coeff(1)) != Poly::zero() || get(&q, 0).sub(&coeff(0)) != Poly::zero() {
        return None;
    }
    let sp = Poly::atom(s);
    let cp = Poly::atom(c);
    let quotient = q.iter().fold(Poly::zero(), |acc, (&k, v)| {
        acc.add(&v.mul(&cp.pow(k as u32)))
    });
    Some(sp.mul(&quotient).add(&Poly::from_terms(b)))
}

/// Divides `p` by the atom `x` (a length, a cosine or a sine of the geometry) when it can.
fn divide(p: &Poly, x: AtomId) -> Option<Poly> {
    match atom::class(x) {
        Class::Param | Class::Cos => divide_atom(p, x),
        Class::Sin => divide_sin(p, x),
        _ => None,
    }
}

/// The monomial `Π x^e` (exponents of either sign).
fn monomial(factors: &BTreeMap<AtomId, i32>, sign: i32) -> Poly {
    factors.iter().fold(Poly::one(), |acc, (&x, &e)| {
        acc.mul(&Poly::term(Mono::atom(x, sign * e), Rational::one()))
    })
}

/// `1 / p` when `p` is a non-zero constant times a product of lengths, sines and cosines.
fn monomial_inverse(p: &Poly) -> Option<Poly> {
    let mut p = p.clone();
    let mut factors: BTreeMap<AtomId, i32> = BTreeMap::new();
    loop {
        if let Some(c) = p.as_constant() {
            return Some(monomial(&factors, -1).scale(&c.recip()?));
        }
        // A sine may divide where only its cosine shows: 1 − cos² y = sin² y.
        let next = p
            .atoms()
            .into_iter()
            .flat_map(|x| {
                let sine = (atom::class(x) == Class::Cos).then(|| atom::partner(x));
                std::iter::once(x).chain(sine)
            })
            .find_map(|x| divide(&p, x).map(|q| (x, q)));
        let (x, q) = next?;
        *factors.entry(x).or_default() += 1;
        p = q;
    }
}

/// The denominator of a Laurent polynomial: every atom's most negative exponent, negated.
fn denominator_factors(x: &Poly) -> Denominator {
    let mut den = Denominator::new();
    for (m, _) in x.terms() {
        for &(a, e) in m.factors() {
            if e < 0 {
                let d = den.entry(a).or_default();
                *d = (*d).max(-e);
            }
        }
    }
    den
}

/// A denominator: atoms (lengths, sines, cosines) with positive exponents.
pub(super) type Denominator = BTreeMap<AtomId, i32>;

/// The least common multiple of the denominators of several Laurent polynomials.
pub(super) fn common_denominator<'a>(xs: impl IntoIterator<Item = &'a Poly>) -> Denominator {
    let mut den = Denominator::new();
    for x in xs {
        for (a, e) in denominator_factors(x) {
            let d = den.entry(a).or_default();
            *d = (*d).max(e);
        }
    }
    den
}

/// `x · Π a^e` (`sign` 1) or `x / Π a^e` (`sign` −1), exponents added term by term before the
/// terms are reduced, so a denominator cancels exactly (multiplying by the reduced `sin² = 1 − cos²`
/// would not cancel `sin⁻²`).
pub(super) fn times(x: &Poly, den: &Denominator, sign: i32) -> Poly {
    if den.is_empty() {
        return x.clone();
    }
    Poly::from_terms(x.terms().iter().map(|(m, c)| {
        let shifted = den
            .iter()
            .fold(m.clone(), |acc, (&a, &e)| lower(&acc, a, -sign * e));
        (shifted, c.clone())
    }))
}

/// A Laurent polynomial in lowest terms: the terms grouped by their lengths (everything but sines
/// and cosines), each group's trigonometric factor written over its least denominator
/// ([`over_least_denominator`]). `a² (1 − cos² α)/sin² α` is `a²`; equal functions print equally.
fn lowest_terms(x: &Poly) -> Poly {
    if denominator_factors(x).is_empty() {
        return x.clone();
    }
    let trig = |a: AtomId| matches!(atom::class(a), Class::Sin | Class::Cos);
    let mut groups: BTreeMap<Mono, Vec<(Mono, Rational)>> = BTreeMap::new();
    for (m, c) in x.terms() {
        let (t, rest): (Vec<_>, Vec<_>) = m.factors().iter().partition(|(a, _)| trig(*a));
        groups
            .entry(Mono::from_sorted(rest))
            .or_default()
            .push((Mono::from_sorted(t), c.clone()));
    }
    let parts: Vec<Poly> = groups
        .into_iter()
        .map(|(rest, t)| {
            over_least_denominator(&Poly::from_terms(t)).mul(&Poly::term(rest, Rational::one()))
        })
        .collect();
    Poly::sum(parts.iter())
}

/// A Laurent polynomial written over its least denominator: `N / D` with `N` in normal form and no
/// atom of `D` dividing `N`.
fn over_least_denominator(x: &Poly) -> Poly {
    let mut den = denominator_factors(x);
    if den.is_empty() {
        return x.clone();
    }
    let mut n = times(x, &den, 1);
    for (&a, e) in den.iter_mut() {
        while *e > 0 {
            match divide(&n, a) {
                Some(q) => {
                    n = q;
                    *e -= 1;
                }
                None => break,
            }
        }
    }
    den.retain(|_, e| *e > 0);
    times(&n, &den, -1)
}

/// The determinant of a small square matrix (Laplace expansion along the first row).
fn det(m: &[Vec<Poly>]) -> Poly {
    match m.len() {
        0 => Poly::one(),
        1 => m[0][0].clone(),
        n => (0..n).fold(Poly::zero(), |acc, c| {
            if m[0][c].is_zero() {
                return acc;
            }
            let minor: Vec<Vec<Poly>> = m[1..]
                .iter()
                .map(|row| {
                    row.iter()
                        .enumerate()
                        .filter(|&(k, _)| k != c)
                        .map(|(_, v)| v.clone())
                        .collect()
                })
                .collect();
            let t = m[0][c].mul(&det(&minor));
            if c % 2 == 0 {
                acc.add(&t)
            } else {
                acc.sub(&t)
            }
        }),
    }
}

/// Solves `m x = b` for each right side `b` by Cramer's rule, when `det m` is a monomial.
fn solve(m: &[Vec<Poly>], rhs: &[Vec<Poly>]) -> Option<Vec<Vec<Poly>>> {
    let inv = monomial_inverse(&det(m))?;
    let n = m.len();
    Some(
        rhs.iter()
            .map(|b| {
                (0..n)
                    .map(|c| {
                        let replaced: Vec<Vec<Poly>> = m
                            .iter()
                            .zip(b)
                            .map(|(row, bv)| {
                                let mut r = row.clone();
                                r[c] = bv.clone();
                                r
                            })
                            .collect();
                        lowest_terms(&det(&replaced).mul(&inv))
                    })
                    .collect()
            })
            .collect(),
    )
}

/// All `k`-subsets of `0..n`, in lexicographic order.
fn subsets(n: usize, k: usize) -> Vec<Vec<usize>> {
    fn go(start: usize, n: usize, k: usize, cur: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        if cur.len() == k {
            out.push(cur.clone());
            return;
        }
        for i in start..n {
            cur.push(i);
            go(i + 1, n, k, cur, out);
            cur.pop();
        }
    }
    let mut out = Vec::new();
    go(0, n, k, &mut Vec::new(), &mut out);
    out
}

/// How many links from the base turn in a plane: joints `1..=k` revolute about parallel axes (0 when
/// joint 1 is prismatic or a joint's geometry cannot be read at `q = 0`).
pub(super) fn planar_links(reg: &Regressor) -> usize {
    let mut k = 0;
    let mut prev: Option<JointAtZero> = None;
    for j in 1..=reg.dof() {
        let Ok(jz) = joint_at_zero(reg, j) else {
            break;
        };
        let parallel = prev.as_ref().is_none_or(|p| parallel_to_previous(&jz, p));
        if jz.kind != JointKind::Revolute || !parallel {
            break;
        }
        k = j;
        prev = Some(jz);
    }
    k
}

/// The grouping coefficients `x[d][r]` (dependent column `dependent[d]`, pivot `pivots[r]`, both
/// indices of standard parameters) with `Y_d = Σ_r x[d][r] Y_{pivots[r]}`, from the joint axes.
pub(super) fn coefficients(
    reg: &Regressor,
    pivots: &[usize],
    dependent: &[usize],
) -> Result<Vec<Vec<Poly>>, String> {
    let np = reg.params.len();
    let n = reg.dof();
    let index: HashMap<StandardParam, usize> = reg
        .params
        .iter()
        .enumerate()
        .map(|(k, p)| (*p, k))
        .collect();
    let zero: Vec<bool> = (0..np).map(|k| reg.zero_column(k)).collect();
    let is_pivot: Vec<bool> = (0..np).map(|k| pivots.contains(&k)).collect();
    // The form of every dependent column found so far: its coefficients over all columns, pivots only.
    let mut forms: HashMap<usize, Vec<Poly>> = HashMap::new();
    let resolve = |f: &[Poly], forms: &HashMap<usize, Vec<Poly>>| -> Result<Vec<Poly>, String> {
        let mut out = vec![Poly::zero(); np];
        for (k, c) in f.iter().enumerate() {
            if c.is_zero() || zero[k] {
                continue;
            }
            if is_pivot[k] {
                out[k] = out[k].add(c);
            } else {
                let g = forms.get(&k).ok_or_else(|| {
                    format!(
                        "{} is grouped before its own link's rule gives it",
                        reg.params[k].name()
                    )
                })?;
                for (o, gv) in out.iter_mut().zip(g) {
                    if !gv.is_zero() {
                        *o = o.add(&c.mul(gv));
                    }
                }
            }
        }
        Ok(out.iter().map(lowest_terms).collect())
    };
    let link_cols =
        |j: usize| -> Vec<usize> { (0..np).filter(|&k| reg.params[k].link == j).collect() };
    let joints: Vec<JointAtZero> = (1..=n)
        .map(|j| joint_at_zero(reg, j))
        .collect::<Result<_, _>>()?;
    // Whether joints 1..j are revolute about parallel axes (links 2..j turn in a plane).
    let mut planar = true;
    for j in 1..=n {
        let jz = &joints[j - 1];
        planar = planar
            && jz.kind == JointKind::Revolute
            && (j == 1 || parallel_to_previous(jz, &joints[j - 2]));
        let cols = link_cols(j);
        let dep: Vec<usize> = cols
            .iter()
            .copied()
            .filter(|k| dependent.contains(k))
            .collect();
        if dep.is_empty() {
            continue;
        }

        // Link 1 turns about (or slides along) a fixed axis; links 2.. of a chain of parallel
        // revolute axes from the base turn in a plane: either acts through a few quantities.
        if j == 1 || planar {
            let rows = if j == 1 {
                link_one_rows(reg, jz, &cols, &index)?
            } else {
                planar_rows(reg, jz, &cols)
            };
            // Link j ≥ 2: the unit mass on joint j's axis is the part of link j that the link
            // before carries (its quantities known through link j − 1's columns).
            let known: Vec<(Vec<Poly>, Vec<Poly>)> = if j == 1 {
                vec![]
            } else {
                let b1 = point_mass(&jz.a);
                let mut carried = vec![Poly::zero(); np];
                for (k, v) in in_link(&b1.carried(&jz.rot, &jz.origin), j - 1, &index) {
                    carried[k] = carried[k].add(&v);
                }
                vec![(quantities(&b1, jz).to_vec(), carried)]
            };
            let piv: Vec<usize> = cols.iter().copied().filter(|&k| is_pivot[k]).collect();
            let x = solve_effective(&rows, &piv, &known, &dep).ok_or_else(|| {
                format!("the quantities link {j} acts through give no monomial determinant")
            })?;
            for (d, xd) in dep.iter().zip(x) {
                let mut f = vec![Poly::zero(); np];
                for (k, v) in piv.iter().zip(&xd) {
                    f[*k] = v.clone();
                }
                for ((_, carried), xk) in known.iter().zip(&xd[piv.len()..]) {
                    for (o, c) in f.iter_mut().zip(carried) {
                        if !c.is_zero() {
                            *o = o.add(&xk.mul(c));
                        }
                    }
                }
                let f = resolve(&f, &forms)?;
                forms.insert(*d, f);
            }
            continue;
        }
        // Joint j ≥ 2: the invariant bodies of link j, in frame j.
        let bodies: Vec<Body> = match jz.kind {
            JointKind::Revolute => {
                let (u, a) = (&jz.u, &jz.a);
                let (su, sa) = (skew(u), skew(a));
                let uu = Mat3(std::array::from_fn(|r| {
                    std::array::from_fn(|c| u.0[r].mul(&u.0[c]))
                }));
                vec![
                    point_mass(a),
                    Body {
                        j: su.mul(&sa).add(&sa.mul(&su)).scale(&Poly::int(-1)),
                        h: u.clone(),
                        m: Poly::zero(),
                    },
                    Body {
                        j: Mat3::identity().add(&uu.scale(&Poly::int(-1))),
                        h: Vec3::zero(),
                        m: Poly::zero(),
                    },
                ]
            }
            JointKind::Prismatic => Quantity::LINK[..6]
                .iter()
                .map(|&q| Body::unit(q).expect("an inertia entry"))
                .collect(),
        };
        // A structurally zero column the rule touches depends on the others too: the rule may be
        // solved for it.
        let touched_zero = |k: usize| {
            zero[k]
                && bodies.iter().any(|b| {
                    b.param(reg.params[k].quantity)
                        .is_some_and(|v| !v.is_zero())
                })
        };
        let dep_or_zero: Vec<usize> = cols
            .iter()
            .copied()
            .filter(|&k| dependent.contains(&k) || touched_zero(k))
            .collect();
        let dep = if dep.len() == bodies.len() {
            dep
        } else if dep_or_zero.len() == bodies.len() {
            dep_or_zero
        } else {
            return Err(format!(
                "link {j} has {} grouped parameters where the rule of joint {j} gives {}: special geometry, whose rules are not derived symbolically",
                dep.len(),
                bodies.len()
            ));
        };
        // Relation i: Σ_k b_ik Y_k (link j) = Σ_k (T b_i)_k Y_k (link j − 1).
        let mut m: Vec<Vec<Poly>> = Vec::new();
        let mut rhs: Vec<Vec<Poly>> = Vec::new(); // rhs[i]: the relation's right side over all columns
        for b in &bodies {
            let own = in_link(b, j, &index);
            let carried = in_link(&b.carried(&jz.rot, &jz.origin), j - 1, &index);
            let mut r = vec![Poly::zero(); np];
            for (k, v) in carried {
                r[k] = r[k].add(&v);
            }
            let mut row = vec![Poly::zero(); dep.len()];
            for (k, v) in own {
                match dep.iter().position(|&d| d == k) {
                    Some(i) => row[i] = v,
                    None => r[k] = r[k].sub(&v),
                }
            }
            m.push(row);
            rhs.push(r);
        }
        // x = m⁻¹ (rhs): solve column by column of the right side, for every column it touches.
        let touched: Vec<usize> = (0..np)
            .filter(|&k| rhs.iter().any(|r| !r[k].is_zero()))
            .collect();
        let sides: Vec<Vec<Poly>> = touched
            .iter()
            .map(|&k| rhs.iter().map(|r| r[k].clone()).collect())
            .collect();
        let sol = solve(&m, &sides).ok_or_else(|| {
            format!("the rule of joint {j} divides by a determinant that is not a product of sines, cosines and lengths")
        })?;
        let mut raw: Vec<Vec<Poly>> = vec![vec![Poly::zero(); np]; dep.len()];
        for (t, &k) in touched.iter().enumerate() {
            for (i, f) in raw.iter_mut().enumerate() {
                f[k] = sol[t][i].clone();
            }
        }
        for (i, &d) in dep.iter().enumerate() {
            let f = resolve(&raw[i], &forms)?;
            forms.insert(d, f);
        }
    }
    dependent
        .iter()
        .map(|d| {
            let f = forms
                .get(d)
                .ok_or_else(|| format!("no rule groups {}", reg.params[*d].name()))?;
            Ok(pivots.iter().map(|&r| lowest_terms(&f[r])).collect())
        })
        .collect()
}

/// The standard parameters of a body in link `link`'s columns: `(column, value)`.
fn in_link(b: &Body, link: usize, index: &HashMap<StandardParam, usize>) -> Vec<(usize, Poly)> {
    Quantity::LINK
        .iter()
        .filter_map(|&q| {
            let k = *index.get(&StandardParam { link, quantity: q })?;
            Some((k, b.param(q)?))
        })
        .collect()
}

/// A unit point mass at `a`: `J = −[a]×²`, `h = a`, `m = 1`.
fn point_mass(a: &Vec3<Poly>) -> Body {
    let sa = skew(a);
    Body {
        j: sa.mul(&sa).scale(&Poly::int(-1)),
        h: a.clone(),
        m: Poly::one(),
    }
}

/// Whether joint `jz`'s axis is parallel to the axis of the joint before it (`prev`), both in the
/// frame between them.
fn parallel_to_previous(jz: &JointAtZero, prev: &JointAtZero) -> bool {
    jz.rot.mul_vec(&jz.u).cross(&prev.u).is_exact_zero()
}

/// What a link turning in a plane (about axes parallel to its own joint's, `u` through `A`) acts
/// through: its inertia about the axis `uᵀ J_A u`, its first moment across the axis
/// `u × (h − m A)` (three components, two independent) and its mass.
fn quantities(b: &Body, jz: &JointAtZero) -> [Poly; 5] {
    let ja = b.inertia_about(&jz.a);
    let w = jz.u.cross(&b.h.sub(&jz.a.scale(&b.m)));
    let [w0, w1, w2] = w.0;
    [jz.u.dot(&ja.mul_vec(&jz.u)), w0, w1, w2, b.m.clone()]
}

/// The rows of [`quantities`] over the inertial columns of a link turning in a plane.
fn planar_rows(reg: &Regressor, jz: &JointAtZero, cols: &[usize]) -> Vec<BTreeMap<usize, Poly>> {
    let mut rows = vec![BTreeMap::new(); 5];
    for &k in cols {
        if let Some(b) = Body::unit(reg.params[k].quantity) {
            for (row, v) in rows.iter_mut().zip(quantities(&b, jz)) {
                row.insert(k, v);
            }
        }
    }
    // All five rows stay, in order: the known parts' values are indexed by them.
    rows
}

/// For each dependent column `d`: `x` with `Σ_p x_p L[·][p] + Σ_b x_b known_b = L[·][d]` over the
/// rows `L` of what the link acts through (`known_b`: a quantity's values per row, for a part of
/// the link the link before carries), from a square choice of rows whose determinant is a
/// monomial. `x` lists the pivots' coefficients, then the known parts'.
fn solve_effective(
    rows: &[BTreeMap<usize, Poly>],
    piv: &[usize],
    known: &[(Vec<Poly>, Vec<Poly>)],
    dep: &[usize],
) -> Option<Vec<Vec<Poly>>> {
    let at =
        |row: &BTreeMap<usize, Poly>, k: usize| row.get(&k).cloned().unwrap_or_else(Poly::zero);
    let width = piv.len() + known.len();
    if width == 0 {
        // Nothing to group into: every dependent column must act through nothing.
        return dep
            .iter()
            .all(|&d| rows.iter().all(|r| at(r, d).is_zero()))
            .then(|| vec![vec![]; dep.len()]);
    }
    // A known part's values are indexed like the rows (the five planar quantities).
    let value =
        |i: usize, b: &(Vec<Poly>, Vec<Poly>)| b.0.get(i).cloned().unwrap_or_else(Poly::zero);
    subsets(rows.len(), width).into_iter().find_map(|pick| {
        let m: Vec<Vec<Poly>> = pick
            .iter()
            .map(|&i| {
                piv.iter()
                    .map(|&k| at(&rows[i], k))
                    .chain(known.iter().map(|b| value(i, b)))
                    .collect()
            })
            .collect();
        let rhs: Vec<Vec<Poly>> = dep
            .iter()
            .map(|&d| pick.iter().map(|&i| at(&rows[i], d)).collect())
            .collect();
        solve(&m, &rhs)
    })
}

/// The rows of link 1's effective quantities over its columns (`column → coefficient`).
fn link_one_rows(
    reg: &Regressor,
    jz: &JointAtZero,
    cols: &[usize],
    index: &HashMap<StandardParam, usize>,
) -> Result<Vec<BTreeMap<usize, Poly>>, String> {
    let rate = jz
        .rate
        .as_constant()
        .filter(|r| !r.is_zero())
        .ok_or("the rate of joint 1 is not a constant")?;
    let inv_rate2 = (&rate * &rate).recip().expect("non-zero");
    let gravity: Vec<Poly> = reg.model.gravity.iter().map(to_poly).collect();
    let g = Vec3([gravity[0].clone(), gravity[1].clone(), gravity[2].clone()]);
    let axis0 = jz.rot.mul_vec(&jz.u);
    let mut kinetic = BTreeMap::new();
    let mut potential: Vec<BTreeMap<usize, Poly>> = Vec::new();
    let mut other = Vec::new();
    match jz.kind {
        JointKind::Revolute => {
            let across = !g.cross(&axis0).is_exact_zero();
            if across {
                potential = vec![BTreeMap::new(); 3];
            }
            for &k in cols {
                let q = reg.params[k].quantity;
                if let Some(b) = Body::unit(q) {
                    let ja = b.inertia_about(&jz.a);
                    let v = jz.u.dot(&ja.mul_vec(&jz.u));
                    kinetic.insert(k, v);
                    if across {
                        let w = jz.u.cross(&b.h.sub(&jz.a.scale(&b.m)));
                        for (row, wv) in potential.iter_mut().zip(w.0) {
                            row.insert(k, wv);
                        }
                    }
                }
            }
        }
        JointKind::Prismatic => {
            let along = !g.dot(&axis0).is_zero();
            let m = *index
                .get(&StandardParam {
                    link: 1,
                    quantity: Quantity::M,
                })
                .expect("every link has a mass column");
            kinetic.insert(m, Poly::one());
            if along {
                potential.push([(m, Poly::one())].into());
            }
        }
    }
    for &k in cols {
        match reg.params[k].quantity {
            Quantity::Ia => {
                kinetic.insert(k, Poly::constant(inv_rate2.clone()));
            }
            Quantity::Fv | Quantity::Fc => other.push([(k, Poly::one())].into()),
            _ => {}
        }
    }
    let mut rows = vec![kinetic];
    rows.extend(potential);
    rows.extend(other);
    rows.retain(|r: &BTreeMap<usize, Poly>| r.values().any(|v| !v.is_zero()));
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn sines_cosines_and_lengths_divide_out() {
        let d = p("3*sin(al)^2*cos(al)*a2");
        let inv = monomial_inverse(&d).expect("a monomial");
        assert_eq!(lowest_terms(&inv.mul(&d)), Poly::one());
        assert!(monomial_inverse(&p("1 + cos(al)")).is_none());
        assert!(monomial_inverse(&p("a2 + a3")).is_none());
        assert!(monomial_inverse(&Poly::zero()).is_none());
        // sin² written as 1 − cos².
        let s2 = p("1 - cos(al)^2");
        assert_eq!(
            lowest_terms(&monomial_inverse(&s2).unwrap().mul(&s2)),
            Poly::one()
        );
    }

    #[test]
    fn lowest_terms_cancels_what_divides() {
        // (sin² · cos) / (sin · cos²) = sin / cos.
        let x = p("sin(al)^2*cos(al)").mul(&monomial_inverse(&p("sin(al)*cos(al)^2")).unwrap());
        assert_eq!(lowest_terms(&x), p("sin(al)/cos(al)"));
        assert_eq!(
            times(&Poly::one(), &common_denominator([&lowest_terms(&x)]), 1),
            p("cos(al)")
        );
        // cos² / sin⁴ − cos⁴ / sin⁴ = cos² / sin².
        let y = p("cos(al)^2 - cos(al)^4").mul(&monomial_inverse(&p("sin(al)^4")).unwrap());
        assert_eq!(lowest_terms(&y), p("cos(al)^2/sin(al)^2"));
        // Each length's factor on its own: a² (1 − cos² α)/sin² α + b cos α / sin α.
        let z = p("a^2 - a^2*cos(al)^2 + b*cos(al)*sin(al)")
            .mul(&monomial_inverse(&p("sin(al)^2")).unwrap());
        assert_eq!(lowest_terms(&z), p("a^2 + b*cos(al)/sin(al)"));
    }
}
