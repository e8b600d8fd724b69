//! Canonical `sin` and `cos`: the sign and the multiples of π/2 come out of the argument, and the exact
//! values at rational multiples of π that are square roots of rationals (or sums of two) are known.
//!
//! Rules, applied when a `sin` or `cos` is built:
//! - split the argument into `x + r π` with `r` rational and `x` free of a π term;
//! - if `x` reads negative, use `sin(-y) = -sin(y)`, `cos(-y) = cos(y)`;
//! - reduce `r` modulo 2, then take out π (`sin(y + π) = -sin(y)`) and π/2 (`sin(y + π/2) = cos(y)`,
//!   `cos(y + π/2) = -sin(y)`), leaving `0 <= r < 1/2`;
//! - if `x` is zero and `r` is a multiple of π/12, the value is exact: `cos(π/3) = 1/2`,
//!   `sin(π/4) = sqrt(2)/2`, `sin(π/12) = (sqrt(6) - sqrt(2))/4`.
//!
//! Degrees never reach here: the parser reads `90deg` as `π/2`.

use super::expr::{Expr, Func, Kind};
use super::number::Rational;

/// Splits `e` into `(x, r)` with `e = x + r π` and no π term left in `x`.
fn split_pi(e: &Expr) -> (Expr, Rational) {
    match e.kind() {
        Kind::Pi => (Expr::zero(), Rational::one()),
        Kind::Mul(c, fs) if fs.len() == 1 && fs[0].1 == 1 && matches!(fs[0].0.kind(), Kind::Pi) => {
            (Expr::zero(), c.clone())
        }
        // Most arguments are angles without a multiple of π (`q1 + q2`): kept as they are.
        Kind::Add(_, ts) if !ts.iter().any(|(t, _)| matches!(t.kind(), Kind::Pi)) => {
            (e.clone(), Rational::zero())
        }
        Kind::Add(..) => {
            let mut r = Rational::zero();
            let mut rest = Vec::new();
            for (t, k) in e.terms() {
                if matches!(t.kind(), Kind::Pi) {
                    r = k;
                } else {
                    rest.push(t.scale(&k));
                }
            }
            (Expr::sum(rest), r)
        }
        _ => (e.clone(), Rational::zero()),
    }
}

fn sqrt_of(n: i64) -> Expr {
    Expr::sqrt(&Expr::int(n)).expect("positive")
}

/// `(sin rπ, cos rπ)` for `0 <= r < 1/2` a multiple of 1/12.
fn exact(r: &Rational) -> Option<(Expr, Expr)> {
    let twelfths = (r * &Rational::int(12)).to_i64()?;
    let q = |n, d| Expr::frac(n, d).expect("non-zero");
    let (s, c) = match twelfths {
        0 => (Expr::zero(), Expr::one()),
        1 => {
            let a = &sqrt_of(6) * &q(1, 4);
            let b = &sqrt_of(2) * &q(1, 4);
            (&a - &b, &a + &b)
        }
        2 => (q(1, 2), &sqrt_of(3) * &q(1, 2)),
        3 => (&sqrt_of(2) * &q(1, 2), &sqrt_of(2) * &q(1, 2)),
        4 => (&sqrt_of(3) * &q(1, 2), q(1, 2)),
        5 => {
            let a = &sqrt_of(6) * &q(1, 4);
            let b = &sqrt_of(2) * &q(1, 4);
            (&a + &b, &a - &b)
        }
        _ => return None,
    };
    Some((s, c))
}

/// Builds the canonical `f(arg)`.
pub(crate) fn canonical_fun(f: Func, arg: &Expr) -> Expr {
    if f == Func::Sgn {
        return Expr::sgn(arg);
    }
    let (mut x, mut r) = split_pi(arg);
    let mut sign = Rational::one();
    if x.reads_negative() {
        x = -&x;
        r = -r;
        if f == Func::Sin {
            sign = -sign;
        }
    }
    if r.is_zero() && !x.is_zero() {
        // No multiple of π to reduce (the common case): what the reduction below gives at once.
        return Expr::fun_unchecked(f, x).scale(&sign);
    }
    // r mod 2 into [0, 2)
    let two = Rational::int(2);
    let floor_div = {
        let q = &r * &Rational::new(1, 2).expect("non-zero");
        let n = q.numer();
        let d = q.denom();
        num_integer::Integer::div_floor(&n, &d)
    };
    r = &r - &(&two * &Rational::from(floor_div));
    let mut f = f;
    let one = Rational::one();
    if r >= one {
        // sin(y + π) = -sin(y), cos(y + π) = -cos(y)
        r = &r - &one;
        sign = -sign;
    }
    let half = Rational::new(1, 2).expect("non-zero");
    if r >= half {
        r = &r - &half;
        match f {
            // sin(y + π/2) = cos(y)
            Func::Sin => f = Func::Cos,
            // cos(y + π/2) = -sin(y)
            Func::Cos => {
                f = Func::Sin;
                sign = -sign;
            }
            // Returned above.
            Func::Sgn => {}
        }
    }
    let value = if x.is_zero() {
        match exact(&r) {
            Some((s, c)) => match f {
                Func::Sin => s,
                Func::Cos | Func::Sgn => c,
            },
            None => Expr::fun_unchecked(f, &Expr::pi() * &Expr::num(r)),
        }
    } else {
        let a = if r.is_zero() {
            x
        } else {
            &x + &(&Expr::pi() * &Expr::num(r))
        };
        Expr::fun_unchecked(f, a)
    };
    value.scale(&sign)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pi_times(n: i64, d: i64) -> Expr {
        &Expr::pi() * &Expr::frac(n, d).unwrap()
    }

    /// (function, argument as a multiple of π, expected value as `a + b sqrt(k)` pieces built by hand)
    #[test]
    fn exact_values_table() {
        let half = Expr::frac(1, 2).unwrap();
        let s2 = &sqrt_of(2) * &half;
        let s3 = &sqrt_of(3) * &half;
        let rows: Vec<(Func, (i64, i64), Expr)> = vec![
            (Func::Cos, (1, 2), Expr::zero()),
            (Func::Sin, (-1, 2), Expr::int(-1)),
            (Func::Cos, (1, 3), half.clone()),
            (Func::Sin, (1, 4), s2.clone()),
            (Func::Cos, (3, 4), -&s2),
            (Func::Sin, (2, 3), s3.clone()),
            (Func::Cos, (1, 1), Expr::int(-1)),
            (Func::Sin, (1, 1), Expr::zero()),
            (Func::Cos, (5, 3), half.clone()),
            (Func::Sin, (7, 6), -&half),
            (Func::Cos, (-1, 6), s3.clone()),
            (Func::Sin, (4, 1), Expr::zero()),
        ];
        for (f, (n, d), want) in rows {
            assert_eq!(
                Expr::fun(f, &pi_times(n, d)),
                want,
                "{}({n}/{d} pi)",
                f.name()
            );
        }
    }

    #[test]
    fn shifts_and_signs() {
        let x = Expr::symbol("x");
        let y = Expr::symbol("y");
        assert_eq!(Expr::sin(&(&x + &pi_times(1, 2))), Expr::cos(&x));
        assert_eq!(Expr::sin(&(&x + &Expr::pi())), -Expr::sin(&x));
        assert_eq!(Expr::cos(&(&x - &pi_times(1, 2))), Expr::sin(&x));
        assert_eq!(Expr::sin(&(&y - &x)), -Expr::sin(&(&x - &y)));
        assert_eq!(Expr::cos(&(&y - &x)), Expr::cos(&(&x - &y)));
        // A multiple of π with no exact value stays, reduced into [0, π/2).
        assert_eq!(Expr::sin(&pi_times(6, 5)), -Expr::sin(&pi_times(1, 5)));
    }
}
