//! Derivatives on the compact form: `∂/∂x` and `d/dt` by the chain rule through the names.
//!
//! The derivative of a quantity `p` over names is `Σ ∂p/∂a · a'` over its atoms `a`; for a name `a`,
//! `a'` is the derivative of its definition, computed once, named (`w3_2` gives `w3_2_q2` for
//! `∂/∂q2`, `w3_2_t` for `d/dt`) and kept in the arena, so differentiating many quantities that share
//! names costs each name's derivative once. Names that cannot depend on the variable (by their
//! recorded [`super::TimeSet`]) are skipped without a look inside.

use super::Compact;
use crate::algebra::atom::{self, AtomId, Class};
use crate::algebra::calculus::{poly_diff, poly_dt};
use crate::algebra::{Poly, Symbol};

/// Which derivative.
#[derive(Clone, Copy)]
enum Wrt<'a> {
    /// `∂/∂x`.
    Var(&'a Symbol, AtomId),
    /// `d/dt`.
    Time,
}

impl Compact {
    /// `∂p/∂x`, names differentiated by the chain rule (each name's derivative named once).
    pub fn diff(&mut self, p: &Poly, x: &Symbol) -> Poly {
        self.derivative(p, Wrt::Var(x, atom::sym(x)))
    }

    /// `dp/dt`: `q_i^(k)` depends on time, every other symbol is constant.
    pub fn dt(&mut self, p: &Poly) -> Poly {
        self.derivative(p, Wrt::Time)
    }

    fn memo(&self, k: u32, wrt: Wrt) -> Option<&Poly> {
        match wrt {
            Wrt::Var(_, x) => self.diff_memo.get(&(k, x)),
            Wrt::Time => self.dt_memo.get(&k),
        }
    }

    /// Whether definition `k` may depend on the variable.
    fn may_vary(&self, k: usize, wrt: Wrt) -> bool {
        match wrt {
            Wrt::Var(x, _) if x.is_coord() => self.defs[k].deps.contains(x),
            Wrt::Var(x, _) => self.may_depend_on(&Poly::atom(self.defs[k].atom), x),
            Wrt::Time => !self.defs[k].deps.is_empty(),
        }
    }

    fn derivative(&mut self, p: &Poly, wrt: Wrt) -> Poly {
        // The names whose derivatives are still missing, found depth-first, then computed in
        // definition order (each refers to earlier names only).
        let mut todo: Vec<usize> = Vec::new();
        let mut stack = self.names_in(p);
        let mut seen = vec![false; self.defs.len()];
        while let Some(k) = stack.pop() {
            if seen[k] || self.memo(k as u32, wrt).is_some() || !self.may_vary(k, wrt) {
                continue;
            }
            seen[k] = true;
            todo.push(k);
            stack.extend(self.names_in(&self.defs[k].value));
        }
        todo.sort_unstable();
        for k in todo {
            let value = self.defs[k].value.clone();
            let d = self.derive_one(&value, wrt);
            let hint = match wrt {
                Wrt::Var(x, _) => {
                    format!("{}_{}", self.defs[k].symbol.ascii_name(), x.ascii_name())
                }
                Wrt::Time => format!("{}_t", self.defs[k].symbol.ascii_name()),
            };
            let named = self.name(d, &hint);
            match wrt {
                Wrt::Var(_, x) => self.diff_memo.insert((k as u32, x), named),
                Wrt::Time => self.dt_memo.insert(k as u32, named),
            };
        }
        self.derive_one(p, wrt)
    }

    /// The derivative of `p` with every name's derivative already in the memo (or zero).
    fn derive_one(&self, p: &Poly, wrt: Wrt) -> Poly {
        p.derive(&mut |id| {
            if let Some(k) = self.index_of(id) {
                return self.memo(k as u32, wrt).filter(|d| !d.is_zero()).cloned();
            }
            match wrt {
                Wrt::Var(x, x_id) => {
                    if id == x_id {
                        return Some(Poly::one());
                    }
                    match atom::class(id) {
                        Class::Param | Class::Coord | Class::Pi | Class::Sqrt => None,
                        _ => {
                            let d = poly_diff(&Poly::atom(id), x);
                            (!d.is_zero()).then_some(d)
                        }
                    }
                }
                Wrt::Time => time_derivative_of_atom(id),
            }
        })
    }
}

/// `d/dt` of a plain atom (not a name): the derivative table of the normal form's own calculus.
fn time_derivative_of_atom(id: AtomId) -> Option<Poly> {
    let d = poly_dt(&Poly::atom(id));
    (!d.is_zero()).then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    /// A small chain of names whose expansion is known, differentiated both ways.
    #[test]
    fn derivatives_through_names_equal_derivatives_of_the_expansion() {
        let mut c = Compact::new();
        let a = c.name(p("l*cos(q1) + m*qd1"), "a");
        let b = c.name(a.mul(&p("sin(q2)")).add(&p("x*q1")), "b");
        let e = b.mul(&a).add(&p("qd2*sin(q1)"));
        let expanded = c.expander(10_000).expand(&e).expect("small");
        for x in ["q1", "q2", "qd1", "l", "x"] {
            let s = Symbol::new(x);
            let d = c.diff(&e, &s);
            let want = poly_diff(&expanded, &s);
            assert_eq!(c.expander(10_000).expand(&d), Ok(want), "∂/∂{x}");
        }
        let d = c.dt(&e);
        assert_eq!(
            c.expander(10_000).expand(&d),
            Ok(poly_dt(&expanded)),
            "d/dt"
        );
    }

    #[test]
    fn derivatives_of_names_are_named_once_and_skipped_when_constant() {
        let mut c = Compact::new();
        let a = c.name(p("l*cos(q1) + m*qd1"), "a");
        let k = c.name(p("l*m + x"), "k");
        let before = c.len();
        let d1 = c.diff(&a.mul(&k), &Symbol::q(1));
        assert_eq!(c.len(), before + 1, "∂a/∂q1 = −l sin q1 is named once");
        assert_eq!(c.defs()[before].symbol, Symbol::new("a_q1"));
        assert_eq!(c.defs()[before].value, p("-l*sin(q1)"));
        let da = Poly::atom(c.defs()[before].atom);
        assert_eq!(d1, da.mul(&k));
        let d2 = c.diff(&a.mul(&k).add(&a), &Symbol::q(1));
        assert_eq!(c.len(), before + 1, "and reused");
        assert_eq!(d2, da.mul(&k).add(&da));
        assert!(c.diff(&k, &Symbol::q(1)).is_zero());
        assert!(c.dt(&k).is_zero());
    }
}
