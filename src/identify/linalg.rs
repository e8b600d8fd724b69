//! Exact linear algebra: the reduced row echelon form, which gives the rank, the pivot columns and
//! every other column as a combination of the pivot columns before it; over ℚ for small systems, and
//! modulo the prime `p = 2^61 − 1` for the large ones (rationals in lowest terms swell during
//! elimination; residues do not), with the rationals recovered by rational reconstruction.
//!
//! The rank modulo `p` is at most the rank over ℚ, so pivots found modulo `p` are independent over ℚ
//! too; what the reconstruction gives is a claim that [`super::base`] proves symbolically.

use crate::algebra::compact::eval::Ring;
use crate::algebra::Rational;
use num_bigint::BigInt;
use num_traits::ToPrimitive;

/// The prime modulus `2^61 − 1`.
pub const P: u64 = (1 << 61) - 1;

/// `a b mod p` for residues `a, b < p`: `p = 2^61 − 1` is a Mersenne prime, so `2^61 ≡ 1` and the
/// 122-bit product folds into 61 bits with shifts and adds (no 128-bit division).
fn mul_mod(a: u64, b: u64) -> u64 {
    let x = a as u128 * b as u128;
    let r = (x as u64 & P) + (x >> 61) as u64; // < 2^62
    let r = (r & P) + (r >> 61); // ≤ p
    if r >= P {
        r - P
    } else {
        r
    }
}

/// `1/2 mod p`: `2 · 2^60 = 2^61 ≡ 1`.
const HALF: u64 = 1 << 60;

/// `a + b mod p` for residues `a, b < p`.
fn add_mod(a: u64, b: u64) -> u64 {
    let r = a + b;
    if r >= P {
        r - P
    } else {
        r
    }
}

fn pow_mod(mut a: u64, mut e: u64) -> u64 {
    let mut r = 1;
    while e > 0 {
        if e & 1 == 1 {
            r = mul_mod(r, a);
        }
        a = mul_mod(a, a);
        e >>= 1;
    }
    r
}

fn inv_mod(a: u64) -> u64 {
    pow_mod(a, P - 2)
}

fn big_mod(b: &BigInt) -> u64 {
    let m = BigInt::from(P);
    let r = ((b % &m) + &m) % &m;
    r.to_u64().expect("reduced")
}

/// An integer modulo `p`.
pub fn int_mod(x: i64) -> u64 {
    x.rem_euclid(P as i64) as u64
}

/// A residue modulo `p`, as a [`Ring`] for evaluating compact quantities without big numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fp(pub u64);

impl Ring for Fp {
    fn from_rational(r: &Rational) -> Self {
        match r.as_small() {
            Some((n, 1)) => Fp(int_mod(n)),
            Some((n, 2)) => Fp(mul_mod(int_mod(n), HALF)),
            Some((n, d)) => Fp(mul_mod(int_mod(n), inv_mod(int_mod(d)))),
            None => Fp(to_mod(r).unwrap_or(0)),
        }
    }
    fn add(&self, o: &Self) -> Self {
        Fp(add_mod(self.0, o.0))
    }
    fn mul(&self, o: &Self) -> Self {
        Fp(mul_mod(self.0, o.0))
    }
    fn powi(&self, e: i32) -> Option<Self> {
        if e >= 0 {
            Some(Fp(pow_mod(self.0, e as u64)))
        } else if self.0 == 0 {
            None
        } else {
            Some(Fp(pow_mod(inv_mod(self.0), e.unsigned_abs() as u64)))
        }
    }
}

impl Fp {
    /// `self / o` (`o` non-zero).
    pub fn over(self, o: Fp) -> Fp {
        Fp(mul_mod(self.0, inv_mod(o.0)))
    }
}

/// A rational modulo `p`; `None` when its denominator is a multiple of `p`.
pub fn to_mod(r: &Rational) -> Option<u64> {
    let d = big_mod(&r.denom());
    (d != 0).then(|| mul_mod(big_mod(&r.numer()), inv_mod(d)))
}

/// The rational `a/b` with `|a|, b < sqrt(p/2)` that is `x` modulo `p` (Wang's rational
/// reconstruction), if there is one.
pub fn reconstruct(x: u64) -> Option<Rational> {
    let bound = ((P / 2) as f64).sqrt() as i128;
    let (mut r0, mut r1) = (P as i128, x as i128);
    let (mut t0, mut t1) = (0i128, 1i128);
    while r1 >= bound {
        let q = r0 / r1;
        (r0, r1) = (r1, r0 - q * r1);
        (t0, t1) = (t1, t0 - q * t1);
    }
    if t1 == 0 || t1.abs() >= bound {
        return None;
    }
    let (num, den) = if t1 < 0 { (-r1, -t1) } else { (r1, t1) };
    let r = Rational::from_bigints(BigInt::from(num), BigInt::from(den))?;
    (to_mod(&r) == Some(x)).then_some(r)
}

/// A reduced row echelon form modulo `p`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EchelonMod {
    /// The pivot columns, in increasing order.
    pub pivots: Vec<usize>,
    /// The first `rank` rows of the reduced matrix.
    pub rows: Vec<Vec<u64>>,
}

impl EchelonMod {
    /// The reduced row echelon form of `m` modulo `p` (Gauss–Jordan).
    pub fn of(mut m: Vec<Vec<u64>>) -> EchelonMod {
        let cols = m.first().map_or(0, Vec::len);
        let mut pivots = Vec::new();
        let mut rank = 0;
        for c in 0..cols {
            if rank == m.len() {
                break;
            }
            let Some(p) = (rank..m.len()).find(|&r| m[r][c] != 0) else {
                continue;
            };
            m.swap(rank, p);
            let inv = inv_mod(m[rank][c]);
            let pivot_row: Vec<u64> = m[rank].iter().map(|&x| mul_mod(x, inv)).collect();
            for (r, row) in m.iter_mut().enumerate() {
                if r == rank || row[c] == 0 {
                    continue;
                }
                let f = row[c];
                for (x, &p) in row.iter_mut().zip(&pivot_row).skip(c) {
                    if p != 0 {
                        let t = mul_mod(f, p);
                        *x = if *x >= t { *x - t } else { *x + P - t };
                    }
                }
            }
            m[rank] = pivot_row;
            pivots.push(c);
            rank += 1;
        }
        m.truncate(rank);
        EchelonMod { pivots, rows: m }
    }

    /// The rank modulo `p`.
    pub fn rank(&self) -> usize {
        self.pivots.len()
    }
}

/// A reduced row echelon form.
#[derive(Clone, Debug, PartialEq)]
pub struct Echelon {
    /// The pivot columns, in increasing order (the rank is their number).
    pub pivots: Vec<usize>,
    /// The first `rank` rows of the reduced matrix: row `r` has 1 in column `pivots[r]`, 0 in the
    /// other pivot columns.
    pub rows: Vec<Vec<Rational>>,
}

impl Echelon {
    /// The reduced row echelon form of `m` (rows of equal length), by Gauss–Jordan elimination with
    /// exact rationals. Column `c` that is no pivot equals `Σ_r rows[r][c] · column(pivots[r])`.
    pub fn of(mut m: Vec<Vec<Rational>>) -> Echelon {
        let cols = m.first().map_or(0, Vec::len);
        let mut pivots = Vec::new();
        let mut rank = 0;
        for c in 0..cols {
            if rank == m.len() {
                break;
            }
            // The pivot: the non-zero entry of the smallest size, to keep numbers short.
            let Some(p) = (rank..m.len())
                .filter(|&r| !m[r][c].is_zero())
                .min_by_key(|&r| size(&m[r][c]))
            else {
                continue;
            };
            m.swap(rank, p);
            let inv = m[rank][c].recip().expect("non-zero pivot");
            let pivot_row: Vec<Rational> = m[rank].iter().map(|x| x * &inv).collect();
            for (r, row) in m.iter_mut().enumerate() {
                if r == rank || row[c].is_zero() {
                    continue;
                }
                let f = row[c].clone();
                for (x, p) in row.iter_mut().zip(&pivot_row).skip(c) {
                    if !p.is_zero() {
                        *x = &*x - &(&f * p);
                    }
                }
            }
            m[rank] = pivot_row;
            pivots.push(c);
            rank += 1;
        }
        m.truncate(rank);
        Echelon { pivots, rows: m }
    }

    /// The rank.
    pub fn rank(&self) -> usize {
        self.pivots.len()
    }
}

/// A rough size of a rational: the bits of its numerator and denominator.
fn size(r: &Rational) -> u64 {
    r.numer().bits() + r.denom().bits()
}

/// [`solve`], first modulo `p` with every unknown recovered by rational reconstruction, which is
/// fast for many right sides whose solutions are small rationals (the grouping coefficients); the
/// recovered solution is accepted only if it satisfies every equation exactly over ℚ, else the
/// system is solved over ℚ.
pub fn solve_fast(a: &[Vec<Rational>], bs: &[Vec<Rational>]) -> Option<Vec<Vec<Rational>>> {
    if let Some(x) = solve_mod(a, bs) {
        let exact = bs.iter().zip(&x).all(|(b, x)| {
            a.iter().zip(b).all(|(row, rhs)| {
                let lhs = row
                    .iter()
                    .zip(x)
                    .filter(|(c, v)| !c.is_zero() && !v.is_zero())
                    .fold(Rational::zero(), |acc, (c, v)| &acc + &(c * v));
                &lhs == rhs
            })
        });
        if exact {
            return Some(x);
        }
    }
    solve(a, bs)
}

/// `A x = b` modulo `p`, each unknown reconstructed as a rational; `None` when `A` has not full
/// column rank modulo `p`, a system is inconsistent or an unknown has no small rational.
fn solve_mod(a: &[Vec<Rational>], bs: &[Vec<Rational>]) -> Option<Vec<Vec<Rational>>> {
    let unknowns = a.first().map_or(0, Vec::len);
    let m: Vec<Vec<u64>> = a
        .iter()
        .enumerate()
        .map(|(r, row)| {
            row.iter()
                .chain(bs.iter().map(|b| &b[r]))
                .map(to_mod)
                .collect::<Option<Vec<u64>>>()
        })
        .collect::<Option<_>>()?;
    let e = EchelonMod::of(m);
    if e.pivots.len() != unknowns || e.pivots.iter().enumerate().any(|(i, &p)| i != p) {
        return None;
    }
    (0..bs.len())
        .map(|k| {
            (0..unknowns)
                .map(|r| reconstruct(e.rows[r][unknowns + k]))
                .collect()
        })
        .collect()
}

/// Solves the square or overdetermined system `A x = b` for each right side in `bs` (columns of
/// `b`), exactly; `None` when `A` has not full column rank or a system is inconsistent.
pub fn solve(a: &[Vec<Rational>], bs: &[Vec<Rational>]) -> Option<Vec<Vec<Rational>>> {
    let unknowns = a.first().map_or(0, Vec::len);
    let m: Vec<Vec<Rational>> = a
        .iter()
        .enumerate()
        .map(|(r, row)| {
            let mut row = row.clone();
            row.extend(bs.iter().map(|b| b[r].clone()));
            row
        })
        .collect();
    let e = Echelon::of(m);
    if e.pivots.len() != unknowns || e.pivots.iter().enumerate().any(|(i, &p)| i != p) {
        return None;
    }
    // The right sides' columns must hold no pivot (else inconsistent): checked above by the count.
    Some(
        (0..bs.len())
            .map(|k| {
                (0..unknowns)
                    .map(|r| e.rows[r][unknowns + k].clone())
                    .collect()
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(v: &[i64]) -> Vec<Rational> {
        v.iter().map(|&x| Rational::int(x)).collect()
    }

    #[test]
    fn dependent_columns_are_combinations_of_earlier_pivots() {
        // Column 2 = column 0 + 2 column 1; column 3 is zero.
        let e = Echelon::of(vec![r(&[1, 0, 1, 0]), r(&[1, 1, 3, 0]), r(&[2, 1, 4, 0])]);
        assert_eq!(e.pivots, vec![0, 1]);
        assert_eq!(e.rows[0][2], Rational::int(1));
        assert_eq!(e.rows[1][2], Rational::int(2));
    }

    #[test]
    fn the_mersenne_fold_is_the_remainder() {
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        let mut samples = vec![0, 1, 2, P - 1, P - 2, 1 << 60, (1 << 61) - 2, 12345];
        for _ in 0..2000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            samples.push(x % P);
        }
        for &a in &samples {
            for &b in samples.iter().take(40) {
                let want = ((a as u128 * b as u128) % P as u128) as u64;
                assert_eq!(mul_mod(a, b), want, "{a} * {b}");
                assert_eq!(add_mod(a, b), (a + b) % P, "{a} + {b}");
                assert_eq!(mul_mod(HALF, 2), 1);
            }
        }
    }

    #[test]
    fn rationals_survive_the_modular_round_trip() {
        for (n, d) in [(0, 1), (3, 7), (-2159, 5000), (46_621_281, 25_000_000)] {
            let r = Rational::new(n, d).unwrap();
            assert_eq!(reconstruct(to_mod(&r).unwrap()), Some(r));
        }
    }

    #[test]
    fn overdetermined_systems_are_solved_or_refused() {
        let a = vec![r(&[1, 0]), r(&[0, 1]), r(&[1, 1])];
        assert_eq!(solve(&a, &[r(&[2, 3, 5])]), Some(vec![r(&[2, 3])]));
        assert_eq!(solve(&a, &[r(&[2, 3, 6])]), None);
        assert_eq!(solve_fast(&a, &[r(&[2, 3, 5])]), Some(vec![r(&[2, 3])]));
        assert_eq!(solve_fast(&a, &[r(&[2, 3, 6])]), None);
    }

    #[test]
    fn a_solution_too_large_to_reconstruct_is_found_exactly() {
        // x = 2^70 + 1/3 has no rational reconstruction modulo p (|numerator| ≥ sqrt(p/2)): the fast
        // solver must still give it, from the exact elimination.
        let big = Rational::from_bigints((BigInt::from(1) << 70) * 3 + 1, BigInt::from(3)).unwrap();
        let a = vec![r(&[1, 0]), r(&[0, 2]), r(&[1, 1])];
        let b = vec![big.clone(), Rational::int(4), &big + &Rational::int(2)];
        assert_eq!(
            solve_fast(&a, &[b]),
            Some(vec![vec![big, Rational::int(2)]])
        );
    }
}
