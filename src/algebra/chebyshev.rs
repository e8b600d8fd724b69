//! The Chebyshev polynomials, term by term: `cos(n y) = T_n(cos y)` and
//! `sin(n y) = sin y · U_{n−1}(cos y)`, which the normal form uses for multiple angles.
//!
//! `T_n(x) = Σ_k a_k x^(n−2k)` with `a_0 = 2^(n−1)` (`T_0 = 1`) and
//! `a_(k+1) = −a_k (n−2k)(n−2k−1) / (4 (k+1)(n−k−1))`; `U_m(x) = Σ_k b_k x^(m−2k)` with `b_0 = 2^m` and
//! `b_(k+1) = −b_k (m−2k)(m−2k−1) / (4 (k+1)(m−k))`. Each is `⌊n/2⌋ + 1` terms, computed one from
//! the last, at the cost of the answer.

use super::number::Rational;

/// The terms `(power, coefficient)` of `T_n`, highest power first.
pub fn t(n: u64) -> Vec<(u64, Rational)> {
    if n == 0 {
        return vec![(0, Rational::one())];
    }
    terms(n, two_to(n - 1), 1)
}

/// The terms `(power, coefficient)` of `U_m`, highest power first.
pub fn u(m: u64) -> Vec<(u64, Rational)> {
    terms(m, two_to(m), 0)
}

fn two_to(k: u64) -> Rational {
    Rational::int(2)
        .pow(i64::try_from(k).expect("a degree within i64"))
        .expect("non-zero")
}

/// `Σ_k a_k x^(degree−2k)` from `a_0 = first` by the ratio with `degree − k − shift` below.
fn terms(degree: u64, first: Rational, shift: u64) -> Vec<(u64, Rational)> {
    let mut out = Vec::with_capacity(degree as usize / 2 + 1);
    let mut a = first;
    for k in 0..=degree / 2 {
        out.push((degree - 2 * k, a.clone()));
        if k < degree / 2 {
            let j = degree - 2 * k;
            let num = -(i128::from(j) * i128::from(j - 1));
            let den = 4 * i128::from(k + 1) * i128::from(degree - k - shift);
            a = &a * &Rational::from_bigints(num.into(), den.into()).expect("non-zero");
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The coefficients, and T_n(cos y) = cos(n y), U_(n−1)(cos y) sin y = sin(n y) at a point.
    #[test]
    fn coefficients_and_values() {
        let r = |n| Rational::int(n);
        assert_eq!(t(0), [(0, r(1))]);
        assert_eq!(t(3), [(3, r(4)), (1, r(-3))]);
        assert_eq!(t(4), [(4, r(8)), (2, r(-8)), (0, r(1))]);
        assert_eq!(u(2), [(2, r(4)), (0, r(-1))]);
        assert_eq!(u(0), [(0, r(1))]);
        let y = 0.37f64;
        // The value and the sum of the terms' magnitudes, the scale of the rounding error.
        let eval = |terms: &[(u64, Rational)]| {
            terms.iter().fold((0.0, 0.0), |(v, s), (p, c)| {
                let x = c.to_f64() * y.cos().powi(*p as i32);
                (v + x, s + x.abs())
            })
        };
        for n in 1..40u64 {
            let (v, scale) = eval(&t(n));
            assert!((v - (n as f64 * y).cos()).abs() < 1e-14 * scale, "T_{n}");
            let (v, scale) = eval(&u(n - 1));
            assert!(
                (v * y.sin() - (n as f64 * y).sin()).abs() < 1e-14 * scale,
                "U_{n}"
            );
        }
    }
}
