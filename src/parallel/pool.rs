//! The helper threads of [`super`]: started once, on first use, and kept for the process, each
//! waiting for work lent to it by [`scope`].
//!
//! Two things made threads started for each job slow to help here (a two-core virtual machine,
//! measured): starting a thread took 50–150 µs, and a new or woken thread was nearly always put on
//! the core of the thread that started or woke it, where it waited for that thread's time slice
//! (0.5–1.2 ms) while the other core stayed idle, so work of a millisecond or two ran on one core.
//! Kept threads are started once; and while [`scope`] does its own share of the work it allows the
//! helpers it lent work to only the cores other than its own (their affinity,
//! `sched_setaffinity(2)`, Linux only: elsewhere the kernel places them), so a helper starts
//! within about 60 µs on an idle core and no wake-up moves it onto the caller's; once its share
//! is done, the caller allows them every core of the process again. (Keeping the caller on its
//! own core as well was measured: setting its own affinity sometimes held it for 1.4 ms, and
//! the sheet gained nothing.)
//!
//! Work that any number of threads may run at once, each taking items until none is left
//! ([`super::map`]'s), is also *open* while its caller runs ([`scope_open`]): a thread that only
//! waits ([`help`], the sheet's thread waiting for the proofs a helper runs) joins it, however late
//! it comes, instead of idling beside it.
//!
//! Each helper lends itself to one [`scope`] at a time and is back in the pool before that call
//! returns. A call takes only the helpers idle at that moment, and runs its own share of the work
//! meanwhile, so a call made by a helper (work nested in work) never waits for a helper that is
//! not coming.

use std::any::Any;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, OnceLock};

/// Work lent to helpers: a borrowed closure whose lifetime [`scope`] erases, and keeps alive by not
/// returning before every helper that took it has finished with it.
type Work = &'static (dyn Fn() + Sync);

/// The most helpers the pool keeps (as many as [`super::threads`] may use beside the caller).
const MOST: usize = 16;

/// One helper thread: the work lent to it, if any, and how to wake it.
struct Helper {
    /// The work lent and not taken yet, with the count its caller waits on.
    lent: Mutex<Option<(Work, Arc<Latch>)>>,
    /// Signalled when work is lent.
    wake: Condvar,
    /// The thread, for the placement hint (set once it is started).
    #[cfg(target_os = "linux")]
    thread: OnceLock<libc::pthread_t>,
}

/// The helpers, idle ones in a list of their own.
struct Pool {
    idle: Mutex<Vec<Arc<Helper>>>,
    /// Every helper started, idle or not ([`release`]).
    all: Mutex<Vec<Arc<Helper>>>,
    /// How many helpers were started.
    started: Mutex<usize>,
}

fn pool() -> &'static Pool {
    static POOL: OnceLock<Pool> = OnceLock::new();
    POOL.get_or_init(|| {
        // The process's cores, read before any helper exists (a helper's own are narrowed).
        placement::remember_cores();
        Pool {
            idle: Mutex::new(Vec::new()),
            all: Mutex::new(Vec::new()),
            started: Mutex::new(0),
        }
    })
}

/// Locks `m`, whose contents stay whole if a thread panicked while holding it (every change under
/// these locks is a single assignment or push). It blocks rather than yields
/// ([`super::lock`]): a helper's state and its latch are waited on with condition variables, and
/// an idle helper is meant to sleep.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|p| p.into_inner())
}

/// Open work ([`scope_open`]): the work, how many threads that joined it ([`help`]) still run it,
/// and the first panic among them.
struct Open {
    work: Work,
    running: AtomicUsize,
    panic: Mutex<Option<Box<dyn Any + Send>>>,
}

/// The open work of every thread, the latest last (locked by yielding, [`super::lock`]: a
/// thread waiting here would otherwise be woken on the core of the thread that held it).
fn open() -> &'static Mutex<Vec<Arc<Open>>> {
    static OPEN: Mutex<Vec<Arc<Open>>> = Mutex::new(Vec::new());
    &OPEN
}

/// Runs some open work on this thread, if there is any, until it is done ([`scope_open`]); whether
/// there was. For a thread that would otherwise wait, holding nothing another thread may wait for
/// (what open work runs is pure, [`super`]).
pub fn help() -> bool {
    let job = {
        let open = super::lock::lock(open());
        let Some(job) = open.last() else {
            return false;
        };
        // Counted while still listed, so its caller waits for this thread before returning.
        job.running.fetch_add(1, Ordering::AcqRel);
        Arc::clone(job)
    };
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(job.work));
    if let Err(p) = outcome {
        lock(&job.panic).get_or_insert(p);
    }
    job.running.fetch_sub(1, Ordering::AcqRel);
    true
}

/// [`scope`] of work that any number of threads may run at once, each call taking items until none
/// is left: open, besides, to every thread that calls [`help`] until this thread's share is done.
pub fn scope_open<R>(
    helpers: usize,
    work: &(dyn Fn() + Sync),
    own: impl FnOnce() -> R,
) -> (R, usize) {
    // SAFETY: as in `scope`: `work` is listed only until `Close` runs, which unlists it under the
    // lock a joining thread counts itself under, then waits until every thread that joined is done
    // with it; this function neither returns nor unwinds past `Close` before that.
    let erased: Work = unsafe { std::mem::transmute::<&(dyn Fn() + Sync), Work>(work) };
    let job = Arc::new(Open {
        work: erased,
        running: AtomicUsize::new(0),
        panic: Mutex::new(None),
    });
    super::lock::lock(open()).push(Arc::clone(&job));
    /// Unlists the work and waits for the threads that joined it, on return and on unwinding.
    struct Close<'a>(&'a Arc<Open>);
    impl Drop for Close<'_> {
        fn drop(&mut self) {
            super::lock::lock(open()).retain(|j| !Arc::ptr_eq(j, self.0));
            let mut waiting = super::Waiting::new();
            while self.0.running.load(Ordering::Acquire) > 0 {
                waiting.pause();
            }
        }
    }
    let close = Close(&job);
    let out = scope(helpers, work, own);
    drop(close);
    if let Some(p) = lock(&job.panic).take() {
        std::panic::resume_unwind(p);
    }
    out
}

/// How many helpers of a [`scope`] have not finished, and the first panic among them.
struct Latch {
    state: Mutex<(usize, Option<Box<dyn Any + Send>>)>,
    done: Condvar,
}

impl Latch {
    fn finish(&self, panic: Option<Box<dyn Any + Send>>) {
        let mut s = lock(&self.state);
        s.0 -= 1;
        if s.1.is_none() {
            s.1 = panic;
        }
        if s.0 == 0 {
            self.done.notify_all();
        }
    }

    /// Waits until every helper finished; the first panic among them, if any.
    fn wait(&self) -> Option<Box<dyn Any + Send>> {
        let mut s = lock(&self.state);
        while s.0 > 0 {
            s = self.done.wait(s).unwrap_or_else(|p| p.into_inner());
        }
        s.1.take()
    }
}

/// Up to `n` helpers: idle ones first, then new ones while the pool has fewer than
/// [`super::threads`] less one (and [`MOST`]), so that work nested in work never starts more
/// threads than there are to use. A helper that cannot be started is not counted (the caller
/// does its work).
fn take(n: usize) -> Vec<Arc<Helper>> {
    let mut got: Vec<Arc<Helper>> = {
        let mut idle = lock(&pool().idle);
        let keep = idle.len().saturating_sub(n);
        idle.split_off(keep)
    };
    while got.len() < n {
        let mut started = lock(&pool().started);
        if *started >= MOST.min(super::threads().saturating_sub(1)) {
            break;
        }
        match start() {
            Some(h) => {
                *started += 1;
                lock(&pool().all).push(Arc::clone(&h));
                got.push(h);
            }
            None => break,
        }
    }
    got
}

/// Allows every helper every core of the process again, for a thread about to leave its own core
/// idle while it waits ([`super::Waiting`]): a helper held to the other cores, behind
/// another process's time slice there, may then run on the waiter's. The next [`scope`] holds
/// the helpers it lends work to away from its caller's core again.
pub fn release() {
    for h in lock(&pool().all).iter() {
        placement::anywhere(h);
    }
}

/// Starts a helper thread, waiting for work.
fn start() -> Option<Arc<Helper>> {
    let helper = Arc::new(Helper {
        lent: Mutex::new(None),
        wake: Condvar::new(),
        #[cfg(target_os = "linux")]
        thread: OnceLock::new(),
    });
    let me = Arc::clone(&helper);
    let _handle = std::thread::Builder::new()
        .name("symdyn-helper".into())
        .spawn(move || serve(&me))
        .ok()?;
    #[cfg(target_os = "linux")]
    let _ = helper
        .thread
        .set(std::os::unix::thread::JoinHandleExt::as_pthread_t(&_handle));
    // Started off this thread's core too, so that it gets to wait for work without waiting for
    // this thread's time slice first.
    placement::away_from_here(&helper);
    Some(helper)
}

/// Starts the helpers [`super::threads`] allows, if not started yet, so that they are waiting
/// by the time work comes (starting a thread here takes 0.3–1.5 ms before it runs on another
/// core): for a command about to derive and print a robot large enough to share its work.
pub fn start_early() {
    let helpers = take(super::threads().saturating_sub(1));
    lock(&pool().idle).extend(helpers);
}

/// A helper's life: take the work lent, run it, go back to the idle list, tell the caller.
fn serve(me: &Arc<Helper>) {
    loop {
        let (work, latch) = {
            let mut lent = lock(&me.lent);
            loop {
                if let Some(job) = lent.take() {
                    break job;
                }
                lent = me.wake.wait(lent).unwrap_or_else(|p| p.into_inner());
            }
        };
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
        lock(&pool().idle).push(Arc::clone(me));
        latch.finish(outcome.err());
    }
}

/// Runs `work` on up to `helpers` helper threads (those idle now, or started now) while this
/// thread runs `own`, and returns `own`'s result with the number of helpers that ran `work`, once
/// each of them has returned. A panic in `work` or `own` reaches the caller after every helper
/// has finished.
pub fn scope<R>(helpers: usize, work: &(dyn Fn() + Sync), own: impl FnOnce() -> R) -> (R, usize) {
    let lent = if helpers == 0 {
        Vec::new()
    } else {
        take(helpers)
    };
    if lent.is_empty() {
        return (own(), 0);
    }
    let latch = Arc::new(Latch {
        state: Mutex::new((0, None)),
        done: Condvar::new(),
    });
    // SAFETY: `work` is borrowed for this call only. Each helper is done with it before it counts
    // itself out of `latch`, and this function neither returns nor unwinds past `Finish` before
    // the count is zero, so no helper uses `work` after the borrow ends.
    let work: Work = unsafe { std::mem::transmute::<&(dyn Fn() + Sync), Work>(work) };
    /// What is left to do once this thread has done its share: allow the helpers every core
    /// again, then wait for them. Done on return and on unwinding alike.
    struct Finish<'a> {
        latch: &'a Latch,
        lent: &'a [Arc<Helper>],
    }
    impl Finish<'_> {
        fn run(&mut self) -> Option<Box<dyn Any + Send>> {
            for h in self.lent {
                placement::anywhere(h);
            }
            self.latch.wait()
        }
    }
    impl Drop for Finish<'_> {
        fn drop(&mut self) {
            // Unwinding from `own`: its panic, not a helper's, goes on.
            let _ = self.run();
        }
    }
    let mut finish = Finish {
        latch: &latch,
        lent: &lent,
    };
    for h in &lent {
        placement::away_from_here(h);
        lock(&latch.state).0 += 1;
        *lock(&h.lent) = Some((work, Arc::clone(&latch)));
        h.wake.notify_one();
    }
    let r = own();
    let panic = finish.run();
    std::mem::forget(finish);
    if let Some(p) = panic {
        std::panic::resume_unwind(p);
    }
    (r, lent.len())
}

/// Where the helpers of a [`scope`] may run (Linux): on the cores other than the caller's, until
/// the caller has done its share.
#[cfg(target_os = "linux")]
mod placement {
    use super::Helper;
    use std::sync::OnceLock;

    /// The cores the process may use, as the first thread to use the pool found them.
    fn allowed() -> Option<&'static libc::cpu_set_t> {
        static ALLOWED: OnceLock<Option<libc::cpu_set_t>> = OnceLock::new();
        ALLOWED
            .get_or_init(|| {
                // SAFETY: `sched_getaffinity` writes at most `size_of::<cpu_set_t>()` bytes into
                // the zeroed set.
                unsafe {
                    let mut set: libc::cpu_set_t = std::mem::zeroed();
                    let ok = libc::sched_getaffinity(
                        0,
                        std::mem::size_of::<libc::cpu_set_t>(),
                        &mut set,
                    ) == 0;
                    (ok && libc::CPU_COUNT(&set) >= 2).then_some(set)
                }
            })
            .as_ref()
    }

    /// Reads the process's cores, for every later call.
    pub(super) fn remember_cores() {
        allowed();
    }

    /// Allows `h` every core of the process but this thread's, when that leaves one.
    pub(super) fn away_from_here(h: &Helper) {
        let Some(all) = allowed() else { return };
        // SAFETY: plain system calls on a copy of the set; `h.thread` is a live thread of the
        // pool (helpers never exit).
        unsafe {
            let here = libc::sched_getcpu();
            if here < 0 || !libc::CPU_ISSET(here as usize, all) {
                return;
            }
            let mut others = *all;
            libc::CPU_CLR(here as usize, &mut others);
            let Some(&thread) = h.thread.get() else {
                return;
            };
            libc::pthread_setaffinity_np(thread, std::mem::size_of::<libc::cpu_set_t>(), &others);
        }
    }

    /// Allows `h` every core of the process again.
    pub(super) fn anywhere(h: &Helper) {
        let Some(all) = allowed() else { return };
        // SAFETY: as in `away_from_here`.
        let Some(&thread) = h.thread.get() else {
            return;
        };
        unsafe {
            libc::pthread_setaffinity_np(thread, std::mem::size_of::<libc::cpu_set_t>(), all);
        }
    }
}

#[cfg(not(target_os = "linux"))]
mod placement {
    use super::Helper;
    pub(super) fn remember_cores() {}
    pub(super) fn away_from_here(_: &Helper) {}
    pub(super) fn anywhere(_: &Helper) {}
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// Work lent to helpers runs beside the caller's own, on other threads, and the call returns
    /// only once every helper is done with it.
    #[test]
    fn lent_work_runs_on_helpers_beside_the_callers_own() {
        let ran = AtomicUsize::new(0);
        let here = std::thread::current().id();
        let elsewhere = Mutex::new(Vec::new());
        let work = || {
            std::thread::sleep(std::time::Duration::from_millis(2));
            lock(&elsewhere).push(std::thread::current().id());
            ran.fetch_add(1, Ordering::SeqCst);
        };
        let (own, helpers) = scope(2, &work, || 7);
        assert_eq!(own, 7);
        // Other tests may hold helpers meanwhile: as many ran as were lent, none on this thread.
        assert_eq!(ran.load(Ordering::SeqCst), helpers);
        assert!(lock(&elsewhere).iter().all(|&id| id != here));
        assert!(helpers <= 2);
    }

    /// A helper's panic reaches the caller, after the caller's own work, and the helper is back
    /// in the pool for the next call.
    #[test]
    fn a_helpers_panic_reaches_the_caller() {
        let own_done = AtomicUsize::new(0);
        let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            scope(1, &|| panic!("the lent work fails"), || {
                own_done.fetch_add(1, Ordering::SeqCst);
            })
        }));
        assert_eq!(own_done.load(Ordering::SeqCst), 1);
        match r {
            // Lent and failed: the panic came back.
            Err(_) => {}
            // No helper to spare (another test holds them): the work did not run.
            Ok(((), helpers)) => assert_eq!(helpers, 0),
        }
        let (_, again) = scope(1, &|| (), || ());
        assert!(again <= 1);
    }

    /// Open work is joined by a thread that calls `help`, however late it comes: each item runs
    /// once, some on the joining thread, and the call returns only once that thread is done.
    #[test]
    fn a_waiting_thread_joins_open_work() {
        const ITEMS: usize = 64;
        let next = AtomicUsize::new(0);
        let done: Vec<AtomicUsize> = (0..ITEMS).map(|_| AtomicUsize::new(0)).collect();
        let joined = std::sync::atomic::AtomicBool::new(false);
        let publisher = std::thread::current().id();
        let work = || loop {
            let k = next.fetch_add(1, Ordering::SeqCst);
            if k >= ITEMS {
                break;
            }
            if std::thread::current().id() == publisher {
                // Holds the items back until the other thread has joined (ten seconds at most).
                let start = std::time::Instant::now();
                while !joined.load(Ordering::SeqCst) && start.elapsed().as_secs() < 10 {
                    std::thread::yield_now();
                }
            } else {
                joined.store(true, Ordering::SeqCst);
            }
            done[k].fetch_add(1, Ordering::SeqCst);
        };
        std::thread::scope(|s| {
            // Other tests' open work may come first: it runs too.
            s.spawn(|| {
                while next.load(Ordering::SeqCst) < ITEMS && !joined.load(Ordering::SeqCst) {
                    if !help() {
                        std::thread::yield_now();
                    }
                }
            });
            scope_open(0, &work, work);
        });
        assert!(joined.load(Ordering::SeqCst), "the waiting thread joined");
        assert!(done.iter().all(|d| d.load(Ordering::SeqCst) == 1));
    }

    /// Work lent from lent work takes only helpers idle at that moment, so it never waits for
    /// one: every level runs to the end.
    #[test]
    fn nested_calls_never_wait_for_a_helper() {
        let leaves = AtomicUsize::new(0);
        let leaf = || {
            leaves.fetch_add(1, Ordering::SeqCst);
        };
        let inner = || {
            let (_, n) = scope(3, &leaf, leaf);
            leaves.fetch_add(100 * n, Ordering::SeqCst);
        };
        let (_, outer) = scope(3, &inner, inner);
        assert!(leaves.load(Ordering::SeqCst) > outer, "every level ran");
    }
}
