//! A tracing scalar: running a recursion over [`Traced`] values records every `f64` operation it would
//! do as a node of a shared DAG (a `Graph`), so that one run of Newton–Euler yields a straight-line
//! program specialised to one robot ([`super::program`]).
//!
//! Recording simplifies as it goes:
//! - constant folding: an operation on constants is a constant (numeric parameters are constants, so
//!   everything that depends only on them is computed once, at compile time);
//! - identities: `x + 0 = x`, `x · 0 = 0`, `x · 1 = x`, `x · (−1) = −x`, `x − x = 0`, `−(−x) = x`,
//!   and negations move into subtractions (`x + (−y) = x − y`) or constant factors (`c · (−x) = (−c) x`),
//!   so the exact zeros and ones of the DH twists vanish;
//! - hash-consing: an operation on the same operands is recorded once (commutative operands sorted).
//!
//! Values that are constants carry no graph (`Scalar::zero()` and `Scalar::from_rational` have no
//! context); the first operation with a traced operand takes that operand's graph.

use crate::algebra::atom::{self, AtomId};
use crate::algebra::{Expr, Func, Kind, Poly, Rational, Symbol};
use crate::dynamics::scalar::Scalar;
use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

/// An operand: a constant (its bits, so that operands hash) or a node of the graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Val {
    /// A constant, as `f64::to_bits`.
    K(u64),
    /// The node with this index.
    N(u32),
}

impl Val {
    pub(crate) fn k(x: f64) -> Val {
        // One zero: `-0.0` and `0.0` behave alike in every later operation we fold.
        Val::K(if x == 0.0 { 0 } else { x.to_bits() })
    }

    pub(crate) fn constant(self) -> Option<f64> {
        match self {
            Val::K(b) => Some(f64::from_bits(b)),
            Val::N(_) => None,
        }
    }
}

/// One recorded operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Op {
    /// Input slot `order · dof + index` (`q`, `q̇`, `q̈` of joint `index + 1`).
    Input(u32),
    /// `a + b`.
    Add(Val, Val),
    /// `a − b`.
    Sub(Val, Val),
    /// `a · b`.
    Mul(Val, Val),
    /// `−a`.
    Neg(Val),
    /// `a^k`, `k ∉ {0, 1}`.
    Powi(Val, i32),
    /// `sin a`.
    Sin(Val),
    /// `cos a`.
    Cos(Val),
    /// `a / b` (generated code's solves only; `compile_tau` never records one).
    Div(Val, Val),
    /// `sgn a` (Coulomb friction).
    Sgn(Val),
}

/// The recorded DAG; nodes are in creation order, which is a topological order.
#[derive(Debug, Default)]
pub(crate) struct Graph {
    pub(crate) nodes: Vec<Op>,
    memo: HashMap<Op, u32>,
}

impl Graph {
    fn node(&mut self, op: Op) -> Val {
        if let Some(&n) = self.memo.get(&op) {
            return Val::N(n);
        }
        let n = self.nodes.len() as u32;
        self.nodes.push(op);
        self.memo.insert(op, n);
        Val::N(n)
    }

    fn op_of(&self, v: Val) -> Option<Op> {
        match v {
            Val::N(n) => Some(self.nodes[n as usize]),
            Val::K(_) => None,
        }
    }

    pub(crate) fn input(&mut self, slot: u32) -> Val {
        self.node(Op::Input(slot))
    }

    pub(crate) fn add(&mut self, a: Val, b: Val) -> Val {
        match (a.constant(), b.constant()) {
            (Some(x), Some(y)) => return Val::k(x + y),
            (Some(0.0), None) => return b,
            (None, Some(0.0)) => return a,
            _ => {}
        }
        if let Some(Op::Neg(y)) = self.op_of(b) {
            return self.sub(a, y);
        }
        if let Some(Op::Neg(x)) = self.op_of(a) {
            return self.sub(b, x);
        }
        let (a, b) = sorted(a, b);
        self.node(Op::Add(a, b))
    }

    pub(crate) fn sub(&mut self, a: Val, b: Val) -> Val {
        if a == b {
            return Val::k(0.0);
        }
        // (x + y) − x = y, the sum of a named value and its own part taken back.
        if let Some(Op::Add(x, y)) = self.op_of(a) {
            if x == b {
                return y;
            }
            if y == b {
                return x;
            }
        }
        match (a.constant(), b.constant()) {
            (Some(x), Some(y)) => return Val::k(x - y),
            (Some(0.0), None) => return self.neg(b),
            (None, Some(0.0)) => return a,
            _ => {}
        }
        if let Some(Op::Neg(y)) = self.op_of(b) {
            return self.add(a, y);
        }
        if let Some(Op::Neg(x)) = self.op_of(a) {
            // −x − b = −(x + b)
            let s = self.add(x, b);
            return self.neg(s);
        }
        self.node(Op::Sub(a, b))
    }

    pub(crate) fn mul(&mut self, a: Val, b: Val) -> Val {
        match (a.constant(), b.constant()) {
            (Some(x), Some(y)) => return Val::k(x * y),
            (Some(c), None) => return self.scale(c, b),
            (None, Some(c)) => return self.scale(c, a),
            _ => {}
        }
        if let Some(Op::Neg(x)) = self.op_of(a) {
            let p = self.mul(x, b);
            return self.neg(p);
        }
        if let Some(Op::Neg(y)) = self.op_of(b) {
            let p = self.mul(a, y);
            return self.neg(p);
        }
        let (a, b) = sorted(a, b);
        self.node(Op::Mul(a, b))
    }

    /// `c · x` for a constant `c`.
    pub(crate) fn scale(&mut self, c: f64, x: Val) -> Val {
        if c == 0.0 {
            return Val::k(0.0);
        }
        if c == 1.0 {
            return x;
        }
        if c == -1.0 {
            return self.neg(x);
        }
        match self.op_of(x) {
            Some(Op::Neg(y)) => self.scale(-c, y),
            Some(Op::Mul(Val::K(k), y)) => self.scale(c * f64::from_bits(k), y),
            _ => self.node(Op::Mul(Val::k(c), x)),
        }
    }

    pub(crate) fn neg(&mut self, a: Val) -> Val {
        if let Some(x) = a.constant() {
            return Val::k(-x);
        }
        match self.op_of(a) {
            Some(Op::Neg(x)) => x,
            Some(Op::Sub(x, y)) => self.sub(y, x),
            Some(Op::Mul(Val::K(k), y)) => self.scale(-f64::from_bits(k), y),
            _ => self.node(Op::Neg(a)),
        }
    }

    /// `a / b`, folded when both are constants, `a` when `b` is one.
    pub(crate) fn div(&mut self, a: Val, b: Val) -> Val {
        match (a.constant(), b.constant()) {
            (Some(x), Some(y)) => return Val::k(x / y),
            (Some(0.0), _) => return Val::k(0.0),
            (_, Some(1.0)) => return a,
            (_, Some(y)) => return self.scale(1.0 / y, a),
            _ => {}
        }
        self.node(Op::Div(a, b))
    }

    pub(crate) fn powi(&mut self, a: Val, k: i32) -> Val {
        match (k, a.constant()) {
            (0, _) => Val::k(1.0),
            (1, _) => a,
            (_, Some(x)) => Val::k(x.powi(k)),
            (2, None) => self.mul(a, a),
            _ => self.node(Op::Powi(a, k)),
        }
    }

    pub(crate) fn sin_cos(&mut self, f: Func, a: Val) -> Val {
        match (f, a.constant()) {
            (Func::Sin, Some(x)) => Val::k(x.sin()),
            (Func::Cos, Some(x)) => Val::k(x.cos()),
            (Func::Sin, None) => self.node(Op::Sin(a)),
            (Func::Cos, None) => self.node(Op::Cos(a)),
            (Func::Sgn, Some(x)) => Val::k(crate::algebra::eval::sign(x)),
            (Func::Sgn, None) => self.node(Op::Sgn(a)),
        }
    }
}

fn sorted(a: Val, b: Val) -> (Val, Val) {
    // Constants first, then nodes by index: a total order, so `a · b` and `b · a` are one node.
    let key = |v: Val| match v {
        Val::K(bits) => (0, bits),
        Val::N(n) => (1, n as u64),
    };
    if key(a) <= key(b) {
        (a, b)
    } else {
        (b, a)
    }
}

/// A value of the traced recursion: a constant, or a node of a shared graph.
#[derive(Clone)]
pub struct Traced {
    pub(crate) val: Val,
    graph: Option<Rc<RefCell<Graph>>>,
}

impl std::fmt::Debug for Traced {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Traced({:?})", self.val)
    }
}

impl Traced {
    fn konst(x: f64) -> Traced {
        Traced {
            val: Val::k(x),
            graph: None,
        }
    }

    fn binary(&self, o: &Traced, f: impl FnOnce(&mut Graph, Val, Val) -> Val) -> Traced {
        let graph = self.graph.as_ref().or(o.graph.as_ref());
        match graph {
            Some(g) => Traced {
                val: f(&mut g.borrow_mut(), self.val, o.val),
                graph: Some(g.clone()),
            },
            // Two constants: fold in a scratch graph, which keeps no node for them.
            None => Traced::konst_of(f(&mut Graph::default(), self.val, o.val)),
        }
    }

    fn konst_of(v: Val) -> Traced {
        Traced {
            val: v,
            graph: None,
        }
    }
}

impl Scalar for Traced {
    fn zero() -> Self {
        Traced::konst(0.0)
    }
    fn from_rational(r: &Rational) -> Self {
        Traced::konst(r.to_f64())
    }
    fn add(&self, o: &Self) -> Self {
        self.binary(o, Graph::add)
    }
    fn sub(&self, o: &Self) -> Self {
        self.binary(o, Graph::sub)
    }
    fn mul(&self, o: &Self) -> Self {
        self.binary(o, Graph::mul)
    }
    fn neg(&self) -> Self {
        self.binary(&Traced::zero(), |g, a, _| g.neg(a))
    }
    fn is_exact_zero(&self) -> bool {
        self.val == Val::k(0.0)
    }
}

/// Turns exact polynomials into traced values: numeric parameters become constants, coordinates
/// become inputs, `sin`/`cos` atoms are traced once each.
pub(crate) struct Tracer {
    pub(crate) graph: Rc<RefCell<Graph>>,
    dof: usize,
    params: HashMap<Symbol, f64>,
    atoms: HashMap<AtomId, Val>,
    exprs: HashMap<Expr, Val>,
}

/// What a polynomial could not be traced for.
#[derive(Debug)]
pub(crate) enum TraceError {
    /// A parameter without a value.
    Missing(Symbol),
    /// A coordinate beyond the robot's joints or of order above 2.
    UnknownCoordinate(Symbol),
}

impl Tracer {
    pub(crate) fn new(dof: usize, params: HashMap<Symbol, f64>) -> Tracer {
        Tracer {
            graph: Rc::new(RefCell::new(Graph::default())),
            dof,
            params,
            atoms: HashMap::new(),
            exprs: HashMap::new(),
        }
    }

    /// A value of the traced graph.
    pub(crate) fn wrap(&self, val: Val) -> Traced {
        Traced {
            val,
            graph: Some(self.graph.clone()),
        }
    }

    /// `p` as a traced value: `Σ c · Π atom^k`, each monomial built left to right.
    pub(crate) fn poly(&mut self, p: &Poly) -> Result<Traced, TraceError> {
        let mut acc = Val::k(0.0);
        for (mono, coef) in p.terms() {
            let mut term = Val::k(coef.to_f64());
            for &(id, k) in mono.factors() {
                let a = self.atom(id)?;
                let mut g = self.graph.borrow_mut();
                let f = g.powi(a, k);
                term = g.mul(term, f);
            }
            acc = self.graph.borrow_mut().add(acc, term);
        }
        Ok(self.wrap(acc))
    }

    fn atom(&mut self, id: AtomId) -> Result<Val, TraceError> {
        if let Some(&v) = self.atoms.get(&id) {
            return Ok(v);
        }
        let v = self.expr(&atom::to_expr(id))?;
        self.atoms.insert(id, v);
        Ok(v)
    }

    fn symbol(&mut self, s: &Symbol) -> Result<Val, TraceError> {
        match s {
            Symbol::Param(_) => self
                .params
                .get(s)
                .map(|&x| Val::k(x))
                .ok_or_else(|| TraceError::Missing(s.clone())),
            Symbol::Coord { index, order } => {
                let i = *index as usize;
                if i == 0 || i > self.dof || *order > 2 {
                    return Err(TraceError::UnknownCoordinate(s.clone()));
                }
                let slot = *order as usize * self.dof + i - 1;
                Ok(self.graph.borrow_mut().input(slot as u32))
            }
        }
    }

    fn expr(&mut self, e: &Expr) -> Result<Val, TraceError> {
        if let Some(&v) = self.exprs.get(e) {
            return Ok(v);
        }
        let v = match e.kind() {
            Kind::Num(r) => Val::k(r.to_f64()),
            Kind::Sym(s) => self.symbol(s)?,
            Kind::Pi => Val::k(std::f64::consts::PI),
            Kind::Sqrt(k) => Val::k(
                num_traits::ToPrimitive::to_f64(k)
                    .unwrap_or(f64::NAN)
                    .sqrt(),
            ),
            Kind::Add(c, ts) => {
                let mut acc = Val::k(c.to_f64());
                for (t, k) in ts {
                    let t = self.expr(t)?;
                    let mut g = self.graph.borrow_mut();
                    let term = g.mul(Val::k(k.to_f64()), t);
                    acc = g.add(acc, term);
                }
                acc
            }
            Kind::Mul(c, fs) => {
                let mut acc = Val::k(c.to_f64());
                for (b, k) in fs {
                    let base = self.expr(b)?;
                    let mut g = self.graph.borrow_mut();
                    let p = g.powi(base, *k as i32);
                    acc = g.mul(acc, p);
                }
                acc
            }
            Kind::Fun(f, a) => {
                let arg = self.expr(a)?;
                self.graph.borrow_mut().sin_cos(*f, arg)
            }
        };
        self.exprs.insert(e.clone(), v);
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(x: f64) -> Traced {
        Traced::konst(x)
    }

    #[test]
    fn folds_constants_and_identities() {
        let tr = Tracer::new(1, HashMap::new());
        let q = tr.graph.borrow_mut().input(0);
        let q = tr.wrap(q);
        assert_eq!(t(2.0).mul(&t(3.0)).val, Val::k(6.0));
        assert_eq!(q.mul(&t(1.0)).val, q.val);
        assert!(q.mul(&t(0.0)).is_exact_zero());
        assert!(q.sub(&q).is_exact_zero());
        assert_eq!(q.neg().neg().val, q.val);
        // x + (−y) is one subtraction; a repeated product is one node.
        let p = q.mul(&q);
        let r = q.add(&p.neg());
        assert_eq!(
            tr.graph.borrow().nodes[r.val_index()],
            Op::Sub(q.val, p.val)
        );
        assert_eq!(q.mul(&q).val, p.val);
        // q, −q, q·q, −(q·q), q − q·q
        assert_eq!(tr.graph.borrow().nodes.len(), 5);
    }

    impl Traced {
        fn val_index(&self) -> usize {
            match self.val {
                Val::N(n) => n as usize,
                Val::K(_) => panic!("a constant"),
            }
        }
    }
}
