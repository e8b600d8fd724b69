//! The number field of constant angles: `c = cos(π/L)` modulo its minimal polynomial `Ψ_L`.
//!
//! The normal form writes every constant angle `r π` of an expression over one base angle `π/L` (`L`
//! the lcm of the denominators, see `normal`): `cos(k π/L)` is `T_k(c)` and, for odd `L`,
//! `sin(k π/L) = s U_(k−1)(c)` with `s = sin(π/L)`. Reduced modulo `Ψ_L`, the minimal polynomial of
//! `c` over the rationals, of degree `N = φ(2L)/2`, these are canonical: `1, c, …, c^(N−1)` is a basis
//! of `Q(c)`, and for odd `L`, `s` lies outside `Q(c)` with `s² = 1 − c²` (for even `L`, `s` is
//! `cos((L/2 − 1) π/L)` and not needed). So two constants are equal exactly when their reduced forms
//! are: `cos(π/5) − cos(2π/5)` is `1/2`, `cos(π/7) − cos(2π/7) + cos(3π/7)` is `1/2`.
//!
//! `Ψ_L` comes from the cyclotomic polynomial: `Φ_(2L)(z) = z^N (a_N + Σ_k a_(N+k) (z^k + z^(−k)))`
//! (it is palindromic), and `z^k + z^(−k) = 2 T_k(cos θ)` on the unit circle, so
//! `Ψ_L(x) ∝ a_N + Σ_k 2 a_(N+k) T_k(x)`. `Φ_n` itself is `Π_(d | n) (z^d − 1)^μ(n/d)`.
//!
//! Every table is cached per `L`; bases above [`MAX_PI_BASE`] are not used (the normal form then
//! keeps each such angle's `sin`/`cos` as an atom pair of its own, exact but not related to others).

use super::chebyshev;
use super::number::Rational;
use num_bigint::BigInt;
use num_traits::{One, Zero};
use std::collections::HashMap;
use std::sync::{Arc, LazyLock, RwLock};

/// The largest base `L` of the angle `π/L` (`π/360` is half a degree); its field has degree at most
/// `φ(720)/2 = 96`.
pub const MAX_PI_BASE: u64 = 360;

/// Cached tables: minimal polynomials by `L`, reduced powers by `(L, e)`.
#[derive(Default)]
struct Tables {
    min: HashMap<u64, Arc<Vec<Rational>>>,
    powers: HashMap<(u64, i64), Arc<Vec<Rational>>>,
}

static TABLES: LazyLock<RwLock<Tables>> = LazyLock::new(|| RwLock::new(Tables::default()));

/// `Ψ_L`, monic, as its coefficients from the constant term (`N + 1` of them).
pub fn min_poly(l: u64) -> Arc<Vec<Rational>> {
    if let Some(p) = crate::parallel::lock::read(&TABLES).min.get(&l) {
        return Arc::clone(p);
    }
    let p = Arc::new(compute_min_poly(l));
    crate::parallel::lock::write(&TABLES)
        .min
        .insert(l, Arc::clone(&p));
    p
}

/// The degree `N` of `Ψ_L`: reduced forms hold `c^0 … c^(N−1)`.
pub fn degree(l: u64) -> usize {
    min_poly(l).len() - 1
}

/// The bits a power of `c` (or `s`) gains per unit of its exponent when reduced: the largest
/// coefficient of `Ψ_L` in bits, at least 1.
pub fn bits_per_power(l: u64) -> u64 {
    min_poly(l)
        .iter()
        .map(super::limits::bits)
        .max()
        .unwrap_or(1)
        .max(1)
}

/// `f` modulo `Ψ_L`: `N` coefficients.
pub fn reduce(l: u64, mut f: Vec<Rational>) -> Vec<Rational> {
    let psi = min_poly(l);
    let n = psi.len() - 1;
    for i in (n..f.len()).rev() {
        let lead = std::mem::take(&mut f[i]);
        if lead.is_zero() {
            continue;
        }
        for (j, p) in psi[..n].iter().enumerate() {
            let k = i - n + j;
            f[k] = &f[k] - &(&lead * p);
        }
    }
    f.resize(n, Rational::zero());
    f
}

/// `a · b` modulo `Ψ_L`.
pub fn mul(l: u64, a: &[Rational], b: &[Rational]) -> Vec<Rational> {
    let mut out = vec![Rational::zero(); (a.len() + b.len()).saturating_sub(1).max(1)];
    for (i, x) in a.iter().enumerate() {
        if x.is_zero() {
            continue;
        }
        for (j, y) in b.iter().enumerate() {
            out[i + j] = &out[i + j] + &(x * y);
        }
    }
    reduce(l, out)
}

/// `c^e` modulo `Ψ_L`, for any integer `e` (`c` is not zero, so `c^(−1)` exists).
pub fn power(l: u64, e: i64) -> Arc<Vec<Rational>> {
    if let Some(p) = crate::parallel::lock::read(&TABLES).powers.get(&(l, e)) {
        return Arc::clone(p);
    }
    let n = degree(l);
    let unit = |k: usize| {
        let mut v = vec![Rational::zero(); n];
        v[k] = Rational::one();
        v
    };
    let base = if e >= 0 {
        unit(1.min(n - 1))
    } else {
        inverse(l, &unit(1)).expect("cos(π/L) is not zero")
    };
    let mut acc = unit(0);
    let mut square = base;
    let mut k = e.unsigned_abs();
    while k > 0 {
        if k & 1 == 1 {
            acc = mul(l, &acc, &square);
        }
        k >>= 1;
        if k > 0 {
            square = mul(l, &square, &square);
        }
    }
    let p = Arc::new(acc);
    crate::parallel::lock::write(&TABLES)
        .powers
        .insert((l, e), Arc::clone(&p));
    p
}

/// `a^k` in `Q(c)`, by repeated squaring.
pub fn power_of(l: u64, a: &[Rational], k: u64) -> Vec<Rational> {
    let mut acc = vec![Rational::one()];
    let mut square = a.to_vec();
    let mut k = k;
    while k > 0 {
        if k & 1 == 1 {
            acc = mul(l, &acc, &square);
        }
        k >>= 1;
        if k > 0 {
            square = mul(l, &square, &square);
        }
    }
    reduce(l, acc)
}

/// The inverse of `a` in `Q(c)` (extended Euclid modulo `Ψ_L`); `None` for zero.
pub fn inverse(l: u64, a: &[Rational]) -> Option<Vec<Rational>> {
    let psi = min_poly(l);
    // Invariants: r0 = s0 a (mod Ψ), r1 = s1 a (mod Ψ).
    let (mut r0, mut r1) = (trim(psi.to_vec()), trim(a.to_vec()));
    let (mut s0, mut s1) = (Vec::new(), vec![Rational::one()]);
    if r1.is_empty() {
        return None;
    }
    while !r1.is_empty() {
        let (q, r) = divide(&r0, &r1);
        let s = sub(&s0, &product(&q, &s1));
        r0 = std::mem::replace(&mut r1, r);
        s0 = std::mem::replace(&mut s1, s);
    }
    // r0 is a non-zero constant (Ψ is irreducible and a is not a multiple of it).
    if r0.len() != 1 {
        return None;
    }
    let inv = r0[0].recip()?;
    Some(reduce(l, s0.iter().map(|x| x * &inv).collect()))
}

fn trim(mut f: Vec<Rational>) -> Vec<Rational> {
    while f.last().is_some_and(Rational::is_zero) {
        f.pop();
    }
    f
}

fn sub(a: &[Rational], b: &[Rational]) -> Vec<Rational> {
    let n = a.len().max(b.len());
    let at = |v: &[Rational], i: usize| v.get(i).cloned().unwrap_or_default();
    trim((0..n).map(|i| &at(a, i) - &at(b, i)).collect())
}

fn product(a: &[Rational], b: &[Rational]) -> Vec<Rational> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![Rational::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] = &out[i + j] + &(x * y);
        }
    }
    trim(out)
}

/// Quotient and remainder of `a / b`, `b` non-zero and trimmed.
fn divide(a: &[Rational], b: &[Rational]) -> (Vec<Rational>, Vec<Rational>) {
    let mut r = trim(a.to_vec());
    let lead = b
        .last()
        .expect("a non-zero divisor")
        .recip()
        .expect("non-zero");
    let mut q = vec![Rational::zero(); r.len().saturating_sub(b.len()) + 1];
    while r.len() >= b.len() && !r.is_empty() {
        let shift = r.len() - b.len();
        let k = r.last().expect("non-empty") * &lead;
        for (j, y) in b.iter().enumerate() {
            r[shift + j] = &r[shift + j] - &(&k * y);
        }
        q[shift] = k;
        r = trim(r);
    }
    (trim(q), r)
}

/// `Ψ_L` from the cyclotomic polynomial `Φ_(2L)` (see the module documentation).
fn compute_min_poly(l: u64) -> Vec<Rational> {
    let phi = cyclotomic(2 * l);
    let n = (phi.len() - 1) / 2;
    let mut psi = vec![Rational::zero(); n + 1];
    psi[0] = Rational::from(phi[n].clone());
    for k in 1..=n {
        let a = Rational::from(&phi[n + k] * BigInt::from(2));
        for (p, c) in chebyshev::t(k as u64) {
            psi[p as usize] = &psi[p as usize] + &(&a * &c);
        }
    }
    let lead = psi[n].recip().expect("leading coefficient 2^N");
    psi.iter().map(|x| x * &lead).collect()
}

/// The cyclotomic polynomial `Φ_n`, integer coefficients from the constant term.
fn cyclotomic(n: u64) -> Vec<BigInt> {
    let mut num = vec![BigInt::one()];
    let mut den = vec![BigInt::one()];
    for d in (1..=n).filter(|d| n.is_multiple_of(*d)) {
        let mut factor = vec![BigInt::zero(); d as usize + 1];
        factor[0] = BigInt::from(-1);
        factor[d as usize] = BigInt::one();
        match mobius(n / d) {
            1 => num = int_product(&num, &factor),
            -1 => den = int_product(&den, &factor),
            _ => {}
        }
    }
    // num / den, exactly; den is monic.
    let mut r = num;
    let mut q = vec![BigInt::zero(); r.len() - den.len() + 1];
    for shift in (0..q.len()).rev() {
        let k = r[shift + den.len() - 1].clone();
        for (j, y) in den.iter().enumerate() {
            r[shift + j] -= &k * y;
        }
        q[shift] = k;
    }
    debug_assert!(r.iter().all(Zero::is_zero));
    q
}

fn int_product(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut out = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// The Möbius function.
fn mobius(mut n: u64) -> i32 {
    let mut sign = 1;
    let mut p = 2;
    while p * p <= n {
        if n.is_multiple_of(p) {
            n /= p;
            if n.is_multiple_of(p) {
                return 0;
            }
            sign = -sign;
        }
        p += 1;
    }
    if n > 1 {
        sign = -sign;
    }
    sign
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(f: &[Rational], x: f64) -> f64 {
        f.iter()
            .enumerate()
            .map(|(i, c)| c.to_f64() * x.powi(i as i32))
            .sum()
    }

    /// The sum of the terms' magnitudes: the scale of the rounding error of [`value`].
    fn scale(f: &[Rational], x: f64) -> f64 {
        f.iter()
            .enumerate()
            .map(|(i, c)| (c.to_f64() * x.powi(i as i32)).abs())
            .sum()
    }

    /// `Ψ_L(cos(π/L)) = 0`, of degree `φ(2L)/2`, for every base up to the limit.
    #[test]
    fn minimal_polynomials_vanish_at_their_cosine() {
        let r = |n, d| Rational::new(n, d).unwrap();
        assert_eq!(*min_poly(5), [r(-1, 4), r(-1, 2), r(1, 1)]); // 4x² − 2x − 1
        assert_eq!(
            *min_poly(10),
            [r(5, 16), r(0, 1), r(-5, 4), r(0, 1), r(1, 1)]
        );
        let totient = |n: u64| {
            (1..=n)
                .filter(|k| num_integer::Integer::gcd(k, &n) == 1)
                .count()
        };
        for l in (3..=MAX_PI_BASE)
            .step_by(7)
            .chain([5, 7, 8, 9, 10, 12, 180, 360])
        {
            let psi = min_poly(l);
            assert_eq!(psi.len() - 1, totient(2 * l) / 2, "L = {l}");
            let c = (std::f64::consts::PI / l as f64).cos();
            let (v, s) = (value(&psi, c), scale(&psi, c));
            assert!(v.abs() < 1e-13 * s, "L = {l}: {v} of {s}");
        }
    }

    /// Powers, negative ones too, and inverses agree with the numbers.
    #[test]
    fn arithmetic_in_the_field() {
        for l in [5u64, 7, 9, 14, 24] {
            let c = (std::f64::consts::PI / l as f64).cos();
            for e in [-3i64, -1, 0, 1, 2, 5, 17] {
                let p = power(l, e);
                let err = (value(&p, c) - c.powi(e as i32)).abs();
                assert!(err < 1e-12 * scale(&p, c), "L = {l}, e = {e}");
            }
            let a = vec![Rational::int(1), Rational::int(2)]; // 1 + 2c
            let inv = inverse(l, &a).unwrap();
            assert!(
                (value(&inv, c) * (1.0 + 2.0 * c) - 1.0).abs() < 1e-9,
                "L = {l}"
            );
        }
        assert_eq!(inverse(7, &[]), None);
    }
}
