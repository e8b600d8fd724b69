//! Derivatives: the partial derivative by a symbol and the total time derivative.
//!
//! Both are one chain-rule walk over the expression, parameterised by the derivative of a symbol:
//! `∂/∂x` maps `x` to 1 and every other symbol to 0; `d/dt` maps `q_i^(k)` to `q_i^(k+1)` and every
//! parameter to 0. The walk is an exhaustive `match` (a new node kind cannot be forgotten); the
//! elementary derivatives live in [`derivative_of_fun`], apart from the walk.

use super::atom::{self, Class};
use super::expr::{Expr, Func, Kind};
use super::normal::to_poly;
use super::number::Rational;
use super::poly::Poly;
use super::symbol::Symbol;

/// The elementary derivative table: `f'(a)` for `f(a)`.
pub fn derivative_of_fun(f: Func, a: &Expr) -> Expr {
    match f {
        Func::Sin => Expr::cos(a),
        Func::Cos => -Expr::sin(a),
        // Zero wherever it is defined (a ≠ 0): Coulomb friction is never differentiated in time.
        Func::Sgn => Expr::zero(),
    }
}

/// The derivative of `e` given the derivative of each symbol (`None` means zero).
fn walk(e: &Expr, d_sym: &dyn Fn(&Symbol) -> Option<Expr>) -> Expr {
    match e.kind() {
        Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) => Expr::zero(),
        Kind::Sym(s) => d_sym(s).unwrap_or_else(Expr::zero),
        Kind::Add(_, ts) => Expr::sum(ts.iter().map(|(t, k)| walk(t, d_sym).scale(k))),
        Kind::Mul(c, fs) => {
            let mut terms = Vec::with_capacity(fs.len());
            for (i, (b, k)) in fs.iter().enumerate() {
                let db = walk(b, d_sym);
                if db.is_zero() {
                    continue;
                }
                let mut factors = Vec::with_capacity(fs.len() + 2);
                factors.push(Expr::num(c * &super::number::Rational::int(*k)));
                factors.push(db);
                for (j, (b2, k2)) in fs.iter().enumerate() {
                    let e = if i == j { k2 - 1 } else { *k2 };
                    if e != 0 {
                        factors.push(b2.pow(e).expect("bases are never zero"));
                    }
                }
                terms.push(Expr::product(factors));
            }
            Expr::sum(terms)
        }
        Kind::Fun(f, a) => {
            let da = walk(a, d_sym);
            if da.is_zero() {
                Expr::zero()
            } else {
                derivative_of_fun(*f, a) * da
            }
        }
    }
}

/// `∂e/∂x`.
pub fn diff(e: &Expr, x: &Symbol) -> Expr {
    walk(e, &|s| (s == x).then(Expr::one))
}

/// The total time derivative `de/dt`: `q_i^(k)` depends on time, every other symbol is constant.
pub fn dt(e: &Expr) -> Expr {
    walk(e, &|s| s.time_derivative().map(Expr::sym))
}

/// The derivative of the `sin`/`cos` atom `id` of the angle `x/over` by its angle's symbol:
/// `cos(x/over)/over` or `−sin(x/over)/over`.
fn trig_rate(id: atom::AtomId, over: u64) -> Poly {
    let partner = Poly::atom(atom::partner(id));
    let d = if atom::class(id) == Class::Sin {
        partner
    } else {
        partner.neg()
    };
    match over {
        1 => d,
        _ => d.scale(
            &Rational::from(num_bigint::BigInt::from(over))
                .recip()
                .expect("over >= 2"),
        ),
    }
}

/// `∂p/∂x` on the normal form.
pub fn poly_diff(p: &Poly, x: &Symbol) -> Poly {
    let x_id = atom::sym(x);
    p.derive(&mut |id| {
        if id == x_id {
            return Some(Poly::one());
        }
        match atom::class(id) {
            Class::Sin | Class::Cos => match atom::angle_of(id) {
                Some((y, over)) if &y == x => Some(trig_rate(id, over)),
                _ => None,
            },
            Class::Other => match atom::lookup(id) {
                atom::Atom::Other(e) if e.contains(x) => Some(to_poly(&diff(&e, x))),
                _ => None,
            },
            _ => None,
        }
    })
}

/// `dp/dt` on the normal form.
pub fn poly_dt(p: &Poly) -> Poly {
    p.derive(&mut |id| match atom::class(id) {
        Class::Coord => {
            let s = atom::symbol_of(id)?;
            Some(Poly::symbol(&s.time_derivative()?))
        }
        Class::Sin | Class::Cos => {
            let (x, over) = atom::angle_of(id)?;
            let xd = Poly::symbol(&x.time_derivative()?);
            Some(trig_rate(id, over).mul(&xd))
        }
        Class::Other => match atom::lookup(id) {
            atom::Atom::Other(e) => {
                let d = dt(&e);
                (!d.is_zero()).then(|| to_poly(&d))
            }
            _ => None,
        },
        Class::Param | Class::Pi | Class::Sqrt | Class::CosPi | Class::SinPi => None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::normal::equal;

    #[test]
    fn derivative_table() {
        let x = Expr::symbol("x");
        let rows = [(Func::Sin, Expr::cos(&x)), (Func::Cos, -Expr::sin(&x))];
        for (f, want) in rows {
            assert_eq!(diff(&Expr::fun(f, &x), &Symbol::new("x")), want);
        }
    }

    #[test]
    fn issue_examples() {
        let m2 = Expr::symbol("m2");
        let lc2 = Expr::symbol("lc2");
        let e = &m2 * &lc2.pow(2).unwrap() * Expr::sin(&Expr::q(2)).pow(2).unwrap();
        let want = Expr::int(2)
            * &m2
            * lc2.pow(2).unwrap()
            * Expr::sin(&Expr::q(2))
            * Expr::cos(&Expr::q(2));
        assert_eq!(diff(&e, &Symbol::q(2)), want);
        let e = Expr::sin(&Expr::q(1)) * Expr::qd(2);
        let want = Expr::cos(&Expr::q(1)) * Expr::qd(1) * Expr::qd(2)
            + Expr::sin(&Expr::q(1)) * Expr::qdd(2);
        assert_eq!(dt(&e), want);
    }

    #[test]
    fn poly_and_expr_derivatives_agree() {
        let e = Expr::cos(&(Expr::q(1) + Expr::q(2))) * Expr::qd(1) * Expr::symbol("m")
            + Expr::sin(&Expr::q(2)).pow(3).unwrap();
        let p = to_poly(&e);
        assert!(equal(&poly_dt(&p).to_expr(), &dt(&e)));
        assert!(equal(
            &poly_diff(&p, &Symbol::q(2)).to_expr(),
            &diff(&e, &Symbol::q(2))
        ));
    }
}
