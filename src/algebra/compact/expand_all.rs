//! Many quantities of a [`Compact`] expanded at once, on several threads, with no size budget:
//! the expanded `D(q)` of a large robot from its composite bodies, whose entries share the names
//! of the composite inertias and of the forces moved down the chain.
//!
//! The names the quantities need ([`Compact::live`]) form a graph in which every name refers to
//! earlier ones only. Each thread takes, in order, the first name no thread has taken whose names
//! are all expanded, expands it ([`Compact::substituted`]) and gives its value to every thread;
//! the quantities come last, each the same way. So each name is expanded once, whichever thread
//! gets to it, and a thread waits only when every name left needs one another thread is
//! expanding. The values are those of an [`super::Expander`] with no budget, on any number of
//! threads: each is a function of the values of its names alone, in the canonical form.
//!
//! Measured on the Franka Panda (7 joints, numeric; 130 names and entries, 1.5 ms of expanding on
//! one thread, 0.35 ms of it the longest chain of names): its `D` expanded in 2.0–2.3 ms before,
//! by one expander on one thread while the other idled (nothing of a document starts before `D`),
//! and in 1.0–1.3 ms so, both threads expanding about equal shares; the whole `derive --format
//! json` 1–2 ms faster, the numeric PUMA 560's `derive` 0.6 ms (interleaved runs).

use super::Compact;
use crate::algebra::poly::Poly;
use crate::parallel::{self, Waiting};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::OnceLock;

/// The estimated work of expanding a definition or quantity, per term of its compact value, in the
/// units of [`parallel::share`] (about 3 ns): its terms multiply out the values of its names.
const WORK_PER_TERM: usize = 1000;

/// What [`Compact::expand_all`] computes: the live names, then the quantities, each a node whose
/// value is a function of earlier nodes' values.
struct Graph<'a> {
    /// Each node's compact value (a definition's, or a quantity).
    values: Vec<&'a Poly>,
    /// Each node's names, as the indices of earlier nodes.
    needs: Vec<Vec<usize>>,
    /// The node of each live definition, by definition index.
    node_of: Vec<usize>,
    /// Each node's expanded value, once expanded.
    done: Vec<OnceLock<Poly>>,
    /// Whether a thread took each node.
    taken: Vec<AtomicBool>,
    /// Every node before this one is taken.
    first_open: AtomicUsize,
    /// Set when a thread panicked expanding a node: the others stop rather than wait for it.
    failed: AtomicBool,
}

impl Compact {
    /// The expanded forms of `outputs`, in their order: what an [`super::Expander`] with no
    /// budget gives for each, computed on up to [`parallel::threads`] threads when the work is
    /// worth sharing (see the module's doc).
    pub fn expand_all(&self, outputs: &[&Poly]) -> Vec<Poly> {
        let live = self.live(outputs.iter().copied());
        let mut node_of = vec![usize::MAX; self.defs.len()];
        for (node, &k) in live.iter().enumerate() {
            node_of[k] = node;
        }
        let values: Vec<&Poly> = live
            .iter()
            .map(|&k| &self.defs[k].value)
            .chain(outputs.iter().copied())
            .collect();
        let needs = values
            .iter()
            .map(|p| self.names_in(p).into_iter().map(|k| node_of[k]).collect())
            .collect();
        let work = values.iter().map(|p| p.len()).sum::<usize>() * WORK_PER_TERM;
        let graph = Graph {
            needs,
            node_of,
            done: values.iter().map(|_| OnceLock::new()).collect(),
            taken: values.iter().map(|_| AtomicBool::new(false)).collect(),
            first_open: AtomicUsize::new(0),
            failed: AtomicBool::new(false),
            values,
        };
        parallel::share(work, parallel::WORTH_SHARING, || graph.expand(self));
        let quantities = graph.done.into_iter().skip(live.len());
        quantities
            .map(|v| v.into_inner().expect("every node is expanded"))
            .collect()
    }
}

impl Graph<'_> {
    /// Expands nodes on this thread until every node is taken, waiting ([`Waiting`]) only when
    /// each node not taken needs one not expanded yet; stops when another thread panicked (its
    /// panic reaches the caller of [`parallel::share`]).
    fn expand(&self, arena: &Compact) {
        let mut waiting = Waiting::new();
        loop {
            let first = self.first_open.load(Ordering::Acquire);
            if first == self.values.len() {
                return;
            }
            match (first..self.values.len()).find(|&i| self.ready(i) && self.claim(i)) {
                Some(i) => {
                    let value = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        arena.substituted(self.values[i], |k| {
                            self.done[self.node_of[k]]
                                .get()
                                .expect("a node's names are expanded before it")
                        })
                    }));
                    match value {
                        Ok(value) => {
                            let _ = self.done[i].set(value);
                        }
                        Err(panic) => {
                            self.failed.store(true, Ordering::Release);
                            std::panic::resume_unwind(panic);
                        }
                    }
                    waiting = Waiting::new();
                }
                None if self.failed.load(Ordering::Acquire) => return,
                None => waiting.pause(),
            }
        }
    }

    /// Whether node `i` is open (not taken) and its names are all expanded.
    fn ready(&self, i: usize) -> bool {
        !self.taken[i].load(Ordering::Acquire)
            && self.needs[i].iter().all(|&j| self.done[j].get().is_some())
    }

    /// Takes node `i` for this thread, if no other thread did; moves `first_open` past the nodes
    /// taken in a row from it.
    fn claim(&self, i: usize) -> bool {
        if self.taken[i].swap(true, Ordering::AcqRel) {
            return false;
        }
        let mut first = self.first_open.load(Ordering::Acquire);
        while first < self.values.len() && self.taken[first].load(Ordering::Acquire) {
            match self.first_open.compare_exchange(
                first,
                first + 1,
                Ordering::AcqRel,
                Ordering::Acquire,
            ) {
                Ok(_) => first += 1,
                Err(now) => first = now,
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::algebra::to_poly;

    fn p(s: &str) -> Poly {
        to_poly(&crate::parse::parse_expr(s).expect("valid expression"))
    }

    /// Quantities over a graph of names (two chains of names that meet, each name used by later
    /// ones and by several quantities, powers and negatives among them) expanded all at once are
    /// what an unbounded [`super::super::Expander`] gives each, on the threads the machine has
    /// (the work passes [`parallel::WORTH_SHARING`], so two cores share it) and on one.
    #[test]
    fn all_at_once_is_each_by_the_expander() {
        let mut arena = Compact::new();
        let mut left = p("x1 + y1");
        let mut right = p("c1 - s1");
        let mut outputs = Vec::new();
        for k in 2..=7 {
            let a = p(&format!("x{k} + {k}*y{} ", k % 3 + 1));
            let b = p(&format!("cos(q{}) + s{k}", k % 4 + 1));
            left = arena.name(left.mul(&a).add(&right), "l");
            right = arena.name(right.mul(&b).sub(&Poly::int(k)), "r");
            outputs.push(left.mul(&right));
            outputs.push(left.pow(2).sub(&right));
            outputs.push(right.neg());
            outputs.push(a.mul(&b).mul(&left).add(&a.mul(&right)));
        }
        outputs.push(Poly::zero());
        outputs.push(p("m1*g"));
        let refs: Vec<&Poly> = outputs.iter().collect();
        let mut expander = arena.expander(usize::MAX);
        let each: Vec<Poly> = refs
            .iter()
            .map(|q| expander.expand(q).expect("no budget"))
            .collect();
        let work: usize = arena
            .live(refs.iter().copied())
            .iter()
            .map(|&k| arena.defs[k].value.len())
            .chain(refs.iter().map(|q| q.len()))
            .sum::<usize>()
            * WORK_PER_TERM;
        assert!(work >= parallel::WORTH_SHARING, "work {work}");
        assert_eq!(arena.expand_all(&refs), each);
        assert_eq!(parallel::serially(|| arena.expand_all(&refs)), each);
        assert!(each.iter().map(Poly::len).max() > Some(100));
    }
}
