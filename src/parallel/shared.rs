//! Values computed once by whichever thread asks first, the others waiting for them without
//! being woken by the thread that computes them.
//!
//! A thread that sleeps until another thread's result is ready is woken by that thread, and the
//! kernel here (a two-core virtual machine, measured) nearly always wakes it on the waker's core,
//! where it waits for that thread's time slice (0.5–1.5 ms) while the other core idles: the
//! Franka Panda's and the SCARA arm's sheets lost a millisecond at a time that way, whenever the
//! layout waited for a vector or a derivation the other thread was computing. A thread waiting
//! here yields its core instead ([`std::thread::yield_now`]) and looks again, so it is never
//! asleep, and gives its core to whatever else wants it.
//!
//! Not for long, though ([`Waiting`]): a wait of more than [`SPIN`] means, as a rule, that the
//! thread it waits for is not running: another process took its core (the helper is held to
//! the cores other than its caller's while the caller does its share, [`super::pool`]). A
//! thread that yields never leaves its own core idle, so the kernel never moves that helper
//! onto it. So after [`SPIN`] the waiter allows every helper every core
//! ([`super::pool::release`]) and naps, [`NAP`] at a time, woken by its own timer rather than by
//! another thread: its core idles meanwhile and the kernel may run the helper there. With a
//! busy loop of another process on the second core (four interleaved rounds of 20–40 runs),
//! the SCARA arm's sheet took 10.7–11.7 ms before and 8.4–10.5 ms after, the all-symbolic PUMA
//! 560's 37.6–42.8 ms before and 31.1–35.1 ms after; on an idle machine the same within the
//! noise (a sheet's waits there are shorter than [`SPIN`], but for the proofs', which the
//! waiter spends helping).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// A [`OnceLock`] whose waiters yield, then nap, instead of sleeping until the thread that sets it
/// wakes them ([`Waiting`], see the module's doc).
#[derive(Debug, Default)]
pub struct Shared<T> {
    cell: OnceLock<T>,
    /// Set while a thread computes the value.
    claimed: AtomicBool,
}

impl<T> Shared<T> {
    /// Empty.
    pub const fn new() -> Shared<T> {
        Shared {
            cell: OnceLock::new(),
            claimed: AtomicBool::new(false),
        }
    }

    /// The value, if computed.
    pub fn get(&self) -> Option<&T> {
        self.cell.get()
    }

    /// The value, computed by `f` on this thread if no thread computes it yet; waits
    /// ([`Waiting`]) while another thread does. If that thread panics, a waiting one computes it instead.
    pub fn get_or_init(&self, f: impl FnOnce() -> T) -> &T {
        let mut f = Some(f);
        let mut waiting = Waiting::new();
        loop {
            if let Some(v) = self.cell.get() {
                return v;
            }
            if !self.claimed.swap(true, Ordering::Acquire) {
                /// Lets another thread compute the value if `f` panics.
                struct Release<'a>(&'a AtomicBool);
                impl Drop for Release<'_> {
                    fn drop(&mut self) {
                        self.0.store(false, Ordering::Release);
                    }
                }
                let _release = Release(&self.claimed);
                let f = f.take().expect("claimed once by this call");
                return self.cell.get_or_init(f);
            }
            waiting.pause();
        }
    }

    /// Sets the value if none is set or being computed; `false` otherwise.
    pub fn set(&self, value: T) -> bool {
        if self.claimed.swap(true, Ordering::Acquire) {
            return false;
        }
        let set = self.cell.set(value).is_ok();
        self.claimed.store(false, Ordering::Release);
        set
    }

    /// The value, waiting ([`Waiting`]) until a thread sets or computes it.
    pub fn wait(&self) -> &T {
        wait_for(&self.cell)
    }

    /// The value, once another thread has set it, this thread running open work meanwhile
    /// ([`super::pool::help`]): for a thread that holds nothing another may wait for.
    pub fn wait_helping(&self) -> &T {
        let mut waiting = Waiting::new();
        loop {
            if let Some(v) = self.cell.get() {
                return v;
            }
            // Open work whose items are all taken is still listed until its caller is done:
            // joining it runs nothing, so this thread pauses either way; after work it ran,
            // the wait starts again (yielding first).
            if super::pool::help() {
                waiting = Waiting::new();
            }
            waiting.pause();
        }
    }
}

/// The value of `cell`, waiting ([`Waiting`]) until another thread sets it.
pub fn wait_for<T>(cell: &OnceLock<T>) -> &T {
    let mut waiting = Waiting::new();
    loop {
        if let Some(v) = cell.get() {
            return v;
        }
        waiting.pause();
    }
}

/// How long a wait yields before it naps (see the module's doc): longer than nearly every wait
/// of a sheet on an idle machine (the layout's for a vector: 42 µs on average, 0.35 ms at most).
pub const SPIN: Duration = Duration::from_micros(200);

/// One nap of a wait past [`SPIN`]: what a wait may last longer than needed (with the kernel's
/// timer slack, 50 µs more).
pub const NAP: Duration = Duration::from_micros(50);

/// A wait for another thread, one [`Waiting::pause`] between looks: yielding until [`SPIN`] has
/// passed, then napping [`NAP`] at a time, the helpers first allowed every core (module doc).
#[derive(Debug, Default)]
pub struct Waiting {
    /// When the first pause was.
    since: Option<Instant>,
    /// Whether the helpers were released.
    napping: bool,
}

impl Waiting {
    /// A wait not started yet.
    pub const fn new() -> Waiting {
        Waiting {
            since: None,
            napping: false,
        }
    }

    /// One pause before looking again.
    pub fn pause(&mut self) {
        if !self.napping {
            let since = *self.since.get_or_insert_with(Instant::now);
            if since.elapsed() < SPIN {
                std::thread::yield_now();
                return;
            }
            self.napping = true;
            super::pool::release();
        }
        std::thread::sleep(NAP);
    }

    /// Whether this wait has napped.
    pub fn napped(&self) -> bool {
        self.napping
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicUsize;

    #[test]
    fn the_value_is_computed_once_whichever_threads_ask() {
        let shared: Shared<usize> = Shared::new();
        let calls = AtomicUsize::new(0);
        let compute = || {
            calls.fetch_add(1, Ordering::SeqCst);
            std::thread::sleep(std::time::Duration::from_millis(2));
            42
        };
        let got: Vec<usize> = std::thread::scope(|s| {
            let hs: Vec<_> = (0..4)
                .map(|_| s.spawn(|| *shared.get_or_init(compute)))
                .collect();
            hs.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert_eq!(got, vec![42; 4]);
        assert_eq!(calls.load(Ordering::SeqCst), 1);
        assert!(!shared.set(7), "already set");
        assert_eq!(*shared.wait(), 42);
    }

    #[test]
    fn a_waiter_computes_the_value_when_the_first_thread_panics() {
        let shared: Shared<usize> = Shared::new();
        let first = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            shared.get_or_init(|| panic!("the first computation fails"))
        }));
        assert!(first.is_err());
        assert_eq!(shared.get(), None);
        assert_eq!(*shared.get_or_init(|| 5), 5);
    }

    /// A wait yields while it is short and naps once it has lasted longer than `SPIN` (the pause
    /// after that naps, however long this thread was held up meanwhile: a loaded machine may keep
    /// it from running for longer than `SPIN` at a time).
    #[test]
    fn a_long_wait_naps() {
        let mut waiting = Waiting::new();
        waiting.pause();
        let started = waiting.since.expect("the first pause starts the wait");
        let mut pauses = 1;
        while started.elapsed() <= SPIN {
            waiting.pause();
            pauses += 1;
        }
        waiting.pause();
        assert!(waiting.napped(), "after {pauses} pauses");
        let mut fresh = Waiting::new();
        assert!(!fresh.napped());
        fresh.pause();
        // One pause naps only if this thread was held up for longer than `SPIN` meanwhile.
        assert!(!fresh.napped() || fresh.since.is_some_and(|t| t.elapsed() >= SPIN));
    }

    #[test]
    fn a_thread_waits_for_a_value_set_elsewhere() {
        let cell: OnceLock<u32> = OnceLock::new();
        let got = std::thread::scope(|s| {
            let h = s.spawn(|| *wait_for(&cell));
            std::thread::sleep(std::time::Duration::from_millis(2));
            cell.set(9).unwrap();
            h.join().unwrap()
        });
        assert_eq!(got, 9);
    }
}
