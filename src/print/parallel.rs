//! Deterministic work sharing for the display layer: [`map`] applies a pure function to many items
//! on a few threads and returns the results in the items' order, so the text printed from them is the
//! same on any number of threads.
//!
//! What may run here: printing polynomials ([`super::poly`]) and tidying into the house style
//! ([`crate::algebra::tidy`]). Tidying may intern new atoms, from several threads at once; atom ids
//! then differ from run to run, but they are only an internal order (see
//! [`crate::algebra::atom`]): tidying works on canonical expressions, ordered structurally, and visits
//! its candidates in that order (never by id or hash), so each result is the same expression
//! whichever thread computes it and whenever.

use std::sync::atomic::{AtomicUsize, Ordering};

/// The most threads a display job uses by default.
const MAX_THREADS: usize = 4;

/// The number of threads set by [`set_threads`] (0: decide from the machine).
static THREADS: AtomicUsize = AtomicUsize::new(0);

/// Sets how many threads [`map`] may use (at least 1; 0 restores the default, the machine's cores
/// up to [`MAX_THREADS`]). The text printed is the same for every setting.
pub fn set_threads(n: usize) {
    THREADS.store(n, Ordering::Relaxed);
}

/// The number of threads [`map`] uses.
pub fn threads() -> usize {
    match THREADS.load(Ordering::Relaxed) {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get().min(MAX_THREADS)),
        n => n,
    }
}

/// `f` of every item, in the items' order, computed on up to [`threads`] threads when `weight`
/// (an estimate of each item's cost) sums to at least `min_total`; on the calling thread otherwise.
/// Threads take items heaviest first, one at a time, so a few large items do not leave a thread idle.
pub fn map<T: Sync, R: Send>(
    items: &[T],
    weight: impl Fn(&T) -> usize,
    min_total: usize,
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let threads = threads();
    let weights: Vec<usize> = items.iter().map(&weight).collect();
    let total: usize = weights.iter().sum();
    if threads < 2 || items.len() < 2 || total < min_total {
        return items.iter().map(f).collect();
    }
    // Heaviest first; equal weights in item order (a stable sort), so the schedule is reproducible.
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| weights[b].cmp(&weights[a]));
    let next = AtomicUsize::new(0);
    let (order, next, f) = (&order, &next, &f);
    let mut done: Vec<(usize, R)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads.min(items.len()))
            .map(|_| {
                scope.spawn(move || {
                    let mut mine = Vec::new();
                    loop {
                        let k = next.fetch_add(1, Ordering::Relaxed);
                        let Some(&i) = order.get(k) else { break };
                        mine.push((i, f(&items[i])));
                    }
                    mine
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("a display thread does not panic"))
            .collect()
    });
    done.sort_by_key(|&(i, _)| i);
    done.into_iter().map(|(_, r)| r).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_back_in_the_items_order() {
        let items: Vec<u64> = (0..200).collect();
        // Uneven costs, so threads finish out of order.
        let work =
            |&n: &u64| (0..(n % 7) * 1000).fold(n, |a, b| a.wrapping_mul(31).wrapping_add(b));
        let want: Vec<u64> = items.iter().map(work).collect();
        assert_eq!(map(&items, |&n| n as usize, 0, work), want);
        // Below the threshold: on this thread, the same.
        assert_eq!(map(&items, |_| 1, usize::MAX, work), want);
        assert!(map(&[] as &[u64], |_| 1, 0, work).is_empty());
    }
}
