//! Numeric evaluation: in `f64`, and exactly where every value is rational.

use super::error::AlgebraError;
use super::expr::{Expr, Func, Kind};
use super::subs::subs;
use super::symbol::Symbol;
use std::collections::{BTreeSet, HashMap};
use thiserror::Error;

/// Why an expression has no numeric value.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum EvalError {
    /// Symbols without a value, sorted.
    #[error("no value given for {}", .0.iter().map(|s| s.ascii_name()).collect::<Vec<_>>().join(", "))]
    Unbound(Vec<Symbol>),
    /// An algebraic failure such as a division by zero.
    #[error(transparent)]
    Algebra(#[from] AlgebraError),
}

fn missing(e: &Expr, values: &dyn Fn(&Symbol) -> bool) -> Vec<Symbol> {
    let all: BTreeSet<Symbol> = e.symbols();
    all.into_iter().filter(|s| !values(s)).collect()
}

/// The `f64` value of `e` with the symbols valued by `values`.
pub fn eval_f64(e: &Expr, values: &HashMap<Symbol, f64>) -> Result<f64, EvalError> {
    let unbound = missing(e, &|s| values.contains_key(s));
    if !unbound.is_empty() {
        return Err(EvalError::Unbound(unbound));
    }
    Ok(eval_unchecked(e, values))
}

/// `sgn x`: −1, 0 or 1 (0 at 0, unlike `f64::signum`).
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

fn eval_unchecked(e: &Expr, values: &HashMap<Symbol, f64>) -> f64 {
    match e.kind() {
        Kind::Num(r) => r.to_f64(),
        Kind::Sym(s) => values[s],
        Kind::Pi => std::f64::consts::PI,
        Kind::Sqrt(k) => num_traits::ToPrimitive::to_f64(k)
            .unwrap_or(f64::NAN)
            .sqrt(),
        Kind::Add(c, ts) => ts.iter().fold(c.to_f64(), |acc, (t, k)| {
            acc + k.to_f64() * eval_unchecked(t, values)
        }),
        Kind::Mul(c, fs) => fs.iter().fold(c.to_f64(), |acc, (b, k)| {
            acc * eval_unchecked(b, values).powi(*k as i32)
        }),
        Kind::Fun(Func::Sin, a) => eval_unchecked(a, values).sin(),
        Kind::Fun(Func::Cos, a) => eval_unchecked(a, values).cos(),
        Kind::Fun(Func::Sgn, a) => sign(eval_unchecked(a, values)),
    }
}

/// The exact value of `e` with every symbol given an exact value: a canonical expression free of
/// symbols, a plain rational whenever the value is rational (`sqrt(2)` or `sin(1)` stay symbolic).
pub fn eval_exact(e: &Expr, values: &HashMap<Symbol, Expr>) -> Result<Expr, EvalError> {
    let unbound = missing(e, &|s| values.contains_key(s));
    if !unbound.is_empty() {
        return Err(EvalError::Unbound(unbound));
    }
    let v = subs(e, values)?;
    Ok(super::normal::normal_form(&v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_and_exact() {
        let e = Expr::symbol("m") * Expr::cos(&Expr::q(1)) + Expr::frac(1, 3).unwrap();
        let vals = HashMap::from([(Symbol::new("m"), 2.0), (Symbol::q(1), 0.0)]);
        assert!((eval_f64(&e, &vals).unwrap() - (2.0 + 1.0 / 3.0)).abs() < 1e-15);
        let exact = HashMap::from([
            (Symbol::new("m"), Expr::int(2)),
            (Symbol::q(1), Expr::zero()),
        ]);
        assert_eq!(eval_exact(&e, &exact).unwrap(), Expr::frac(7, 3).unwrap());
        let err = eval_f64(&e, &HashMap::new()).unwrap_err();
        assert_eq!(err.to_string(), "no value given for m, q1");
    }
}
