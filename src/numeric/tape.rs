//! A compiled evaluator: a set of [`Poly`]s flattened into one instruction tape over `f64` registers.
//!
//! Compilation shares every subexpression it can name:
//! - each input symbol (a parameter, `q_i`, `q̇_i`, `q̈_i`) is one register;
//! - each atom (`sin q2`, `cos q2`, an opaque expression) is computed once per call, and `sin x` and
//!   `cos x` come from one `sin_cos`;
//! - each power `x^k` and each product is memoised, and a monomial is built left to right from its
//!   factors, so monomials that share a prefix share its product;
//! - every instruction that depends only on parameters and constants goes to a *setup* tape, run once
//!   when the parameters are bound ([`Tape::bind`]); only the rest runs per call.
//!
//! [`Evaluator::eval`] runs the per-call tape over a register file allocated at bind time: no
//! allocation per call.

use super::NumericError;
use crate::algebra::atom::{self, AtomId};
use crate::algebra::{Expr, Func, Kind, Poly, Symbol};
use std::collections::{BTreeMap, BTreeSet, HashMap};

type Reg = u32;

/// A monomial's factors: atoms with exponents.
type Factors = Vec<(AtomId, i32)>;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Instr {
    /// `sin = sin(arg)`, `cos = cos(arg)`.
    SinCos { arg: Reg, sin: Reg, cos: Reg },
    /// `dst = a · b`.
    Mul { a: Reg, b: Reg, dst: Reg },
    /// `dst = a^k`.
    Powi { a: Reg, k: i32, dst: Reg },
    /// `dst = sgn a`.
    Sgn { a: Reg, dst: Reg },
    /// `dst = c + Σ coef · reg` over `terms[start..end]`.
    Sum {
        c: f64,
        start: u32,
        end: u32,
        dst: Reg,
    },
}

/// A compiled set of polynomials in parameters and the coordinates `q`, `q̇`, `q̈` of `dof` joints.
#[derive(Clone, Debug)]
pub struct Tape {
    dof: usize,
    n_regs: usize,
    consts: Vec<(Reg, f64)>,
    params: Vec<(Symbol, Reg)>,
    /// `(register, order, index from 0)` of each coordinate input.
    coords: Vec<(Reg, u8, usize)>,
    setup: Vec<Instr>,
    body: Vec<Instr>,
    terms: Vec<(f64, Reg)>,
    outputs: Vec<Reg>,
}

#[derive(Default)]
struct Builder {
    n_regs: u32,
    per_call: Vec<bool>,
    consts: Vec<(Reg, f64)>,
    const_memo: HashMap<u64, Reg>,
    inputs: BTreeMap<Symbol, Reg>,
    sincos: HashMap<Reg, (Reg, Reg)>,
    atoms: HashMap<AtomId, Reg>,
    exprs: HashMap<Expr, Reg>,
    pows: HashMap<(Reg, i32), Reg>,
    muls: HashMap<(Reg, Reg), Reg>,
    setup: Vec<Instr>,
    body: Vec<Instr>,
    terms: Vec<(f64, Reg)>,
}

impl Builder {
    fn fresh(&mut self, per_call: bool) -> Reg {
        let r = self.n_regs;
        self.n_regs += 1;
        self.per_call.push(per_call);
        r
    }

    fn emit(&mut self, per_call: bool, instr: Instr) {
        if per_call {
            self.body.push(instr);
        } else {
            self.setup.push(instr);
        }
    }

    fn constant(&mut self, x: f64) -> Reg {
        if let Some(&r) = self.const_memo.get(&x.to_bits()) {
            return r;
        }
        let r = self.fresh(false);
        self.consts.push((r, x));
        self.const_memo.insert(x.to_bits(), r);
        r
    }

    fn input(&mut self, s: &Symbol) -> Reg {
        if let Some(&r) = self.inputs.get(s) {
            return r;
        }
        let r = self.fresh(s.is_coord());
        self.inputs.insert(s.clone(), r);
        r
    }

    fn sin_cos(&mut self, arg: Reg) -> (Reg, Reg) {
        if let Some(&p) = self.sincos.get(&arg) {
            return p;
        }
        let pc = self.per_call[arg as usize];
        let (sin, cos) = (self.fresh(pc), self.fresh(pc));
        self.emit(pc, Instr::SinCos { arg, sin, cos });
        self.sincos.insert(arg, (sin, cos));
        (sin, cos)
    }

    fn mul(&mut self, a: Reg, b: Reg) -> Reg {
        let key = (a.min(b), a.max(b));
        if let Some(&r) = self.muls.get(&key) {
            return r;
        }
        let pc = self.per_call[a as usize] || self.per_call[b as usize];
        let dst = self.fresh(pc);
        self.emit(pc, Instr::Mul { a, b, dst });
        self.muls.insert(key, dst);
        dst
    }

    fn pow(&mut self, a: Reg, k: i32) -> Reg {
        if k == 1 {
            return a;
        }
        if let Some(&r) = self.pows.get(&(a, k)) {
            return r;
        }
        let pc = self.per_call[a as usize];
        let dst = if k == 2 {
            self.mul(a, a)
        } else {
            let dst = self.fresh(pc);
            self.emit(pc, Instr::Powi { a, k, dst });
            dst
        };
        self.pows.insert((a, k), dst);
        dst
    }

    fn sum(&mut self, c: f64, terms: &[(f64, Reg)]) -> Reg {
        let pc = terms.iter().any(|&(_, r)| self.per_call[r as usize]);
        let start = self.terms.len() as u32;
        self.terms.extend_from_slice(terms);
        let end = self.terms.len() as u32;
        let dst = self.fresh(pc);
        self.emit(pc, Instr::Sum { c, start, end, dst });
        dst
    }

    fn expr(&mut self, e: &Expr) -> Reg {
        if let Some(&r) = self.exprs.get(e) {
            return r;
        }
        let r = match e.kind() {
            Kind::Num(r) => self.constant(r.to_f64()),
            Kind::Sym(s) => self.input(s),
            Kind::Pi => self.constant(std::f64::consts::PI),
            Kind::Sqrt(k) => self.constant(
                num_traits::ToPrimitive::to_f64(k)
                    .unwrap_or(f64::NAN)
                    .sqrt(),
            ),
            Kind::Add(c, ts) => {
                let terms: Vec<(f64, Reg)> =
                    ts.iter().map(|(t, k)| (k.to_f64(), self.expr(t))).collect();
                self.sum(c.to_f64(), &terms)
            }
            Kind::Mul(c, fs) => {
                let mut acc: Option<Reg> = None;
                for (b, k) in fs {
                    let base = self.expr(b);
                    let p = self.pow(base, *k as i32);
                    acc = Some(match acc {
                        None => p,
                        Some(a) => self.mul(a, p),
                    });
                }
                let acc = acc.unwrap_or_else(|| self.constant(1.0));
                if c.is_one() {
                    acc
                } else {
                    self.sum(0.0, &[(c.to_f64(), acc)])
                }
            }
            Kind::Fun(Func::Sgn, a) => {
                let arg = self.expr(a);
                let pc = self.per_call[arg as usize];
                let dst = self.fresh(pc);
                self.emit(pc, Instr::Sgn { a: arg, dst });
                dst
            }
            Kind::Fun(f, a) => {
                let arg = self.expr(a);
                let (s, c) = self.sin_cos(arg);
                match f {
                    Func::Sin => s,
                    Func::Cos | Func::Sgn => c,
                }
            }
        };
        self.exprs.insert(e.clone(), r);
        r
    }

    fn atom(&mut self, id: AtomId) -> Reg {
        if let Some(&r) = self.atoms.get(&id) {
            return r;
        }
        let r = self.expr(&atom::to_expr(id));
        self.atoms.insert(id, r);
        r
    }

    /// The product of `factors` (atoms with exponents), left to right, memoised; `None` for none.
    fn product(&mut self, factors: &[(Reg, i32)]) -> Option<Reg> {
        let mut acc: Option<Reg> = None;
        for &(r, k) in factors {
            let p = self.pow(r, k);
            acc = Some(match acc {
                None => p,
                Some(a) => self.mul(a, p),
            });
        }
        acc
    }

    /// `p` as `Σ_v v · (Σ_t c_t t)`: terms grouped by their rate factor `v` (a monomial in `q̇`, `q̈`),
    /// so each rate monomial is multiplied in once; within a group, factors that depend only on
    /// parameters come first, so that their product is set up once, then those in `q`.
    fn poly(&mut self, p: &Poly) -> Reg {
        let mut c = 0.0;
        let mut groups: BTreeMap<Factors, Vec<(f64, Reg)>> = BTreeMap::new();
        for (mono, coef) in p.terms() {
            let (rate, rest): (Factors, Factors) =
                mono.factors().iter().partition(|&&(id, _)| is_rate(id));
            let mut factors: Vec<(Reg, i32)> =
                rest.iter().map(|&(id, k)| (self.atom(id), k)).collect();
            factors.sort_by_key(|&(r, _)| self.per_call[r as usize]);
            let coef = coef.to_f64();
            match self.product(&factors) {
                Some(r) => groups.entry(rate).or_default().push((coef, r)),
                None if rate.is_empty() => c += coef,
                None => {
                    let one = self.constant(1.0);
                    groups.entry(rate).or_default().push((coef, one));
                }
            }
        }
        let mut terms = Vec::new();
        for (rate, inner) in groups {
            let rate: Vec<(Reg, i32)> = rate.iter().map(|&(id, k)| (self.atom(id), k)).collect();
            match self.product(&rate) {
                None => terms.extend(inner),
                Some(v) => match inner.as_slice() {
                    [(k, r)] => terms.push((*k, self.mul(*r, v))),
                    _ => {
                        let s = self.sum(0.0, &inner);
                        terms.push((1.0, self.mul(s, v)));
                    }
                },
            }
        }
        self.sum(c, &terms)
    }
}

/// Whether an atom is a rate `q̇_i` or `q̈_i`.
fn is_rate(id: AtomId) -> bool {
    atom::class(id) == atom::Class::Coord
        && matches!(atom::symbol_of(id), Some(Symbol::Coord { order, .. }) if order > 0)
}

/// Compiles `polys` (in parameters and the coordinates of `dof` joints) into one tape whose outputs are
/// their values, in order. Fails when a coordinate beyond `dof` appears.
pub fn compile(polys: &[Poly], dof: usize) -> Result<Tape, NumericError> {
    let mut b = Builder::default();
    let outputs: Vec<Reg> = polys.iter().map(|p| b.poly(p)).collect();
    let mut params = Vec::new();
    let mut coords = Vec::new();
    for (s, &r) in &b.inputs {
        match s {
            Symbol::Param(_) => params.push((s.clone(), r)),
            Symbol::Coord { index, order } => {
                let i = *index as usize;
                if i == 0 || i > dof || *order > 2 {
                    return Err(NumericError::UnknownCoordinate {
                        name: s.ascii_name(),
                        dof,
                    });
                }
                coords.push((r, *order, i - 1));
            }
        }
    }
    Ok(Tape {
        dof,
        n_regs: b.n_regs as usize,
        consts: b.consts,
        params,
        coords,
        setup: b.setup,
        body: b.body,
        terms: b.terms,
        outputs,
    })
}

fn run(instrs: &[Instr], terms: &[(f64, Reg)], regs: &mut [f64]) {
    for instr in instrs {
        match *instr {
            Instr::SinCos { arg, sin, cos } => {
                let (s, c) = regs[arg as usize].sin_cos();
                regs[sin as usize] = s;
                regs[cos as usize] = c;
            }
            Instr::Mul { a, b, dst } => regs[dst as usize] = regs[a as usize] * regs[b as usize],
            Instr::Powi { a, k, dst } => regs[dst as usize] = regs[a as usize].powi(k),
            Instr::Sgn { a, dst } => {
                regs[dst as usize] = crate::algebra::eval::sign(regs[a as usize])
            }
            Instr::Sum { c, start, end, dst } => {
                let mut acc = c;
                for &(k, r) in &terms[start as usize..end as usize] {
                    acc += k * regs[r as usize];
                }
                regs[dst as usize] = acc;
            }
        }
    }
}

impl Tape {
    /// The number of joints.
    pub fn dof(&self) -> usize {
        self.dof
    }

    /// The parameters (every symbol that is not a coordinate), sorted.
    pub fn parameters(&self) -> Vec<Symbol> {
        self.params.iter().map(|(s, _)| s.clone()).collect()
    }

    /// Whether the outputs depend on `q̇` (`order` 1) or `q̈` (`order` 2), or `q` (`order` 0).
    pub fn uses(&self, order: u8) -> bool {
        self.coords.iter().any(|&(_, o, _)| o == order)
    }

    /// The parameters that `values` leaves without a value, sorted.
    pub fn missing(&self, values: &HashMap<Symbol, f64>) -> BTreeSet<Symbol> {
        self.params
            .iter()
            .filter(|(s, _)| !values.contains_key(s))
            .map(|(s, _)| s.clone())
            .collect()
    }

    /// The number of instructions run once at binding and per call.
    pub fn instruction_counts(&self) -> (usize, usize) {
        (self.setup.len(), self.body.len())
    }

    /// Binds values to every parameter and runs the setup tape; fails listing every parameter
    /// without a value. Extra values are ignored.
    pub fn bind(&self, values: &HashMap<Symbol, f64>) -> Result<Evaluator, NumericError> {
        let missing = self.missing(values);
        if !missing.is_empty() {
            return Err(NumericError::Missing(missing.into_iter().collect()));
        }
        let mut regs = vec![0.0; self.n_regs];
        for &(r, x) in &self.consts {
            regs[r as usize] = x;
        }
        for (s, r) in &self.params {
            regs[*r as usize] = values[s];
        }
        run(&self.setup, &self.terms, &mut regs);
        Ok(Evaluator {
            out: vec![0.0; self.outputs.len()],
            tape: self.clone(),
            regs,
        })
    }
}

/// A tape with its parameters bound: evaluates the outputs for given `q`, `q̇`, `q̈`.
#[derive(Clone, Debug)]
pub struct Evaluator {
    tape: Tape,
    regs: Vec<f64>,
    out: Vec<f64>,
}

impl Evaluator {
    /// The tape.
    pub fn tape(&self) -> &Tape {
        &self.tape
    }

    /// The outputs at `q`, `q̇`, `q̈` (each of length `dof`; a slice the outputs do not depend on may be
    /// empty). Allocates nothing.
    pub fn eval(&mut self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<&[f64], NumericError> {
        let n = self.tape.dof;
        for (order, (what, xs)) in [("q", q), ("qd", qd), ("qdd", qdd)].into_iter().enumerate() {
            if xs.len() != n && (order == 0 || !xs.is_empty() || self.tape.uses(order as u8)) {
                return Err(NumericError::WrongLength {
                    what,
                    expected: n,
                    got: xs.len(),
                });
            }
        }
        for &(r, order, i) in &self.tape.coords {
            self.regs[r as usize] = match order {
                0 => q[i],
                1 => qd[i],
                _ => qdd[i],
            };
        }
        run(&self.tape.body, &self.tape.terms, &mut self.regs);
        for (o, &r) in self.out.iter_mut().zip(&self.tape.outputs) {
            *o = self.regs[r as usize];
        }
        Ok(&self.out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;
    use crate::parse::parse_expr;

    #[test]
    fn shares_sin_cos_and_hoists_parameters() {
        let p = to_poly(&parse_expr("m*l^2*cos(q2)*qd1 + m*l^2*sin(q2)*qdd1 + 3").unwrap());
        let tape = compile(&[p], 2).unwrap();
        // setup: l^2, m*l^2; per call: sin_cos(q2), two products, two with m l^2, the sum.
        assert_eq!(tape.parameters(), vec![Symbol::new("l"), Symbol::new("m")]);
        let (_, body) = tape.instruction_counts();
        assert!(body <= 6, "{body}");
        let err = tape.bind(&HashMap::new()).unwrap_err();
        assert_eq!(err.to_string(), "no value given for l, m");
        let vals = HashMap::from([(Symbol::new("m"), 2.0), (Symbol::new("l"), 3.0)]);
        let mut ev = tape.bind(&vals).unwrap();
        let out = ev.eval(&[0.0, 0.5], &[1.0, 0.0], &[2.0, 0.0]).unwrap()[0];
        let want = 18.0 * 0.5f64.cos() + 18.0 * 0.5f64.sin() * 2.0 + 3.0;
        assert!((out - want).abs() < 1e-12);
        assert!(ev.eval(&[0.0], &[1.0, 0.0], &[2.0, 0.0]).is_err());
    }
}
