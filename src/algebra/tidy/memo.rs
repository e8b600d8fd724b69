//! Bounded memos of the pure display rewrites, shared by every thread.
//!
//! A sheet tidies the same few sums many times: a link's `(q̇1 + q̇2)² a2 s12 − …` recurs in the
//! forces and moments of every link before it, and in both frames' equations. Each rule here is a
//! pure function of its input's structure, so a result from a [`Memo`] is the one the rule would
//! compute: the display is the same whether or not it came from here, on any number of threads.
//! A memo forgets everything when it holds [`Memo::LIMIT`] entries, so a long session (the REPL)
//! never grows it without bound.

use crate::algebra::fast_hash::FxHashMap;
use std::borrow::Cow;
use std::hash::Hash;
use std::sync::{LazyLock, Mutex, MutexGuard};

/// A memo of a pure function from `K` to `V`, for a `static`.
pub struct Memo<K, V>(LazyLock<Mutex<FxHashMap<K, V>>>);

impl<K: Hash + Eq + Clone, V: Clone> Memo<K, V> {
    /// The most entries a memo holds before it starts again.
    pub const LIMIT: usize = 4096;

    /// An empty memo.
    pub const fn new() -> Self {
        Memo(LazyLock::new(Mutex::default))
    }

    /// `f(key)`, remembered: computed (outside the lock, so threads never wait for each other's
    /// work) when the memo does not hold it.
    pub fn get_or(&self, key: &K, f: impl FnOnce(&K) -> V) -> V {
        self.get_or_cow(Cow::Borrowed(key), f)
    }

    /// [`Memo::get_or`] of a key the caller owns: kept as it is when remembered, not cloned.
    pub fn get_or_owned(&self, key: K, f: impl FnOnce(&K) -> V) -> V {
        self.get_or_cow(Cow::Owned(key), f)
    }

    /// [`Memo::get_or`] that remembers a computed value only if `keep` says so (a memo of texts
    /// keeps the short ones, so that it never holds megabytes).
    pub fn get_or_kept(
        &self,
        key: &K,
        f: impl FnOnce(&K) -> V,
        keep: impl FnOnce(&V) -> bool,
    ) -> V {
        self.get_or_cow_kept(Cow::Borrowed(key), f, keep)
    }

    /// [`Memo::get_or`] of a key borrowed (cloned when remembered) or owned (kept).
    fn get_or_cow(&self, key: Cow<'_, K>, f: impl FnOnce(&K) -> V) -> V {
        self.get_or_cow_kept(key, f, |_| true)
    }

    /// [`Memo::get_or_cow`], the value remembered only if `keep` says so.
    fn get_or_cow_kept(
        &self,
        key: Cow<'_, K>,
        f: impl FnOnce(&K) -> V,
        keep: impl FnOnce(&V) -> bool,
    ) -> V {
        if let Some(v) = self.lock().get(key.as_ref()) {
            return v.clone();
        }
        let v = f(key.as_ref());
        if keep(&v) {
            let mut map = self.lock();
            if map.len() >= Self::LIMIT {
                map.clear();
            }
            map.insert(key.into_owned(), v.clone());
        }
        v
    }

    /// Forgets every entry ([`super::forget_memos`]).
    pub fn clear(&self) {
        self.lock().clear();
    }

    fn lock(&self) -> MutexGuard<'_, FxHashMap<K, V>> {
        // A thread that panicked while holding the lock left the map whole (inserts are single
        // calls): its contents stay good. Taken by yielding rather than sleeping
        // (`parallel::lock`).
        crate::parallel::lock::lock(&self.0)
    }
}

impl<K: Hash + Eq + Clone, V: Clone> Default for Memo<K, V> {
    fn default() -> Self {
        Self::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn a_memo_computes_each_key_once_and_forgets_when_full() {
        static MEMO: Memo<usize, usize> = Memo::new();
        let calls = AtomicUsize::new(0);
        let square = |k: &usize| {
            calls.fetch_add(1, Ordering::Relaxed);
            k * k
        };
        assert_eq!(MEMO.get_or(&7, square), 49);
        assert_eq!(MEMO.get_or(&7, square), 49);
        assert_eq!(calls.load(Ordering::Relaxed), 1);
        for k in 0..Memo::<usize, usize>::LIMIT {
            MEMO.get_or(&(k + 100), square);
        }
        // Full at the limit: the next new key cleared it, so 7 is computed again.
        assert!(MEMO.lock().len() <= Memo::<usize, usize>::LIMIT);
        let before = calls.load(Ordering::Relaxed);
        assert_eq!(MEMO.get_or(&7, square), 49);
        assert_eq!(calls.load(Ordering::Relaxed), before + 1);
    }

    #[test]
    fn a_memo_keeps_only_the_values_it_is_told_to() {
        static MEMO: Memo<usize, String> = Memo::new();
        let calls = AtomicUsize::new(0);
        let text = |k: &usize| {
            calls.fetch_add(1, Ordering::Relaxed);
            "x".repeat(*k)
        };
        let short = |s: &String| s.len() <= 3;
        for _ in 0..2 {
            assert_eq!(MEMO.get_or_kept(&2, text, short), "xx");
            assert_eq!(MEMO.get_or_kept(&5, text, short), "xxxxx");
        }
        // The short text was computed once, the long one each time.
        assert_eq!(calls.load(Ordering::Relaxed), 3);
        assert!(MEMO.lock().contains_key(&2) && !MEMO.lock().contains_key(&5));
    }

    #[test]
    fn a_cleared_memo_computes_again() {
        static MEMO: Memo<usize, usize> = Memo::new();
        let calls = AtomicUsize::new(0);
        let double = |k: &usize| {
            calls.fetch_add(1, Ordering::Relaxed);
            2 * k
        };
        assert_eq!(MEMO.get_or(&3, double), 6);
        MEMO.clear();
        assert_eq!(MEMO.get_or(&3, double), 6);
        assert_eq!(calls.load(Ordering::Relaxed), 2);
    }
}
