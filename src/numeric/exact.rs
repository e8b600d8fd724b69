//! Exact evaluation: every symbol valued by an exact expression ([`crate::algebra::eval_exact`]), results
//! as canonical expressions, rationals when they are rational; and the forward dynamics solved over the
//! rationals.

use super::forward::{condition_number, COND_LIMIT};
use super::NumericError;
use crate::algebra::{eval_exact, Expr, Poly, Rational, Symbol};
use crate::print::{self, Style};
use nalgebra::DMatrix;
use std::collections::{BTreeSet, HashMap};

/// The exact values of `polys`; fails listing every symbol without a value.
pub fn exact_values(
    polys: &[Poly],
    values: &HashMap<Symbol, Expr>,
) -> Result<Vec<Expr>, NumericError> {
    let exprs: Vec<Expr> = polys.iter().map(Poly::to_expr).collect();
    let missing: BTreeSet<Symbol> = exprs
        .iter()
        .flat_map(Expr::symbols)
        .filter(|s| !values.contains_key(s))
        .collect();
    if !missing.is_empty() {
        return Err(NumericError::Missing(missing.into_iter().collect()));
    }
    exprs.iter().map(|e| Ok(eval_exact(e, values)?)).collect()
}

/// The values as rationals; fails at the first that is not rational, naming it by its label.
pub fn rationals(values: &[Expr], labels: &[String]) -> Result<Vec<Rational>, NumericError> {
    values
        .iter()
        .zip(labels)
        .map(|(e, label)| {
            e.as_rational()
                .cloned()
                .ok_or_else(|| NumericError::NotRational {
                    what: label.clone(),
                    value: print::to_string(e, Style::Ascii),
                })
        })
        .collect()
}

/// Solves `D q̈ = rhs` exactly by Gaussian elimination, after refusing a `D` whose condition number
/// (in `f64`, as in [`super::forward_dynamics`]) exceeds [`COND_LIMIT`].
pub fn exact_forward_dynamics(
    d: &[Vec<Rational>],
    rhs: &[Rational],
) -> Result<Vec<Rational>, NumericError> {
    let n = rhs.len();
    let df = DMatrix::from_fn(n, n, |r, c| d[r][c].to_f64());
    let cond = condition_number(&df);
    if cond.is_nan() || cond > COND_LIMIT {
        return Err(NumericError::Singular { cond });
    }
    let mut a: Vec<Vec<Rational>> = d
        .iter()
        .zip(rhs)
        .map(|(row, b)| row.iter().cloned().chain([b.clone()]).collect())
        .collect();
    for col in 0..n {
        let pivot = (col..n)
            .find(|&r| !a[r][col].is_zero())
            .ok_or(NumericError::Singular { cond })?;
        a.swap(col, pivot);
        let inv = a[col][col].recip().ok_or(NumericError::Singular { cond })?;
        for r in 0..n {
            if r != col && !a[r][col].is_zero() {
                let f = &a[r][col] * &inv;
                for c in col..=n {
                    let v = &a[r][c] - &(&f * &a[col][c]);
                    a[r][c] = v;
                }
            }
        }
    }
    Ok((0..n)
        .map(|i| {
            let inv = a[i][i].recip().expect("non-zero pivot");
            &a[i][n] * &inv
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_exactly() {
        let r = |n, d| Rational::new(n, d).unwrap();
        let d = vec![vec![r(2, 1), r(1, 1)], vec![r(1, 1), r(3, 1)]];
        let x = exact_forward_dynamics(&d, &[r(1, 1), r(2, 1)]).unwrap();
        assert_eq!(x, vec![r(1, 5), r(3, 5)]);
        let zero = vec![vec![r(0, 1); 2]; 2];
        assert!(matches!(
            exact_forward_dynamics(&zero, &[r(1, 1), r(2, 1)]),
            Err(NumericError::Singular { .. })
        ));
    }
}
