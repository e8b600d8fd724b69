//! The nested (multivariate Horner) form of derived polynomials, evaluated in `f64`.
//!
//! The expanded form `Σ_k c_k m_k` (what [`crate::numeric::compile`] evaluates, sharing products) is
//! rewritten greedily as `p = x · p₁ + p₀`, where `x` is the variable (an atom: a parameter, `q̇_i`,
//! `q̈_i`, a prismatic `q_i`, `sin q_i`, `cos q_i`) that occurs in the most terms of `p` (ties: the
//! smallest atom id), `p₁` holds the terms containing `x` with one power of `x` removed and `p₀` the
//! others; `p₁` and `p₀` are nested the same way. Each node costs one multiplication and one addition.
//!
//! Along any term's path there are at most `D` multiplications (its degree) and at most `D + T`
//! additions (each level either lowers the term's degree or, in `p₀`, removes at least one term),
//! plus the rounding of its coefficient: [`Nested::max_roundings`] reports the exact maximum, the `N`
//! of the forward error bound `|p̂ − p| ≤ γ_N Σ_k |c_k m_k|` (Higham, *Accuracy and Stability of
//! Numerical Algorithms*, §3.1).

use crate::algebra::atom::{self, Atom, AtomId, Class};
use crate::algebra::{eval_f64, Expr, Poly, Symbol};
use crate::numeric::NumericError;
use std::collections::{BTreeMap, HashMap};

type Reg = u32;

#[derive(Clone, Copy, Debug)]
enum Op {
    /// `dst = c`.
    Const { c: f64, dst: Reg },
    /// `dst = x[var] · a + b`.
    MulAdd { var: u32, a: Reg, b: Reg, dst: Reg },
    /// `dst = x[var] · a`.
    Mul { var: u32, a: Reg, dst: Reg },
}

/// How one variable gets its value per call.
#[derive(Clone, Debug)]
enum Source {
    /// A parameter's bound value.
    Param(f64),
    /// `q_i`, `q̇_i`, `q̈_i` (order, index from 0).
    Coord(u8, usize),
    /// `sin q_i` / `cos q_i` (true for sin).
    Trig(bool, usize),
    /// A constant (π, a surd, sin of a constant angle, sin of a parameter).
    Const(f64),
    /// An opaque expression, evaluated with `eval_f64`.
    Other(Expr),
}

/// Compiled nested forms of a list of polynomials, with parameters bound.
#[derive(Clone, Debug)]
pub struct Nested {
    dof: usize,
    vars: Vec<Source>,
    /// Negative powers: `x[var] = 1 / x[base]`, computed per call.
    inverses: Vec<(u32, u32)>,
    x: Vec<f64>,
    code: Vec<Op>,
    regs: Vec<f64>,
    outputs: Vec<Reg>,
    out: Vec<f64>,
    depth: Vec<usize>,
    params: HashMap<Symbol, f64>,
}

struct Builder {
    code: Vec<Op>,
    depth: Vec<usize>,
    n_regs: u32,
}

/// A term: sorted `(variable, exponent > 0)` pairs and the coefficient.
type Term = (Vec<(u32, i32)>, f64);

impl Builder {
    fn push(&mut self, op: impl FnOnce(Reg) -> Op, depth: usize) -> Reg {
        let dst = self.n_regs;
        self.n_regs += 1;
        self.code.push(op(dst));
        self.depth.push(depth);
        dst
    }

    fn build(&mut self, terms: Vec<Term>) -> Reg {
        let mut counts: BTreeMap<u32, usize> = BTreeMap::new();
        for (m, _) in &terms {
            for &(v, _) in m {
                *counts.entry(v).or_default() += 1;
            }
        }
        // The variable in most terms; ties to the smallest.
        let Some((&var, _)) = counts.iter().max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(a.0))) else {
            let c: f64 = terms.iter().map(|t| t.1).sum();
            return self.push(|dst| Op::Const { c, dst }, 1);
        };
        let (mut with, without): (Vec<Term>, Vec<Term>) = terms
            .into_iter()
            .partition(|(m, _)| m.iter().any(|&(v, _)| v == var));
        for (m, _) in &mut with {
            for f in m.iter_mut() {
                if f.0 == var {
                    f.1 -= 1;
                }
            }
            m.retain(|f| f.1 > 0);
        }
        let a = self.build(with);
        let da = self.depth[a as usize];
        if without.is_empty() {
            self.push(|dst| Op::Mul { var, a, dst }, da + 1)
        } else {
            let b = self.build(without);
            let db = self.depth[b as usize];
            self.push(|dst| Op::MulAdd { var, a, b, dst }, (da + 2).max(db + 1))
        }
    }
}

impl Nested {
    /// Nests `polys` (in parameters and the coordinates of `dof` joints) and binds the parameters.
    pub fn new(
        polys: &[Poly],
        dof: usize,
        params: &HashMap<Symbol, f64>,
    ) -> Result<Nested, NumericError> {
        let mut index: HashMap<AtomId, u32> = HashMap::new();
        let mut vars: Vec<Source> = Vec::new();
        let mut inverses = Vec::new();
        let mut missing = std::collections::BTreeSet::new();
        let mut var_of = |id: AtomId, vars: &mut Vec<Source>| -> Result<u32, NumericError> {
            if let Some(&v) = index.get(&id) {
                return Ok(v);
            }
            let coord = |s: &Symbol| match s {
                Symbol::Coord { index, order } if *index as usize <= dof && *index > 0 => {
                    Ok((*order, *index as usize - 1))
                }
                _ => Err(NumericError::UnknownCoordinate {
                    name: s.ascii_name(),
                    dof,
                }),
            };
            let src = match (atom::class(id), atom::lookup(id)) {
                (Class::Sin | Class::Cos, Atom::Sym(x)) if x.is_coord() => {
                    let (order, i) = coord(&x)?;
                    if order != 0 {
                        return Err(NumericError::UnknownCoordinate {
                            name: x.ascii_name(),
                            dof,
                        });
                    }
                    Source::Trig(atom::class(id) == Class::Sin, i)
                }
                (_, Atom::Sym(s)) if s.is_coord() => {
                    let (order, i) = coord(&s)?;
                    Source::Coord(order, i)
                }
                (Class::Param, Atom::Sym(s)) => match params.get(&s) {
                    Some(&x) => Source::Param(x),
                    None => {
                        missing.insert(s);
                        Source::Param(f64::NAN)
                    }
                },
                (_, Atom::Other(e)) if !e.symbols().is_empty() => Source::Other(e),
                _ => {
                    let e = atom::to_expr(id);
                    match eval_f64(&e, params) {
                        Ok(x) => Source::Const(x),
                        Err(_) => Source::Other(e),
                    }
                }
            };
            vars.push(src);
            let v = vars.len() as u32 - 1;
            index.insert(id, v);
            Ok(v)
        };
        let mut neg: HashMap<u32, u32> = HashMap::new();
        let mut b = Builder {
            code: Vec::new(),
            depth: Vec::new(),
            n_regs: 0,
        };
        let mut outputs = Vec::new();
        for p in polys {
            let mut terms: Vec<Term> = Vec::with_capacity(p.len());
            for (mono, coef) in p.terms() {
                let mut m = Vec::new();
                for &(id, k) in mono.factors() {
                    let mut v = var_of(id, &mut vars)?;
                    if k < 0 {
                        v = *neg.entry(v).or_insert_with(|| {
                            vars.push(Source::Const(f64::NAN));
                            let inv = vars.len() as u32 - 1;
                            inverses.push((inv, v));
                            inv
                        });
                    }
                    m.push((v, k.abs()));
                }
                m.sort_unstable();
                terms.push((m, coef.to_f64()));
            }
            outputs.push(b.build(terms));
        }
        if !missing.is_empty() {
            return Err(NumericError::Missing(missing.into_iter().collect()));
        }
        let n_vars = vars.len();
        let mut x = vec![0.0; n_vars];
        for (v, s) in vars.iter().enumerate() {
            if let Source::Param(c) | Source::Const(c) = s {
                x[v] = *c;
            }
        }
        // An inverse adds one rounding to every path through it: count it once for all.
        let extra = usize::from(!inverses.is_empty());
        Ok(Nested {
            dof,
            vars,
            inverses,
            x,
            regs: vec![0.0; b.n_regs as usize],
            out: vec![0.0; outputs.len()],
            depth: outputs
                .iter()
                .map(|&r| b.depth[r as usize] + extra)
                .collect(),
            code: b.code,
            outputs,
            params: params.clone(),
        })
    }

    /// The number of multiply(-add) nodes.
    pub fn len(&self) -> usize {
        self.code.len()
    }

    /// Whether there is no code at all.
    pub fn is_empty(&self) -> bool {
        self.code.is_empty()
    }

    /// For each output, the largest number of roundings on the path of any term (its coefficient's
    /// rounding, each multiplication and addition it passes through).
    pub fn max_roundings(&self) -> &[usize] {
        &self.depth
    }

    /// The outputs at `q`, `q̇`, `q̈` (each of length `dof`).
    pub fn eval(&mut self, q: &[f64], qd: &[f64], qdd: &[f64]) -> Result<&[f64], NumericError> {
        for (what, xs) in [("q", q), ("qd", qd), ("qdd", qdd)] {
            if xs.len() != self.dof {
                return Err(NumericError::WrongLength {
                    what,
                    expected: self.dof,
                    got: xs.len(),
                });
            }
        }
        for (v, src) in self.vars.iter().enumerate() {
            self.x[v] = match src {
                Source::Param(c) | Source::Const(c) => *c,
                Source::Coord(0, i) => q[*i],
                Source::Coord(1, i) => qd[*i],
                Source::Coord(_, i) => qdd[*i],
                Source::Trig(true, i) => q[*i].sin(),
                Source::Trig(false, i) => q[*i].cos(),
                Source::Other(e) => {
                    let mut vals = self.params.clone();
                    for i in 0..self.dof {
                        vals.insert(Symbol::q(i as u32 + 1), q[i]);
                        vals.insert(Symbol::qd(i as u32 + 1), qd[i]);
                        vals.insert(Symbol::qdd(i as u32 + 1), qdd[i]);
                    }
                    eval_f64(e, &vals)?
                }
            };
        }
        for &(inv, base) in &self.inverses {
            self.x[inv as usize] = 1.0 / self.x[base as usize];
        }
        let (x, r) = (&self.x, &mut self.regs);
        for op in &self.code {
            match *op {
                Op::Const { c, dst } => r[dst as usize] = c,
                Op::MulAdd { var, a, b, dst } => {
                    r[dst as usize] = x[var as usize] * r[a as usize] + r[b as usize]
                }
                Op::Mul { var, a, dst } => r[dst as usize] = x[var as usize] * r[a as usize],
            }
        }
        for (o, &reg) in self.out.iter_mut().zip(&self.outputs) {
            *o = self.regs[reg as usize];
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
    fn nested_matches_direct_evaluation() {
        let e = parse_expr("m*l^2*cos(q2)*qd1^2 + m*l*sin(q2)*qdd1 + 3*qd1*qd2/m - 7").unwrap();
        let p = to_poly(&e);
        let params = HashMap::from([(Symbol::new("m"), 2.0), (Symbol::new("l"), 0.5)]);
        let mut n = Nested::new(&[p], 2, &params).unwrap();
        let (q, qd, qdd) = ([0.3, -1.1], [0.7, 2.0], [1.5, -0.25]);
        let got = n.eval(&q, &qd, &qdd).unwrap()[0];
        let mut vals = params.clone();
        for i in 0..2 {
            vals.insert(Symbol::q(i as u32 + 1), q[i]);
            vals.insert(Symbol::qd(i as u32 + 1), qd[i]);
            vals.insert(Symbol::qdd(i as u32 + 1), qdd[i]);
        }
        let want = eval_f64(&e, &vals).unwrap();
        assert!((got - want).abs() < 1e-13 * want.abs(), "{got} vs {want}");
        assert!(n.max_roundings()[0] >= 3);
        assert!(Nested::new(&[to_poly(&e)], 2, &HashMap::new()).is_err());
    }
}
