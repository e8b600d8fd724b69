//! Compact quantities lowered into one `f64` operation graph ([`crate::numeric::trace`]'s `Graph`:
//! constants folded, each operation on the same operands recorded once, so common subexpressions are
//! shared across every output asked for).
//!
//! Inputs are graph slots: `q` at `0..n`, `q̇` at `n..2n`, `q̈` at `2n..3n`, `u` at `3n..4n`, the free
//! parameters `p` from `4n` on. A polynomial is lowered in greedy multivariate Horner form: the atom
//! that occurs in most terms is factored out (`a x + b x + c` → `x (a + b) + c`), recursively, so a
//! shared factor costs one multiplication. The forward dynamics `q̈ = D⁻¹ (u − h)` is solved in the
//! graph by an unrolled `L diag(d) Lᵀ` factorisation, a forward and a backward substitution.

use super::build::Built;
use super::What;
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::expr::{Func, Kind};
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::{Expr, Poly, Symbol};
use crate::numeric::trace::{Graph, Val};

/// The lowered graph and each quantity's output values.
pub struct Lowered {
    pub(crate) graph: Graph,
    /// Joints.
    pub n: usize,
    /// Free parameters.
    pub np: usize,
    /// Each quantity's outputs (for `qdd`, the solved accelerations).
    pub(crate) outputs: Vec<(What, Vec<Val>)>,
    /// The potential energy, when built.
    pub(crate) potential: Option<Val>,
}

/// One term: `coefficient · Π atom^e`.
type Term = (f64, Vec<(AtomId, i32)>);

struct Lowerer<'a> {
    built: &'a Built,
    graph: Graph,
    n: usize,
    atoms: FxHashMap<AtomId, Val>,
    params: FxHashMap<Symbol, u32>,
    keys: FxHashMap<AtomId, Expr>,
}

impl Lowerer<'_> {
    fn slot(&mut self, slot: usize) -> Val {
        self.graph.input(slot as u32)
    }

    fn symbol(&mut self, s: &Symbol) -> Val {
        match s {
            Symbol::Coord { index, order } => {
                let i = *index as usize - 1;
                self.slot((*order as usize).min(2) * self.n + i)
            }
            Symbol::Param(_) => match self.params.get(s) {
                Some(&k) => self.slot(4 * self.n + k as usize),
                // A symbol that is not a parameter of the scene cannot occur; zero keeps it total.
                None => Val::k(0.0),
            },
        }
    }

    /// A leaf atom's value (names are valued before their users).
    fn atom(&mut self, id: AtomId) -> Val {
        if let Some(&v) = self.atoms.get(&id) {
            return v;
        }
        let v = match (atom::class(id), atom::symbol_of(id)) {
            (Class::Param | Class::Coord, Some(s)) => self.symbol(&s),
            (Class::Sin, Some(s)) => {
                let x = self.symbol(&s);
                self.graph.sin_cos(Func::Sin, x)
            }
            (Class::Cos, Some(s)) => {
                let x = self.symbol(&s);
                self.graph.sin_cos(Func::Cos, x)
            }
            _ => self.expr(&atom::to_expr(id)),
        };
        self.atoms.insert(id, v);
        v
    }

    /// Any other atom through its expression.
    fn expr(&mut self, e: &Expr) -> Val {
        match e.kind() {
            Kind::Num(r) => Val::k(r.to_f64()),
            Kind::Sym(s) => self.symbol(s),
            Kind::Pi => Val::k(std::f64::consts::PI),
            Kind::Sqrt(k) => Val::k(
                num_traits::ToPrimitive::to_f64(k)
                    .unwrap_or(f64::NAN)
                    .sqrt(),
            ),
            Kind::Add(c, ts) => {
                let mut acc = Val::k(c.to_f64());
                for (t, k) in ts {
                    let t = self.expr(t);
                    let t = self.graph.scale(k.to_f64(), t);
                    acc = self.graph.add(acc, t);
                }
                acc
            }
            Kind::Mul(c, fs) => {
                let (mut num, mut den) = (Val::k(c.to_f64()), Val::k(1.0));
                for (b, k) in fs {
                    let base = self.expr(b);
                    let p = self.power(base, k.unsigned_abs() as u32);
                    if *k > 0 {
                        num = self.graph.mul(num, p);
                    } else {
                        den = self.graph.mul(den, p);
                    }
                }
                self.graph.div(num, den)
            }
            Kind::Fun(f, a) => {
                let x = self.expr(a);
                self.graph.sin_cos(*f, x)
            }
        }
    }

    /// `x^k` by repeated squaring, every step a multiplication.
    fn power(&mut self, x: Val, k: u32) -> Val {
        match k {
            0 => Val::k(1.0),
            1 => x,
            _ => {
                let half = self.power(x, k / 2);
                let sq = self.graph.mul(half, half);
                if k % 2 == 1 {
                    self.graph.mul(sq, x)
                } else {
                    sq
                }
            }
        }
    }

    /// An atom's canonical expression (cached): the order of atoms in the generated code follows it,
    /// never the process-wide interning order of atom ids, so the code is the same on every run.
    fn key(&mut self, id: AtomId) -> Expr {
        self.keys
            .entry(id)
            .or_insert_with(|| atom::to_expr(id))
            .clone()
    }

    fn poly(&mut self, p: &Poly) -> Val {
        let mut terms: Vec<(Vec<(Expr, i32)>, Term)> = p
            .terms()
            .iter()
            .map(|(m, c)| {
                let mut fs: Vec<(Expr, AtomId, i32)> = m
                    .factors()
                    .iter()
                    .map(|&(id, e)| (self.key(id), id, e))
                    .collect();
                fs.sort_by(|a, b| a.0.cmp(&b.0));
                let key = fs.iter().map(|(k, _, e)| (k.clone(), *e)).collect();
                (
                    key,
                    (
                        c.to_f64(),
                        fs.into_iter().map(|(_, id, e)| (id, e)).collect(),
                    ),
                )
            })
            .collect();
        terms.sort_by(|a, b| a.0.cmp(&b.0));
        self.horner(terms.into_iter().map(|(_, t)| t).collect())
    }

    /// Greedy multivariate Horner form: factor out the atom (to the first power) that occurs in most
    /// terms, while one occurs in two or more; a product of what is left.
    fn horner(&mut self, terms: Vec<Term>) -> Val {
        match terms.len() {
            0 => return Val::k(0.0),
            1 => {
                let (c, fs) = terms.into_iter().next().expect("one term");
                return self.product(c, &fs);
            }
            _ => {}
        }
        let mut count: FxHashMap<AtomId, usize> = FxHashMap::default();
        for (_, fs) in &terms {
            for &(id, e) in fs {
                if e > 0 {
                    *count.entry(id).or_insert(0) += 1;
                }
            }
        }
        let mut candidates: Vec<(usize, Expr, AtomId)> = count
            .iter()
            .filter(|(_, &k)| k >= 2)
            .map(|(&id, &k)| (k, id, 0))
            .map(|(k, id, _)| (k, self.key(id), id))
            .collect();
        // The most frequent atom; among equals the first in the canonical order.
        candidates.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
        let best = candidates.first().map(|c| c.2);
        let Some(x) = best else {
            let mut acc = Val::k(0.0);
            let mut vals: Vec<Val> = Vec::with_capacity(terms.len());
            for (c, fs) in terms {
                vals.push(self.product(c, &fs));
            }
            for v in vals {
                acc = self.graph.add(acc, v);
            }
            return acc;
        };
        let (mut with, mut without) = (Vec::new(), Vec::new());
        for (c, fs) in terms {
            match fs.iter().position(|&(id, e)| id == x && e > 0) {
                Some(at) => {
                    let mut fs = fs;
                    fs[at].1 -= 1;
                    if fs[at].1 == 0 {
                        fs.remove(at);
                    }
                    with.push((c, fs));
                }
                None => without.push((c, fs)),
            }
        }
        let inner = self.horner(with);
        let xv = self.atom_or_name(x);
        let a = self.graph.mul(xv, inner);
        let b = self.horner(without);
        self.graph.add(a, b)
    }

    fn atom_or_name(&mut self, id: AtomId) -> Val {
        self.atom(id)
    }

    /// `c · Π atom^e` (negative powers divide).
    fn product(&mut self, c: f64, fs: &[(AtomId, i32)]) -> Val {
        let (mut num, mut den) = (Val::k(1.0), Val::k(1.0));
        for &(id, e) in fs {
            let x = self.atom_or_name(id);
            let p = self.power(x, e.unsigned_abs());
            if e > 0 {
                num = self.graph.mul(num, p);
            } else {
                den = self.graph.mul(den, p);
            }
        }
        let num = self.graph.scale(c, num);
        self.graph.div(num, den)
    }

    /// `q̈ = D⁻¹ (u − h)` by `D = L diag(d) Lᵀ` (unrolled LDLᵀ, `L` unit lower triangular, no
    /// square roots; one division per joint, for `1/d_j`): `L y = u − h`, `Lᵀ q̈ = diag(d)⁻¹ y`.
    fn solve(&mut self, m: &[Val], h: &[Val]) -> Vec<Val> {
        let n = self.n;
        let mut l = vec![Val::k(0.0); n * n];
        let mut d = vec![Val::k(0.0); n];
        let mut inv = vec![Val::k(0.0); n];
        for j in 0..n {
            // d_j = m_jj − Σ_k l_jk² d_k; with w_jk = l_jk d_k kept for the column below.
            let mut s = m[j * n + j];
            for k in 0..j {
                let w = self.graph.mul(l[j * n + k], d[k]);
                let p = self.graph.mul(w, l[j * n + k]);
                s = self.graph.sub(s, p);
            }
            d[j] = s;
            inv[j] = self.graph.div(Val::k(1.0), s);
            for i in j + 1..n {
                let mut s = m[i * n + j];
                for k in 0..j {
                    let w = self.graph.mul(l[j * n + k], d[k]);
                    let p = self.graph.mul(l[i * n + k], w);
                    s = self.graph.sub(s, p);
                }
                l[i * n + j] = self.graph.mul(s, inv[j]);
            }
        }
        let mut y = vec![Val::k(0.0); n];
        for i in 0..n {
            let u = self.slot(3 * n + i);
            let mut s = self.graph.sub(u, h[i]);
            for k in 0..i {
                let p = self.graph.mul(l[i * n + k], y[k]);
                s = self.graph.sub(s, p);
            }
            y[i] = s;
        }
        let mut x = vec![Val::k(0.0); n];
        for i in (0..n).rev() {
            let mut s = self.graph.mul(y[i], inv[i]);
            for k in i + 1..n {
                let p = self.graph.mul(l[k * n + i], x[k]);
                s = self.graph.sub(s, p);
            }
            x[i] = s;
        }
        x
    }
}

/// Lowers every quantity of `built` into one graph.
pub fn lower(built: &Built) -> Lowered {
    let n = built.robot.dof();
    let mut lw = Lowerer {
        built,
        graph: Graph::default(),
        n,
        atoms: FxHashMap::default(),
        keys: FxHashMap::default(),
        params: built
            .parameters
            .iter()
            .enumerate()
            .map(|(k, s)| (s.clone(), k as u32))
            .collect(),
    };
    let all: Vec<&Poly> = built
        .outputs
        .iter()
        .flat_map(|(_, v)| v.iter())
        .chain(built.potential.iter())
        .collect();
    for k in built.arena.live(all.iter().copied()) {
        let def = &lw.built.arena.defs()[k];
        let v = lw.poly(&def.value);
        lw.atoms.insert(def.atom, v);
    }
    let mut outputs = Vec::new();
    for (what, polys) in &built.outputs {
        let vals: Vec<Val> = polys.iter().map(|p| lw.poly(p)).collect();
        let vals = if *what == What::Qdd {
            let (d, h) = vals.split_at(n * n);
            lw.solve(d, h)
        } else {
            vals
        };
        outputs.push((*what, vals));
    }
    let potential = built.potential.as_ref().map(|p| lw.poly(p));
    Lowered {
        graph: lw.graph,
        n,
        np: built.parameters.len(),
        outputs,
        potential,
    }
}
