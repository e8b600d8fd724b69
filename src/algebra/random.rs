//! A small deterministic random generator (splitmix64): random rational points for the randomized
//! identity test, random states and parameters for benchmarks and tests. Runs are repeatable from a
//! seed, and nothing depends on a crate.

use super::Rational;

/// The splitmix64 generator of Steele, Lea and Flood: 64 bits of state, every seed valid.
#[derive(Clone, Debug)]
pub struct Rng(u64);

impl Rng {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in `[0, 1)`.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A uniform number in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// A uniform integer in `[1, 2^bits]`, `1 ≤ bits ≤ 62`, without modulo bias.
    pub fn positive(&mut self, bits: u32) -> i64 {
        let bits = bits.clamp(1, 62);
        ((self.next_u64() >> (64 - bits)) + 1) as i64
    }

    /// A uniform integer in `[lo, hi]`.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        let span = (hi - lo) as u64 + 1;
        // Rejection keeps it uniform for any span.
        let limit = u64::MAX - u64::MAX % span;
        loop {
            let x = self.next_u64();
            if x < limit {
                return lo + (x % span) as i64;
            }
        }
    }

    /// `k / den` with `k` uniform in `[lo, hi]`.
    pub fn rational(&mut self, lo: i64, hi: i64, den: i64) -> Rational {
        Rational::new(self.int(lo, hi), den).expect("non-zero denominator")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_hold_and_seeds_repeat() {
        let mut a = Rng::new(7);
        let mut b = Rng::new(7);
        for _ in 0..1000 {
            assert_eq!(a.next_u64(), b.next_u64());
        }
        for _ in 0..1000 {
            let k = a.positive(3);
            assert!((1..=8).contains(&k), "{k}");
            let i = a.int(-2, 2);
            assert!((-2..=2).contains(&i), "{i}");
            let u = a.unit();
            assert!((0.0..1.0).contains(&u));
        }
        let mut seen = [false; 8];
        for _ in 0..200 {
            seen[(a.positive(3) - 1) as usize] = true;
        }
        assert!(seen.iter().all(|&s| s), "every value of [1, 8] occurs");
    }
}
