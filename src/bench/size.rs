//! The size of a derived result: how many terms, and how many arithmetic operations a straight-line
//! evaluation of its printed form costs.
//!
//! Both are measured on what symdyn prints: the expanded normal form (`Poly`) for terms, and the
//! canonical [`Expr`] of `Poly::to_expr` for operations, evaluated node by node with no sharing
//! between terms (the compiled tape of `numeric::tape` shares far more; its instruction counts are
//! reported separately). The operation count of an expression is defined recursively:
//!
//! - a number, a symbol, `π` or `sqrt(k)` costs nothing (constants);
//! - a sum of `k` terms (the constant counting as a term when non-zero) costs `k − 1` additions;
//!   subtraction counts as an addition, so a term with coefficient `−1` is free; a term with any other
//!   coefficient `c ≠ ±1` costs one multiplication (`c · term`), plus the term's own cost;
//! - a product of `k` factors `b^e` costs `k − 1` multiplications, plus one for a coefficient
//!   `c ≠ ±1`; a negative coefficient's sign is free (folded into the enclosing sum);
//! - a power `x^n` is counted as `|n| − 1` multiplications (repeated multiplication, not one `pow`);
//!   a negative exponent makes a division, counted as a multiplication: `y/x` is one, `y/x^2` two; a
//!   product whose every factor has a negative exponent and whose coefficient is `±1` (`1/x`) costs
//!   one more, the reciprocal;
//! - `sin(a)`, `cos(a)` cost their argument's operations; the call itself is counted in
//!   [`Size::calls`], not in the operations.
//!
//! Examples (each is a row of the tests): `x` 0; `x + y` 1 addition; `2 x` 1 multiplication;
//! `x − y` 1 addition; `x^3` 2 multiplications; `2 x y + z` 2 multiplications, 1 addition;
//! `sin(q1 + q2) m` 1 multiplication, 1 addition, 1 call.

use crate::algebra::{Expr, Kind, Poly, Rational};

/// The size of one expression or a list of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Size {
    /// Terms of the expanded normal form (`Poly::len`, summed over the list).
    pub terms: u64,
    /// Multiplications (and divisions) in the canonical expression.
    pub mults: u64,
    /// Additions (and subtractions).
    pub adds: u64,
    /// Calls of `sin` and `cos`.
    pub calls: u64,
}

impl Size {
    /// Multiplications plus additions.
    pub fn ops(&self) -> u64 {
        self.mults + self.adds
    }

    /// The size of a list of polynomials (terms from the `Poly`, operations from `to_expr`).
    pub fn of_polys<'a, I: IntoIterator<Item = &'a Poly>>(polys: I) -> Size {
        let mut s = Size::default();
        for p in polys {
            s.terms += p.len() as u64;
            count(&p.to_expr(), &mut s);
        }
        s
    }

    /// The operations of one expression (its `terms` is its number of top-level terms).
    pub fn of_expr(e: &Expr) -> Size {
        let mut s = Size {
            terms: e.terms().len() as u64,
            ..Size::default()
        };
        count(e, &mut s);
        s
    }
}

fn is_unit(c: &Rational) -> bool {
    c.is_one() || c.is_minus_one()
}

fn count(e: &Expr, s: &mut Size) {
    match e.kind() {
        Kind::Num(_) | Kind::Sym(_) | Kind::Pi | Kind::Sqrt(_) => {}
        Kind::Add(c, ts) => {
            let k = ts.len() + usize::from(!c.is_zero());
            s.adds += k.saturating_sub(1) as u64;
            for (t, coeff) in ts {
                if !is_unit(coeff) {
                    s.mults += 1;
                }
                count(t, s);
            }
        }
        Kind::Mul(c, fs) => {
            s.mults += fs.len().saturating_sub(1) as u64;
            if !is_unit(c) {
                s.mults += 1;
            }
            for (b, e) in fs {
                s.mults += e.unsigned_abs() - 1;
                count(b, s);
            }
            if is_unit(c) && !fs.is_empty() && fs.iter().all(|(_, e)| *e < 0) {
                s.mults += 1;
            }
        }
        Kind::Fun(_, a) => {
            s.calls += 1;
            count(a, s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::parse_expr;

    fn check(src: &str, mults: u64, adds: u64, calls: u64) {
        let s = Size::of_expr(&parse_expr(src).unwrap());
        assert_eq!((s.mults, s.adds, s.calls), (mults, adds, calls), "{src}");
    }

    #[test]
    fn operation_counts_follow_the_definition() {
        check("x", 0, 0, 0);
        check("x + y", 0, 1, 0);
        check("2*x", 1, 0, 0);
        check("x - y", 0, 1, 0);
        check("-x", 0, 0, 0);
        check("x^3", 2, 0, 0);
        check("2*x*y + z", 2, 1, 0);
        check("sin(q1 + q2)*m", 1, 1, 1);
        check("y/x", 1, 0, 0);
        check("y/x^2", 2, 0, 0);
        check("1/x", 1, 0, 0);
        check("x*y + 3", 1, 1, 0);
        check("1/2*m*l^2", 3, 0, 0);
    }

    #[test]
    fn terms_of_polys_add_up() {
        let p = crate::algebra::to_poly(&parse_expr("x + 2*y + 3").unwrap());
        let q = crate::algebra::to_poly(&parse_expr("x*y").unwrap());
        let s = Size::of_polys([&p, &q]);
        assert_eq!(s.terms, 4);
        assert_eq!(s.ops(), 2 + 1 + 1);
    }
}
