//! Deterministic work sharing: [`map`] applies a pure function to many items on a few threads and
//! returns the results in the items' order, so whatever is built or printed from them is the same on
//! any number of threads; [`share`] runs a worker loop on a few threads, for work whose results
//! are taken one by one as they are ready (the sheet's vectors); [`join`] runs two closures side
//! by side. The derivation ([`crate::dynamics::lagrange`]: the Christoffel symbols, `τ`, `C`), the
//! checks and the display layer ([`crate::print::parallel`]) share it. The calling thread always
//! takes a share of the work; the others are the helper threads of [`pool`], started once and
//! kept, and a value several threads wait for is a [`Shared`], waited for without being woken by
//! another thread (both for the same reason: a thread started or woken here ran on its waker's
//! core for up to a millisecond, see [`pool`]): by yielding, and past [`SPIN`] by napping
//! ([`Waiting`]), so that a helper kept from its core by another process may run on the
//! waiter's.
//!
//! What may run here must be pure. It may intern new atoms only where their ids order nothing that
//! is printed or generated (see [`crate::algebra::atom`]): tidying and printing, which order
//! structurally. The derivation's stages that run here intern no atom at all (sums, products by
//! `q̇` and `q̈`, derivatives of `sin` and `cos`, whose partner atom is computed, not interned), so
//! the polynomials they build, term order included, do not depend on the threads. The compact
//! derivations ([`crate::dynamics::compact`], [`crate::dynamics::ne_compact`]) intern a new atom
//! for each name, and may run beside each other (a sheet derives its Newton–Euler programs on a
//! helper): they create names in the order of their recursions and of their definitions, and find
//! a value's name by its polynomial, so no name depends on the ids either.
//!
//! The process-wide tables that threads write in turn (the atom interner, the display memos) are
//! locked by yielding too ([`lock`]).

pub mod lock;
pub mod pool;
mod shared;

pub use shared::{wait_for, Shared, Waiting, NAP, SPIN};

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};

/// The most threads a job uses by default.
const MAX_THREADS: usize = 4;

/// The machine's threads, up to [`MAX_THREADS`].
static MACHINE: OnceLock<usize> = OnceLock::new();

/// The number of threads set by [`set_threads`] (0: decide from the machine).
static THREADS: AtomicUsize = AtomicUsize::new(0);

/// Sets how many threads [`map`] may use (at least 1; 0 restores the default, the machine's cores
/// up to four). Every result is the same for every setting.
pub fn set_threads(n: usize) {
    THREADS.store(n, Ordering::Relaxed);
}

/// The number of threads [`map`] uses.
pub fn threads() -> usize {
    match THREADS.load(Ordering::Relaxed) {
        // Asked once: the standard library reads the cgroup's files every time (tens of µs).
        0 => *MACHINE.get_or_init(|| {
            std::thread::available_parallelism().map_or(1, |n| n.get().min(MAX_THREADS))
        }),
        n => n,
    }
}

thread_local! {
    /// Set while this thread runs [`serially`].
    static SERIAL: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` with every [`map`] it calls on this thread kept on this thread: for work that already
/// runs beside another thread's (a derivation while a helper prints its earlier stages), where more
/// threads would only share the same cores.
pub fn serially<R>(f: impl FnOnce() -> R) -> R {
    let before = SERIAL.with(|s| s.replace(true));
    let r = f();
    SERIAL.with(|s| s.set(before));
    r
}

/// `f` of every item, in the items' order, computed on up to [`threads`] threads when `weight`
/// (an estimate of each item's cost) sums to at least `min_total`; on the calling thread otherwise,
/// and always inside [`serially`].
/// Threads take items heaviest first, one at a time, so a few large items do not leave a thread idle.
/// Lending work to a helper and taking the results back costs some tens of microseconds, so
/// `min_total` should stand for more work than that.
pub fn map<T: Sync, R: Send>(
    items: &[T],
    weight: impl Fn(&T) -> usize,
    min_total: usize,
    f: impl Fn(&T) -> R + Sync,
) -> Vec<R> {
    let weights: Vec<usize> = items.iter().map(&weight).collect();
    let total: usize = weights.iter().sum();
    if items.len() < 2 || total < min_total {
        return items.iter().map(f).collect();
    }
    let threads = threads();
    if threads < 2 || SERIAL.with(|s| s.get()) {
        return items.iter().map(f).collect();
    }
    // Heaviest first; equal weights in item order (a stable sort), so the schedule is reproducible.
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| weights[b].cmp(&weights[a]));
    let next = AtomicUsize::new(0);
    let done: Mutex<Vec<(usize, R)>> = Mutex::new(Vec::with_capacity(items.len()));
    let (order, next, f, all) = (&order, &next, &f, &done);
    let take = move || {
        let mut mine = Vec::new();
        loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let Some(&i) = order.get(k) else { break };
            mine.push((i, f(&items[i])));
        }
        all.lock().unwrap_or_else(|p| p.into_inner()).extend(mine);
    };
    pool::scope_open(threads - 1, &take, take);
    let mut done = done.into_inner().unwrap_or_else(|p| p.into_inner());
    done.sort_by_key(|&(i, _)| i);
    done.into_iter().map(|(_, r)| r).collect()
}

/// Runs `work` on up to [`threads`] threads at once, each its own call (`work` takes its items from
/// a queue of its own until none is left), when `total`, the work's estimated weight as for [`map`],
/// is at least `min_total`; once on the calling thread otherwise, and always inside [`serially`].
/// The calling thread runs `work` too.
pub fn share(total: usize, min_total: usize, work: impl Fn() + Sync) {
    let threads = threads();
    if total < min_total || threads < 2 || SERIAL.with(|s| s.get()) {
        work();
        return;
    }
    pool::scope(threads - 1, &work, &work);
}

/// `a()` and `b()`: `a` on a helper thread ([`pool`]) while this thread runs `b`, when there is one
/// to spare and [`threads`] allows two or more outside [`serially`]; `a` after `b` on this thread
/// otherwise. A panic in either reaches the caller once both have stopped.
pub fn join<A: Send, B>(a: impl FnOnce() -> A + Send, b: impl FnOnce() -> B) -> (A, B) {
    if threads() < 2 || SERIAL.with(|s| s.get()) {
        let rb = b();
        return (a(), rb);
    }
    let a = Mutex::new(Some(a));
    let out = Mutex::new(None);
    let work = || {
        let a = a.lock().unwrap_or_else(|p| p.into_inner()).take();
        if let Some(a) = a {
            let r = a();
            *out.lock().unwrap_or_else(|p| p.into_inner()) = Some(r);
        }
    };
    let (rb, _) = pool::scope(1, &work, b);
    // Not taken by a helper (none to spare): here.
    work();
    let ra = out
        .into_inner()
        .unwrap_or_else(|p| p.into_inner())
        .expect("`a` ran, on a helper or here");
    (ra, rb)
}

/// `f` of every item, given to `consume` on the calling thread in the items' order as soon as it
/// and every item before it are computed: computed on up to [`threads`] threads, taken in the
/// items' order, when `weight` sums to at least `min_total` (as for [`map`]); one by one on the
/// calling thread otherwise, and always inside [`serially`]. A result is dropped once consumed, and
/// the workers compute at most `AHEAD` (four) items per thread past the last one consumed, so
/// that only a few results are held at a time however slow the consumer (a pipe to a slow
/// reader): for a document of megabytes written as it is printed (memory touched for the first
/// time costs more here than the printing). The calling thread consumes, and computes the next
/// item no thread took, within the same window, whenever the one it is due to consume is not
/// ready (past the window it waits: a worker holds that item).
pub fn map_in_order<T: Sync, R: Send>(
    items: &[T],
    weight: impl Fn(&T) -> usize,
    min_total: usize,
    f: impl Fn(&T) -> R + Sync,
    mut consume: impl FnMut(usize, R),
) {
    let total: usize = items.iter().map(weight).sum();
    let threads = threads();
    if items.len() < 2 || total < min_total || threads < 2 || SERIAL.with(|s| s.get()) {
        for (i, item) in items.iter().enumerate() {
            consume(i, f(item));
        }
        return;
    }
    /// The results computed and not consumed yet, how many were consumed, and whether a thread
    /// stopped by panicking.
    struct Ready<R> {
        results: Vec<Option<R>>,
        consumed: usize,
        failed: bool,
    }
    /// Marks the work as failed if its thread unwinds, so the others stop waiting.
    struct Alarm<'s, R>(&'s (std::sync::Mutex<Ready<R>>, std::sync::Condvar));
    impl<R> Drop for Alarm<'_, R> {
        fn drop(&mut self) {
            if std::thread::panicking() {
                if let Ok(mut ready) = self.0 .0.lock() {
                    ready.failed = true;
                }
                self.0 .1.notify_all();
            }
        }
    }
    let state = (
        std::sync::Mutex::new(Ready {
            results: (0..items.len()).map(|_| None).collect(),
            consumed: 0,
            failed: false,
        }),
        std::sync::Condvar::new(),
    );
    let next = AtomicUsize::new(0);
    let (state, next, f) = (&state, &next, &f);
    let ahead = AHEAD * threads;
    let work = move || {
        let _alarm = Alarm(state);
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(item) = items.get(i) else { break };
            // The item the consumer waits for is never held back (it is below the window), so
            // the wait always ends.
            let mut ready = state.0.lock().expect("a worker does not panic");
            while i >= ready.consumed + ahead && !ready.failed {
                ready = state.1.wait(ready).expect("a worker does not panic");
            }
            if ready.failed {
                break;
            }
            drop(ready);
            let r = f(item);
            state.0.lock().expect("a worker does not panic").results[i] = Some(r);
            state.1.notify_all();
        }
    };
    // The calling thread consumes, and computes the next item not taken whenever the one it is
    // due to consume is not ready.
    pool::scope(threads - 1, &work, || {
        // A consumer that panics stops the workers too.
        let _alarm = Alarm(state);
        for i in 0..items.len() {
            let r = loop {
                let mut ready = state.0.lock().expect("a worker does not panic");
                if let Some(r) = ready.results[i].take() {
                    ready.consumed = i + 1;
                    break r;
                }
                assert!(!ready.failed, "a worker thread does not panic");
                drop(ready);
                // The next item no thread took, within the workers' window past this one: a
                // worker that took item `i` and was then held off its core (a busy machine) must
                // not let this thread compute every item after it meanwhile. Item `i` itself is
                // within the window, so when none can be taken a worker holds it and will give it.
                let taken = next.fetch_update(Ordering::Relaxed, Ordering::Relaxed, |j| {
                    (j < items.len() && j < i + ahead).then_some(j + 1)
                });
                if let Ok(j) = taken {
                    let r = f(&items[j]);
                    state.0.lock().expect("a worker does not panic").results[j] = Some(r);
                    continue;
                }
                let mut ready = state.0.lock().expect("a worker does not panic");
                while ready.results[i].is_none() && !ready.failed {
                    ready = state.1.wait(ready).expect("a worker does not panic");
                }
            };
            state.1.notify_all();
            consume(i, r);
        }
    });
}

/// How many items per thread [`map_in_order`]'s workers compute past the last one consumed.
const AHEAD: usize = 4;

/// About a third of a millisecond of work (the items' weights, in units of about 3 ns): below it
/// a job stays on the calling thread, whose share would be most of it.
pub const WORTH_SHARING: usize = 100_000;

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

    #[test]
    fn results_are_consumed_in_the_items_order_on_the_calling_thread() {
        let items: Vec<u64> = (0..300).collect();
        // Uneven costs, so later items are often ready before earlier ones.
        let work =
            |&n: &u64| (0..(n % 5) * 3000).fold(n, |a, b| a.wrapping_mul(31).wrapping_add(b));
        let want: Vec<(usize, u64)> = items.iter().map(work).enumerate().collect();
        let here = std::thread::current().id();
        for min_total in [0, usize::MAX] {
            let mut got = Vec::new();
            map_in_order(
                &items,
                |&n| n as usize,
                min_total,
                work,
                |i, r| {
                    assert_eq!(std::thread::current().id(), here, "consumed here");
                    got.push((i, r));
                },
            );
            assert_eq!(got, want, "min_total {min_total}");
        }
        map_in_order(&[] as &[u64], |_| 1, 0, work, |_, _| panic!("no item"));
    }

    /// The most items started past the one being consumed, over 64 items each consumed in 300 µs;
    /// with `hold`, the first item a worker takes sleeps 20 ms first (a worker held off its core
    /// while it holds the item due). Every item is computed once.
    fn most_ahead_of_a_slow_consumer(hold: bool) -> usize {
        let items: Vec<u64> = (0..64).collect();
        let caller = std::thread::current().id();
        let held = std::sync::atomic::AtomicBool::new(!hold);
        let started = AtomicUsize::new(0);
        let mut most = 0;
        map_in_order(
            &items,
            |_| usize::MAX / 128,
            0,
            |&n| {
                started.fetch_add(1, Ordering::SeqCst);
                if std::thread::current().id() != caller && !held.swap(true, Ordering::SeqCst) {
                    std::thread::sleep(std::time::Duration::from_millis(20));
                }
                n
            },
            |i, _| {
                most = most.max(started.load(Ordering::SeqCst) - i);
                std::thread::sleep(std::time::Duration::from_micros(300));
            },
        );
        assert_eq!(started.load(Ordering::SeqCst), items.len());
        most
    }

    /// A worker held off its core while it holds the item due does not let the consuming thread
    /// compute every later item meanwhile: it computes up to the window and waits (without that,
    /// 63 items ahead; CI met it once with the tests of other modules running beside this one).
    #[test]
    fn the_consumer_stays_within_the_window_while_a_worker_holds_the_item_due() {
        let most = most_ahead_of_a_slow_consumer(true);
        assert!(most <= AHEAD * threads() + 1, "{most} computed ahead");
    }

    /// A slow consumer holds the workers back: they never compute more than their window past the
    /// last item consumed (without the window, they would compute every item at once).
    #[test]
    fn workers_stay_a_few_items_ahead_of_a_slow_consumer() {
        let most = most_ahead_of_a_slow_consumer(false);
        assert!(most <= AHEAD * threads() + 1, "{most} computed ahead");
        assert!(
            most < 32,
            "{most} computed ahead: the window holds them back"
        );
    }

    #[test]
    fn a_consumer_that_panics_stops_the_workers() {
        let items: Vec<u64> = (0..64).collect();
        let stopped = std::panic::catch_unwind(|| {
            map_in_order(
                &items,
                |_| usize::MAX / 128,
                0,
                |&n| n,
                |i, _| assert!(i != 2, "item 2 is refused"),
            )
        });
        assert!(
            stopped.is_err(),
            "the panic reaches the caller, which does not hang"
        );
    }

    #[test]
    fn a_worker_that_panics_stops_the_consumer() {
        let items: Vec<u64> = (0..64).collect();
        let stopped = std::panic::catch_unwind(|| {
            map_in_order(
                &items,
                |_| usize::MAX / 128,
                0,
                |&n| {
                    assert!(n != 3, "item 3 fails");
                    n
                },
                |_, _| {},
            )
        });
        // Only with two or more threads does a worker run apart from the consumer.
        assert!(stopped.is_err() || threads() < 2);
    }

    #[test]
    fn share_runs_the_work_until_its_queue_is_empty_on_this_thread_below_the_threshold() {
        let items: Vec<u64> = (0..500).collect();
        let next = AtomicUsize::new(0);
        let total = std::sync::atomic::AtomicU64::new(0);
        let work = || loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let Some(x) = items.get(k) else { break };
            total.fetch_add(*x, Ordering::Relaxed);
        };
        share(usize::MAX, 0, work);
        assert_eq!(total.load(Ordering::Relaxed), items.iter().sum::<u64>());
        // Below the threshold, or inside `serially`: once, on this thread.
        let here = std::thread::current().id();
        let calls = std::sync::Mutex::new(Vec::new());
        let record = || calls.lock().unwrap().push(std::thread::current().id());
        share(0, 1, record);
        serially(|| share(usize::MAX, 0, record));
        assert_eq!(*calls.lock().unwrap(), vec![here, here]);
    }

    #[test]
    fn serially_keeps_every_item_on_this_thread_and_restores() {
        let items: Vec<u64> = (0..64).collect();
        let here = std::thread::current().id();
        let on = |_: &u64| std::thread::current().id();
        let inside = serially(|| {
            // Nested: still on this thread after the inner call returns.
            serially(|| ());
            map(&items, |_| usize::MAX / 128, 0, on)
        });
        assert!(inside.iter().all(|&id| id == here));
        assert!(!SERIAL.with(|s| s.get()), "the flag is restored");
    }
}
