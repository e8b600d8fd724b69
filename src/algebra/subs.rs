//! Substitution of symbols by expressions, rebuilt through the canonical constructors (so `sin(q1)`
//! with `q1 = pi/2` becomes `1`).

use super::error::AlgebraError;
use super::expr::{Expr, Kind};
use super::symbol::Symbol;
use std::collections::HashMap;

/// `e` with every symbol in `map` replaced by its value. An error only where a replacement makes a
/// denominator zero (`1/x` with `x = 0`).
pub fn subs(e: &Expr, map: &HashMap<Symbol, Expr>) -> Result<Expr, AlgebraError> {
    Ok(match e.kind() {
        Kind::Num(_) | Kind::Pi | Kind::Sqrt(_) => e.clone(),
        Kind::Sym(s) => map.get(s).cloned().unwrap_or_else(|| e.clone()),
        Kind::Add(c, ts) => {
            let mut parts = Vec::with_capacity(ts.len() + 1);
            parts.push(Expr::num(c.clone()));
            for (t, k) in ts {
                parts.push(subs(t, map)?.scale(k));
            }
            Expr::sum(parts)
        }
        Kind::Mul(c, fs) => {
            let mut parts = Vec::with_capacity(fs.len() + 1);
            parts.push(Expr::num(c.clone()));
            for (b, k) in fs {
                parts.push(subs(b, map)?.pow(*k)?);
            }
            Expr::product(parts)
        }
        Kind::Fun(f, a) => Expr::fun(*f, &subs(a, map)?),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_values_after_substitution() {
        let e = Expr::sin(&Expr::q(1)) * Expr::symbol("m");
        let map = HashMap::from([
            (Symbol::q(1), Expr::pi() * Expr::frac(1, 2).unwrap()),
            (Symbol::new("m"), Expr::frac(3, 2).unwrap()),
        ]);
        assert_eq!(subs(&e, &map).unwrap(), Expr::frac(3, 2).unwrap());
        let inv = Expr::one().div(&Expr::symbol("x")).unwrap();
        let zero = HashMap::from([(Symbol::new("x"), Expr::zero())]);
        assert_eq!(subs(&inv, &zero), Err(AlgebraError::DivisionByZero));
    }
}
