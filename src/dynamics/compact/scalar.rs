//! A scalar that keeps any recursion written over [`Scalar`] in compact form: [`Named`] values are
//! polynomials over one shared arena, and a product never multiplies two sums — a factor with more
//! than one term is named first (`v17 = …`), so every value stays a short sum of short products, and
//! the recursion's own checkpoints ([`Scalar::label`]: `ω_i`, `α_i`, `f_i`, …) name its book
//! quantities. This is how the Newton–Euler recursion of [`crate::dynamics::newton_euler`] runs in the
//! inertial frame on the compact form, with no second implementation.

use crate::algebra::compact::Compact;
use crate::algebra::{Poly, Rational};
use crate::dynamics::scalar::Scalar;
use crate::dynamics::vec3::Vec3;
use std::cell::RefCell;
use std::rc::Rc;

/// A polynomial over the names of a shared arena (constants carry no arena: they need none).
#[derive(Clone, Debug)]
pub struct Named {
    arena: Option<Rc<RefCell<Compact>>>,
    value: Poly,
}

impl Named {
    /// `value` over `arena`.
    pub fn new(arena: &Rc<RefCell<Compact>>, value: Poly) -> Named {
        Named {
            arena: Some(arena.clone()),
            value,
        }
    }

    /// The polynomial.
    pub fn value(&self) -> &Poly {
        &self.value
    }

    /// Takes the polynomial.
    pub fn into_value(self) -> Poly {
        self.value
    }

    fn arena_of<'a>(&'a self, o: &'a Named) -> Option<Rc<RefCell<Compact>>> {
        self.arena.clone().or_else(|| o.arena.clone())
    }

    /// The value as a factor of a product: itself when it is a single term, else its name.
    fn factor(&self, arena: &Option<Rc<RefCell<Compact>>>) -> Poly {
        match arena {
            Some(a) if self.value.len() > 1 => {
                let mut a = a.borrow_mut();
                let hint = format!("v{}", a.len() + 1);
                a.name(self.value.clone(), &hint)
            }
            _ => self.value.clone(),
        }
    }
}

impl Scalar for Named {
    fn zero() -> Self {
        Named {
            arena: None,
            value: Poly::zero(),
        }
    }
    fn from_rational(r: &Rational) -> Self {
        Named {
            arena: None,
            value: Poly::constant(r.clone()),
        }
    }
    fn add(&self, o: &Self) -> Self {
        Named {
            arena: self.arena_of(o),
            value: self.value.add(&o.value),
        }
    }
    fn sub(&self, o: &Self) -> Self {
        Named {
            arena: self.arena_of(o),
            value: self.value.sub(&o.value),
        }
    }
    fn mul(&self, o: &Self) -> Self {
        if self.value.is_zero() || o.value.is_zero() {
            return Named::zero();
        }
        let arena = self.arena_of(o);
        let value = self.factor(&arena).mul(&o.factor(&arena));
        Named { arena, value }
    }
    fn neg(&self) -> Self {
        Named {
            arena: self.arena.clone(),
            value: self.value.neg(),
        }
    }
    fn is_exact_zero(&self) -> bool {
        self.value.is_zero()
    }
    fn label(v: Vec3<Self>, hint: &dyn Fn() -> String) -> Vec3<Self> {
        let Some(arena) = v.0.iter().find_map(|x| x.arena.clone()) else {
            return v;
        };
        let base = hint();
        let mut a = arena.borrow_mut();
        Vec3(std::array::from_fn(|k| Named {
            arena: Some(arena.clone()),
            value: a.name(v.0[k].value.clone(), &format!("{base}_{}", k + 1)),
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    #[test]
    fn products_of_sums_name_their_factors() {
        let arena = Rc::new(RefCell::new(Compact::new()));
        let a = Named::new(&arena, p("x + y"));
        let b = Named::new(&arena, p("z"));
        let ab = a.mul(&b).mul(&a);
        assert_eq!(arena.borrow().len(), 1, "x + y named once (hash-consed)");
        let v = Poly::atom(arena.borrow().defs()[0].atom);
        assert_eq!(ab.value(), &v.mul(&v).mul(&p("z")));
        let expanded = arena.borrow().expander(100).expand(ab.value());
        assert_eq!(expanded, Ok(p("(x + y)^2*z")));
    }
}
