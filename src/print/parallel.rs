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
//!
//! [`pipeline`] goes one step further: it prints the stages of a derivation (`D`, then the
//! Christoffel symbols, then `τ`) on a helper thread while this thread derives the later ones, so
//! printing a large robot's equations overlaps deriving them. The derivation and the printers then
//! intern atoms concurrently too, under the same rule: ids order nothing that is printed.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

pub use crate::parallel::{map, set_threads, threads};

/// Below this much work in all (the items' weights: about 3 ns a unit, see `report::side_work`), a
/// [`pipeline`] that does not overlap its derivation prints on one thread.
pub const SHARED_WORK: usize = crate::parallel::WORTH_SHARING;

/// One stage of a [`pipeline`]: returns its items, and the context they are printed in, once their
/// inputs exist (it may wait for another thread to derive them).
pub type Stage<'a, C, T> = Box<dyn Fn() -> (C, Vec<T>) + Sync + 'a>;

/// A stage's items once it has returned them, with their weights and which have been taken.
struct Ready<C, T> {
    ctx: C,
    items: Vec<T>,
    /// Each item's weight.
    weights: Vec<usize>,
    /// Item indices, heaviest first (equal weights in item order).
    order: Vec<usize>,
    /// Whether a thread has taken each item.
    taken: Vec<AtomicBool>,
}

impl<C, T> Ready<C, T> {
    /// Takes item `i` for this thread, unless another has.
    fn take(&self, i: usize) -> bool {
        !self.taken[i].swap(true, Ordering::Relaxed)
    }
}

/// `f` of every item of every stage, by stage and in item order, printed while this thread runs
/// `work` (a derivation): a helper thread takes each stage's items as soon as the stage returns
/// them, while later stages are still being derived, heaviest first; when `work` is done this
/// thread joins in, and the items left are taken heaviest first across all stages. The first stage
/// is asked for on this thread, before `work`: when its items are not `worth` overlapping (a
/// derivation too quick to print beside), or on one thread, `work` runs first and then every item
/// is printed by [`map`] (on several threads past [`SHARED_WORK`] in all). The results are the same
/// on any number of threads (`f` is pure).
pub fn pipeline<C: Send + Sync, T: Send + Sync, R: Send>(
    work: impl FnOnce(),
    stages: &[Stage<'_, C, T>],
    worth: impl FnOnce(&[T]) -> bool,
    weight: impl Fn(&T) -> usize + Sync,
    f: impl Fn(&C, &T) -> R + Sync,
) -> Vec<Vec<R>> {
    let Some((first, rest)) = stages.split_first() else {
        work();
        return Vec::new();
    };
    let (ctx, items) = first();
    let threads = threads();
    if threads < 2 || !worth(&items) {
        work();
        let mut all = vec![(ctx, items)];
        all.extend(rest.iter().map(|stage| stage()));
        let flat: Vec<(usize, &T)> = all
            .iter()
            .enumerate()
            .flat_map(|(s, (_, items))| items.iter().map(move |t| (s, t)))
            .collect();
        let mut printed = map(
            &flat,
            |(_, t)| weight(t),
            SHARED_WORK,
            |(s, t)| f(&all[*s].0, t),
        )
        .into_iter();
        return all
            .iter()
            .map(|(_, items)| printed.by_ref().take(items.len()).collect())
            .collect();
    }
    let ready_from = |(ctx, items): (C, Vec<T>)| {
        let weights: Vec<usize> = items.iter().map(&weight).collect();
        let mut order: Vec<usize> = (0..items.len()).collect();
        order.sort_by(|&a, &b| weights[b].cmp(&weights[a]));
        Ready {
            ctx,
            taken: items.iter().map(|_| AtomicBool::new(false)).collect(),
            items,
            weights,
            order,
        }
    };
    let ready: Vec<OnceLock<Ready<C, T>>> = stages.iter().map(|_| OnceLock::new()).collect();
    if ready[0].set(ready_from((ctx, items))).is_err() {
        unreachable!("the first stage is set once, here");
    }
    // Once `work` is done every stage is ready, and the items left are taken heaviest first across
    // all stages, so a long one is not left to the end.
    let all: OnceLock<Vec<(usize, usize)>> = OnceLock::new();
    let (ready, all, f) = (&ready, &all, &f);
    let from_all = |mine: &mut Vec<(usize, usize, R)>| {
        for &(s, i) in all.get().expect("set once the work is done") {
            let r = ready[s].get().expect("every stage is ready");
            if r.take(i) {
                mine.push((s, i, f(&r.ctx, &r.items[i])));
            }
        }
    };
    let helper = || {
        let mut mine: Vec<(usize, usize, R)> = Vec::new();
        for (s, stage) in stages.iter().enumerate() {
            let r = ready[s].get_or_init(|| ready_from(stage()));
            for &i in &r.order {
                if all.get().is_some() {
                    from_all(&mut mine);
                    return mine;
                }
                if r.take(i) {
                    mine.push((s, i, f(&r.ctx, &r.items[i])));
                }
            }
        }
        mine
    };
    let mut done = std::thread::scope(|scope| {
        let helpers: Vec<_> = (1..threads).map(|_| scope.spawn(helper)).collect();
        // The helpers already use the other cores: the derivation's own work sharing would only
        // share them too.
        crate::parallel::serially(work);
        let mut left: Vec<(usize, usize, usize)> = Vec::new();
        for (s, stage) in stages.iter().enumerate() {
            let r = ready[s].get_or_init(|| ready_from(stage()));
            left.extend(r.order.iter().map(|&i| (r.weights[i], s, i)));
        }
        // Heaviest first; equal weights by stage and item, so the schedule is reproducible.
        left.sort_by(|a, b| b.0.cmp(&a.0).then((a.1, a.2).cmp(&(b.1, b.2))));
        if all
            .set(left.into_iter().map(|(_, s, i)| (s, i)).collect())
            .is_err()
        {
            unreachable!("set once, here");
        }
        let mut done = Vec::new();
        from_all(&mut done);
        for h in helpers {
            done.extend(h.join().expect("a display thread does not panic"));
        }
        done
    });
    done.sort_by_key(|&(s, i, _)| (s, i));
    let mut out: Vec<Vec<R>> = stages.iter().map(|_| Vec::new()).collect();
    for (s, _, r) in done {
        out[s].push(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pipeline_prints_each_stage_in_order_once_its_inputs_exist() {
        // `work` fills two cells in turn; each stage waits for its cell, as a stage of a
        // derivation waits for the quantity it prints.
        let first: OnceLock<Vec<u64>> = OnceLock::new();
        let second: OnceLock<Vec<u64>> = OnceLock::new();
        let wait = |cell: &OnceLock<Vec<u64>>| loop {
            if let Some(v) = cell.get() {
                return v.clone();
            }
            std::thread::yield_now();
        };
        let stages: Vec<Stage<'_, u64, u64>> = vec![
            Box::new(|| (1, wait(&first))),
            Box::new(|| (2, wait(&second))),
        ];
        let work = || second.set((50..120).collect()).unwrap();
        let f = |c: &u64, n: &u64| c * 1000 + n * n % 97;
        let want: Vec<Vec<u64>> = vec![
            (0..50).map(|n| f(&1, &n)).collect(),
            (50..120).map(|n| f(&2, &n)).collect(),
        ];
        // The first stage is asked for before `work`: it must not wait for it.
        first.set((0..50).collect()).unwrap();
        let got = pipeline(work, &stages, |_| true, |&n| (n % 5) as usize, f);
        assert_eq!(got, want);
        // Not worth a helper: the same, on this thread.
        let (first, second) = (OnceLock::new(), OnceLock::new());
        first.set((0..50).collect::<Vec<u64>>()).unwrap();
        let stages: Vec<Stage<'_, u64, u64>> = vec![
            Box::new(|| (1, wait(&first))),
            Box::new(|| (2, wait(&second))),
        ];
        let work = || second.set((50..120).collect()).unwrap();
        assert_eq!(pipeline(work, &stages, |_| false, |_| 1, f), want);
    }
}
