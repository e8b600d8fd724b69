//! A fast, deterministic hasher for the hash maps of the polynomial hot loops.
//!
//! The keys there are short runs of small integers (monomials, atom ids), for which SipHash's
//! protection against adversarial collisions costs more than the rest of a multiplication. This is
//! the multiply-rotate hash of Firefox and rustc (`FxHasher`). It is deterministic, but nothing may
//! depend on hash order anyway: every result is sorted before it leaves the algebra core.

use std::hash::{BuildHasherDefault, Hasher};

/// The `FxHasher`: one rotate, xor and multiply per word.
#[derive(Clone, Copy, Default)]
pub struct FxHasher {
    hash: u64,
}

const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl FxHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.hash = (self.hash.rotate_left(5) ^ word).wrapping_mul(SEED);
    }
}

impl Hasher for FxHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            self.add(u64::from_le_bytes(c.try_into().expect("eight bytes")));
        }
        for &b in chunks.remainder() {
            self.add(b as u64);
        }
    }
    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(i as u64);
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.add(i as u64);
    }
    #[inline]
    fn write_i32(&mut self, i: i32) {
        self.add(i as u32 as u64);
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.add(i);
    }
    #[inline]
    fn write_i64(&mut self, i: i64) {
        self.add(i as u64);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }
    #[inline]
    fn finish(&self) -> u64 {
        self.hash
    }
}

/// A `HashMap` keyed with [`FxHasher`].
pub type FxHashMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// A `HashSet` keyed with [`FxHasher`].
pub type FxHashSet<K> = std::collections::HashSet<K, BuildHasherDefault<FxHasher>>;

#[cfg(test)]
mod tests {
    use super::*;
    use std::hash::Hash;

    fn hash_of<T: Hash>(t: &T) -> u64 {
        let mut h = FxHasher::default();
        t.hash(&mut h);
        h.finish()
    }

    #[test]
    fn equal_keys_hash_alike_and_different_keys_differ() {
        let a: Vec<(u32, i32)> = vec![(1, 2), (3, 1)];
        assert_eq!(hash_of(&a), hash_of(&a.clone()));
        assert_eq!(hash_of(&a), hash_of(&a.as_slice()));
        assert_ne!(hash_of(&a), hash_of(&vec![(1u32, 2i32), (3, 2)]));
        assert_ne!(hash_of(&a), hash_of(&vec![(3u32, 1i32), (1, 2)]));
    }
}
