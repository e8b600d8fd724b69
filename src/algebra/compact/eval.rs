//! Values of compact quantities: each name computed once, in definition order, in any [`Ring`]
//! (`f64`, or exact [`Rational`]s for proofs and reference values).

use super::Compact;
use crate::algebra::atom::AtomId;
use crate::algebra::fast_hash::FxHashMap;
use crate::algebra::{Poly, Rational};
use thiserror::Error;

/// The arithmetic an evaluation needs.
pub trait Ring: Clone {
    /// An exact constant.
    fn from_rational(r: &Rational) -> Self;
    /// `self + o`.
    fn add(&self, o: &Self) -> Self;
    /// `self · o`.
    fn mul(&self, o: &Self) -> Self;
    /// `self^e`; `None` for a negative power of zero.
    fn powi(&self, e: i32) -> Option<Self>;
}

impl Ring for f64 {
    fn from_rational(r: &Rational) -> Self {
        r.to_f64()
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn powi(&self, e: i32) -> Option<Self> {
        Some(f64::powi(*self, e))
    }
}

impl Ring for Rational {
    fn from_rational(r: &Rational) -> Self {
        r.clone()
    }
    fn add(&self, o: &Self) -> Self {
        self + o
    }
    fn mul(&self, o: &Self) -> Self {
        self * o
    }
    fn powi(&self, e: i32) -> Option<Self> {
        self.pow(e as i64)
    }
}

/// Why a value could not be computed.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum EvalFailure {
    /// An atom without a value (a symbol not given, or an atom the caller cannot value).
    #[error("no value for {0}")]
    Unbound(String),
    /// A negative power of zero.
    #[error("division by zero")]
    DivisionByZero,
}

/// Evaluates `outputs` with the leaves (every atom that is not a name) valued by `leaf`.
pub fn eval<T: Ring>(
    arena: &Compact,
    outputs: &[&Poly],
    leaf: &mut dyn FnMut(AtomId) -> Option<T>,
) -> Result<Vec<T>, EvalFailure> {
    let mut ev = Evaluation {
        arena,
        names: FxHashMap::default(),
        leaves: FxHashMap::default(),
    };
    for k in arena.live(outputs.iter().copied()) {
        let v = ev.poly(&arena.defs()[k].value, leaf)?;
        ev.names.insert(arena.defs()[k].atom, v);
    }
    outputs.iter().map(|p| ev.poly(p, leaf)).collect()
}

struct Evaluation<'a, T> {
    arena: &'a Compact,
    names: FxHashMap<AtomId, T>,
    leaves: FxHashMap<AtomId, T>,
}

impl<T: Ring> Evaluation<'_, T> {
    fn atom(
        &mut self,
        id: AtomId,
        leaf: &mut dyn FnMut(AtomId) -> Option<T>,
    ) -> Result<T, EvalFailure> {
        if let Some(v) = self.names.get(&id).or_else(|| self.leaves.get(&id)) {
            return Ok(v.clone());
        }
        debug_assert!(
            self.arena.index_of(id).is_none(),
            "names are valued in order"
        );
        let v = leaf(id).ok_or_else(|| EvalFailure::Unbound(super::atom_name(id)))?;
        self.leaves.insert(id, v.clone());
        Ok(v)
    }

    fn poly(
        &mut self,
        p: &Poly,
        leaf: &mut dyn FnMut(AtomId) -> Option<T>,
    ) -> Result<T, EvalFailure> {
        let mut acc = T::from_rational(&Rational::zero());
        for (m, c) in p.terms() {
            let mut t = T::from_rational(c);
            for &(id, e) in m.factors() {
                let v = self.atom(id, leaf)?;
                let v = if e == 1 {
                    v
                } else {
                    v.powi(e).ok_or(EvalFailure::DivisionByZero)?
                };
                t = t.mul(&v);
            }
            acc = acc.add(&t);
        }
        Ok(acc)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::{atom, to_poly, Symbol};

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn names_are_valued_once_in_order() {
        let mut c = Compact::new();
        let a = c.name(p("x + 2*y"), "a");
        let b = c.name(a.mul(&a).add(&p("1/2")), "b");
        let out = b.mul(&p("x")).sub(&a);
        let x = atom::sym(&Symbol::new("x"));
        let y = atom::sym(&Symbol::new("y"));
        let value = |id| {
            if id == x {
                Some(Rational::int(3))
            } else if id == y {
                Some(Rational::new(1, 2).expect("non-zero"))
            } else {
                None
            }
        };
        // a = 4, b = 33/2, out = 3 · 33/2 − 4 = 91/2
        let got = eval(&c, &[&out], &mut |id| value(id)).expect("every leaf valued");
        assert_eq!(got, vec![Rational::new(91, 2).expect("non-zero")]);
        let got: Vec<f64> =
            eval(&c, &[&out], &mut |id| value(id).map(|r| r.to_f64())).expect("valued");
        assert_eq!(got, vec![45.5]);
        assert_eq!(
            eval::<f64>(&c, &[&out], &mut |_| None),
            Err(EvalFailure::Unbound("x".into()))
        );
    }
}
