//! Locks taken by yielding instead of sleeping, for the process-wide tables several threads read
//! and write in turn: the atom interner ([`crate::algebra::atom`]), the tables of `cos(π/L)`
//! ([`crate::algebra::pi_field`]) and the display memos ([`crate::algebra::tidy`]).
//!
//! Each holds its lock for a hash lookup or insert. A thread that slept on such a lock was woken
//! on its waker's core and waited there up to a millisecond (see [`super::Shared`]): the Stanford
//! arm's sheet, whose two threads both name intermediates (each new name is a new atom), lost
//! several milliseconds that way. A thread here looks again after yielding its core.

use std::sync::{
    Mutex, MutexGuard, RwLock, RwLockReadGuard, RwLockWriteGuard, TryLockError, TryLockResult,
};

/// `try` until it gives the lock, yielding in between; a poisoned lock is taken as it is (each
/// table here is whole between single calls, so a panic elsewhere leaves it good).
fn taken<G>(mut attempt: impl FnMut() -> TryLockResult<G>) -> G {
    loop {
        match attempt() {
            Ok(guard) => return guard,
            Err(TryLockError::Poisoned(p)) => return p.into_inner(),
            Err(TryLockError::WouldBlock) => std::thread::yield_now(),
        }
    }
}

/// Reads `lock`, yielding while a writer holds it.
pub fn read<T>(lock: &RwLock<T>) -> RwLockReadGuard<'_, T> {
    taken(|| lock.try_read())
}

/// Writes `lock`, yielding while another thread holds it.
pub fn write<T>(lock: &RwLock<T>) -> RwLockWriteGuard<'_, T> {
    taken(|| lock.try_write())
}

/// Locks `lock`, yielding while another thread holds it.
pub fn lock<T>(lock: &Mutex<T>) -> MutexGuard<'_, T> {
    taken(|| lock.try_lock())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two threads adding to one table in turn, by writes and reads: every write lands.
    #[test]
    fn writes_from_two_threads_all_land() {
        let table = RwLock::new(Vec::new());
        let m = Mutex::new(0u32);
        std::thread::scope(|s| {
            for t in 0..2u32 {
                let (table, m) = (&table, &m);
                s.spawn(move || {
                    for k in 0..2000u32 {
                        write(table).push(t * 10_000 + k);
                        assert!(read(table).contains(&(t * 10_000 + k)));
                        *lock(m) += 1;
                    }
                });
            }
        });
        let mut all = table.into_inner().unwrap();
        all.sort_unstable();
        let want: Vec<u32> = (0..2u32)
            .flat_map(|t| (0..2000).map(move |k| t * 10_000 + k))
            .collect();
        assert_eq!(all, want);
        assert_eq!(*m.lock().unwrap(), 4000);
    }
}
