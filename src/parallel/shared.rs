//! Values computed once by whichever thread asks first, the others waiting for them without
//! sleeping.
//!
//! A thread that sleeps until another thread's result is ready is woken by that thread, and the
//! kernel here (a two-core virtual machine, measured) nearly always wakes it on the waker's core,
//! where it waits for that thread's time slice (0.5–1.5 ms) while the other core idles: the
//! Franka Panda's and the SCARA arm's sheets lost a millisecond at a time that way, whenever the
//! layout waited for a vector or a derivation the other thread was computing. A thread waiting
//! here yields its core instead ([`std::thread::yield_now`]) and looks again, so it is never
//! asleep, and gives its core to whatever else wants it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

/// A [`OnceLock`] whose waiters yield instead of sleeping (see the module's doc).
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

    /// The value, computed by `f` on this thread if no thread computes it yet; waits (yielding)
    /// while another thread does. If that thread panics, a waiting one computes it instead.
    pub fn get_or_init(&self, f: impl FnOnce() -> T) -> &T {
        let mut f = Some(f);
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
            std::thread::yield_now();
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

    /// The value, waiting (yielding) until a thread sets or computes it.
    pub fn wait(&self) -> &T {
        wait_for(&self.cell)
    }

    /// The value, once another thread has set it, this thread running open work meanwhile
    /// ([`super::pool::help`]): for a thread that holds nothing another may wait for.
    pub fn wait_helping(&self) -> &T {
        loop {
            if let Some(v) = self.cell.get() {
                return v;
            }
            // Open work whose items are all taken is still listed until its caller is done:
            // joining it runs nothing, so this thread yields either way.
            super::pool::help();
            std::thread::yield_now();
        }
    }
}

/// The value of `cell`, waiting (yielding, see the module's doc) until another thread sets it.
pub fn wait_for<T>(cell: &OnceLock<T>) -> &T {
    loop {
        if let Some(v) = cell.get() {
            return v;
        }
        std::thread::yield_now();
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
