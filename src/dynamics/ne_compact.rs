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

use super::kinematics::{joint_frame, JointFrame};
use super::model::{JointKind, ModelError, Robot};
use super::vec3::{Mat3, Vec3};
use crate::algebra::atom::AtomId;
use crate::algebra::poly::Mono;
use crate::algebra::{eval_f64, to_poly, EvalError, Expr, Poly, Rational, Symbol};
use std::collections::{HashMap, HashSet};

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

/// Records named intermediates, hash-consed by canonical form.
struct Builder {
    lines: Vec<Intermediate>,
    index: HashMap<Poly, usize>,
    taken: HashSet<String>,
}

/// Whether a value is propagated inline: a constant (zero included), an atom or `−atom`.
fn trivial(p: &Poly) -> bool {
    if p.as_constant().is_some() {
        return true;
    }
    match p.terms() {
        [(m, c)] => matches!(m.factors(), [(_, 1)]) && c.abs() == Rational::one(),
        _ => false,
    }
}

impl Builder {
    fn new(robot: &Robot) -> Builder {
        let mut taken = HashSet::new();
        let mut note = |e: &Expr| {
            for s in e.symbols() {
                if let Some(n) = s.param_name() {
                    taken.insert(n.to_string());
                }
            }
        };
        robot.gravity.iter().for_each(&mut note);
        for j in &robot.joints {
            [&j.a, &j.alpha, &j.d, &j.theta]
                .into_iter()
                .for_each(&mut note);
        }
        for l in &robot.links {
            note(&l.mass);
            l.com.iter().for_each(&mut note);
            if let Some(t) = &l.inertia {
                t.iter().flatten().for_each(&mut note);
            }
        }
        taken.extend(robot.inputs.iter().cloned());
        Builder {
            lines: Vec::new(),
            index: HashMap::new(),
            taken,
        }
    }

    /// The value itself when trivial, else the name of an equal earlier value (or minus the name of
    /// its negative), else a new name `name`.
    fn name(&mut self, value: Poly, name: String) -> Poly {
        if trivial(&value) {
            return value;
        }
        if let Some(&k) = self.index.get(&value) {
            return Poly::symbol(&self.lines[k].symbol);
        }
        let neg = value.neg();
        if let Some(&k) = self.index.get(&neg) {
            return Poly::symbol(&self.lines[k].symbol).neg();
        }
        let mut name = name;
        while self.taken.contains(&name) {
            name.push('_');
        }
        self.taken.insert(name.clone());
        let symbol = Symbol::Param(name.as_str().into());
        self.index.insert(value.clone(), self.lines.len());
        self.lines.push(Intermediate {
            symbol: symbol.clone(),
            value,
        });
        Poly::symbol(&symbol)
    }

    /// Names the components `{base}_1 … {base}_3`.
    fn vec(&mut self, v: Vec3<Poly>, base: &str) -> Vec3<Poly> {
        let [x, y, z] = v.0;
        Vec3([
            self.name(x, format!("{base}_1")),
            self.name(y, format!("{base}_2")),
            self.name(z, format!("{base}_3")),
        ])
    }

    /// Names the entries `{base}_{rc}`.
    fn mat(&mut self, m: Mat3<Poly>, base: &str) -> Mat3<Poly> {
        let mut out = Mat3::zero();
        for (r, row) in m.0.into_iter().enumerate() {
            for (c, v) in row.into_iter().enumerate() {
                out.0[r][c] = self.name(v, format!("{base}_{}{}", r + 1, c + 1));
            }
        }
        out
    }
}

/// `S(v)`, the matrix of `v × ·`.
fn skew(v: &Vec3<Poly>) -> Mat3<Poly> {
    let [x, y, z] = &v.0;
    Mat3([
        [Poly::zero(), z.neg(), y.clone()],
        [z.clone(), Poly::zero(), x.neg()],
        [y.neg(), x.clone(), Poly::zero()],
    ])
}

fn mat_add(a: &Mat3<Poly>, b: &Mat3<Poly>) -> Mat3<Poly> {
    Mat3(std::array::from_fn(|r| {
        std::array::from_fn(|c| a.0[r][c].add(&b.0[r][c]))
    }))
}

fn vec_of(e: &[Expr; 3]) -> Vec3<Poly> {
    Vec3(std::array::from_fn(|k| to_poly(&e[k])))
}

impl CompactProgram {
    /// The compact Newton–Euler program of a robot, in body-fixed frames.
    pub fn derive(robot: &Robot) -> Result<CompactProgram, ModelError> {
        robot.validate()?;
        let n = robot.dof();
        let mut b = Builder::new(robot);
        let locals: Vec<JointFrame> = (1..=n).map(|i| joint_frame(robot, i)).collect();
        let two = Poly::int(2);

        // Forward: ω, α, U, the accelerations less gravity.
        let (mut w_prev, mut wd_prev) = (Vec3::<Poly>::zero(), Vec3::<Poly>::zero());
        let mut ae_prev = vec_of(&robot.gravity).scale(&Poly::int(-1));
        let mut u_prev = Mat3::<Poly>::zero();
        let mut rotates = Vec::with_capacity(n);
        let mut any_revolute = false;
        let (mut omega, mut alpha, mut a_c) = (Vec::new(), Vec::new(), Vec::new());
        for (idx, jf) in locals.iter().enumerate() {
            let i = idx + 1;
            any_revolute |= jf.kind == JointKind::Revolute;
            rotates.push(any_revolute);
            let rt = jf.rot.transpose();
            let (qd, qdd) = (
                jf.rate.mul(&Poly::symbol(&Symbol::qd(i as u32))),
                jf.rate.mul(&Poly::symbol(&Symbol::qdd(i as u32))),
            );
            let w0 = rt.mul_vec(&w_prev);
            let wd0 = rt.mul_vec(&wd_prev);
            let (w, wd) = if jf.kind == JointKind::Revolute {
                let w = b.vec(w0.add(&jf.axis_local.scale(&qd)), &format!("w{i}"));
                let wd = wd0
                    .add(&jf.axis_local.scale(&qdd))
                    .add(&w.cross(&jf.axis_local.scale(&qd)));
                (w, b.vec(wd, &format!("wd{i}")))
            } else {
                (b.vec(w0, &format!("w{i}")), b.vec(wd0, &format!("wd{i}")))
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
            let aj = b.vec(aj, &format!("aj{i}"));
            let s2 = skew(&w);
            let u = b.mat(mat_add(&skew(&wd), &s2.mul(&s2)), &format!("U{i}"));
            let link = &robot.links[idx];
            let r_jo = rt.mul_vec(&jf.origin.sub(&jf.joint_point));
            let r_jc = r_jo.add(&vec_of(&link.com));
            a_c.push(b.vec(aj.add(&u.mul_vec(&r_jc)), &format!("ac{i}")));
            if i < n {
                ae_prev = b.vec(aj.add(&u.mul_vec(&r_jo)), &format!("ae{i}"));
            }
            w_prev = w.clone();
            wd_prev = wd.clone();
            u_prev = u;
            omega.push(w);
            alpha.push(wd);
        }

        // Backward: f, n, τ.
        let mut tau = vec![Poly::zero(); n];
        let (mut f_next, mut n_next) = (Vec3::<Poly>::zero(), Vec3::<Poly>::zero());
        for idx in (0..n).rev() {
            let i = idx + 1;
            let jf = &locals[idx];
            let link = &robot.links[idx];
            let (f_here, n_here, s_next) = match locals.get(idx + 1) {
                Some(next) => (
                    b.vec(next.rot.mul_vec(&f_next), &format!("fc{i}")),
                    next.rot.mul_vec(&n_next),
                    next.joint_point.clone(),
                ),
                None => (Vec3::zero(), Vec3::zero(), Vec3::zero()),
            };
            let mass = to_poly(&link.mass);
            let fi = b.vec(f_here.add(&a_c[idx].scale(&mass)), &format!("f{i}"));
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
                    let jw = b.vec(inertia.mul_vec(&omega[idx]), &format!("jw{i}"));
                    ni = ni
                        .add(&inertia.mul_vec(&alpha[idx]))
                        .add(&omega[idx].cross(&jw));
                }
                let ni = b.vec(ni, &format!("n{i}"));
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
            f_next = fi;
        }
        Ok(CompactProgram {
            intermediates: live(b.lines, &tau),
            tau,
        })
    }

    /// `τ` with every name substituted back, recursively: the fully expanded Newton–Euler `τ`. Swells
    /// exponentially with the number of joints, as the expanded form does.
    pub fn expand(&self) -> Vec<Poly> {
        let mut map: HashMap<AtomId, Poly> = HashMap::new();
        for line in &self.intermediates {
            let value = substitute(&line.value, &map);
            map.insert(crate::algebra::atom::sym(&line.symbol), value);
        }
        self.tau.iter().map(|t| substitute(t, &map)).collect()
    }

    /// `τ` in `f64`, evaluating the program line by line with the symbols valued by `values` (scene
    /// parameters and `q`, `q̇`, `q̈`).
    pub fn eval_f64(&self, values: &HashMap<Symbol, f64>) -> Result<Vec<f64>, EvalError> {
        let mut values = values.clone();
        for line in &self.intermediates {
            let v = eval_f64(&line.value.to_expr(), &values)?;
            values.insert(line.symbol.clone(), v);
        }
        self.tau
            .iter()
            .map(|t| eval_f64(&t.to_expr(), &values))
            .collect()
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

/// The lines that `τ` needs, directly or through later lines, in their order (the moments of link 1
/// about its other axes, for one, serve no `τ`).
fn live(lines: Vec<Intermediate>, tau: &[Poly]) -> Vec<Intermediate> {
    let mut needed: HashSet<AtomId> = tau.iter().flat_map(Poly::atoms).collect();
    let mut keep = vec![false; lines.len()];
    for (k, line) in lines.iter().enumerate().rev() {
        if needed.contains(&crate::algebra::atom::sym(&line.symbol)) {
            keep[k] = true;
            needed.extend(line.value.atoms());
        }
    }
    lines
        .into_iter()
        .zip(keep)
        .filter_map(|(l, k)| k.then_some(l))
        .collect()
}

/// `p` with the atoms of `map` replaced by their polynomials (exponents of mapped atoms are positive,
/// as names only ever appear in products and sums).
fn substitute(p: &Poly, map: &HashMap<AtomId, Poly>) -> Poly {
    let mut parts = Vec::with_capacity(p.len());
    for (m, c) in p.terms() {
        let mut kept = Vec::new();
        let mut prod = Poly::constant(c.clone());
        for &(id, e) in m.factors() {
            match map.get(&id) {
                Some(v) if e > 0 => prod = prod.mul(&v.pow(e as u32)),
                _ => kept.push((id, e)),
            }
        }
        let rest = kept.into_iter().fold(Poly::one(), |acc, (id, e)| {
            acc.mul(&Poly::term(Mono::atom(id, e), Rational::one()))
        });
        parts.push(prod.mul(&rest));
    }
    Poly::sum(parts.iter())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn trivial_values_are_constants_atoms_and_negated_atoms() {
        for (s, want) in [
            ("0", true),
            ("-3/2", true),
            ("x", true),
            ("-cos(q1)", true),
            ("2*x", false),
            ("x*y", false),
            ("x^2", false),
            ("x + 1", false),
        ] {
            assert_eq!(trivial(&p(s)), want, "{s}");
        }
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

    #[test]
    fn substitution_replaces_names_by_their_values() {
        let t = Symbol::new("t");
        let map = HashMap::from([(crate::algebra::atom::sym(&t), p("x + 1"))]);
        assert_eq!(substitute(&p("t^2*y - t"), &map), p("(x + 1)^2*y - x - 1"));
    }
}
