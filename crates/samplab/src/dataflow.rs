//! Tasks run on rayon's pool as soon as the tasks they wait for are done, with no barrier:
//! the schedule of the constructions whose steps must meet each other in one fixed order
//! while steps that share nothing run together (CCVT's swaps, the tiled elimination's turns).
//!
//! The tasks are listed in the order of the serial definition, each with the keys (sites,
//! tiles) it reads and those it owns: a task waits for the latest earlier owner of each key
//! it reads, then owns its own keys. Two tasks that share a key therefore run in the order
//! of the list, so a run gives the serial definition's result whatever the threads, as long
//! as every key a task changes is one it owns, or is owned by every task that reads it later
//! and also reads one of this task's own keys (the tiles' turns: adjacency is symmetric).

use std::sync::atomic::{
    AtomicUsize,
    Ordering::{AcqRel, Relaxed},
};

use rayon::prelude::*;

/// A list of tasks and what each waits for.
pub(crate) struct Graph {
    /// Per task, how many earlier tasks it waits for.
    waits: Vec<AtomicUsize>,
    /// The later tasks that wait for task t: `next[first[t]..first[t + 1]]`, increasing.
    first: Vec<usize>,
    next: Vec<usize>,
}

impl Graph {
    /// Tasks 0..tasks over keys 0..keys: task t waits for the latest earlier owner of each
    /// key of `reads(t)`, then owns each key of `owns(t)` (which `reads(t)` should hold
    /// too). Each key's owners are listed in task order, and each task finds the latest
    /// before it by bisection, the tasks in parallel; the lists themselves are counting
    /// sorts, linear in the keys and tasks.
    pub(crate) fn new<R, O>(
        keys: usize,
        tasks: usize,
        reads: impl Fn(usize) -> R + Sync,
        owns: impl Fn(usize) -> O + Sync,
    ) -> Graph
    where
        R: IntoIterator<Item = usize>,
        O: IntoIterator<Item = usize>,
    {
        let (by_key, owners) = lists(keys, || (0..tasks).flat_map(|t| owns(t).into_iter().map(move |k| (k, t))));
        // per task, the latest owner before it of each key it reads, once each
        let before: Vec<Vec<usize>> = (0..tasks)
            .into_par_iter()
            .map(|t| {
                let mut before: Vec<usize> = reads(t)
                    .into_iter()
                    .filter_map(|k| {
                        let owners = &owners[by_key[k]..by_key[k + 1]];
                        owners[..owners.partition_point(|&u| u < t)].last().copied()
                    })
                    .collect();
                before.sort_unstable();
                before.dedup();
                before
            })
            .collect();
        let (first, next) =
            lists(tasks, || before.iter().enumerate().flat_map(|(t, b)| b.iter().map(move |&u| (u, t))));
        Graph { waits: before.iter().map(|b| AtomicUsize::new(b.len())).collect(), first, next }
    }

    /// Run `task` on every task, each once, as soon as the tasks it waits for are done.
    pub(crate) fn run(self, task: impl Fn(usize) + Sync) {
        // the tasks that wait for none, listed before any runs: once one runs, it may bring
        // a later task's count to zero and start it itself, and a scan of the counts then
        // would start that task a second time
        let ready: Vec<usize> = (0..self.waits.len()).filter(|&t| self.waits[t].load(Relaxed) == 0).collect();
        let flow = Flow { graph: self, task };
        rayon::scope(|scope| {
            let flow = &flow;
            for t in ready {
                scope.spawn(move |scope| flow.run(scope, t));
            }
        });
    }
}

/// The values of `pairs()`'s (list, value) pairs, list by list, each list's in the order
/// given, and where each list starts (a counting sort over `count` lists; `pairs` is
/// called twice).
fn lists<I: Iterator<Item = (usize, usize)>>(count: usize, pairs: impl Fn() -> I) -> (Vec<usize>, Vec<usize>) {
    let mut first = vec![0; count + 1];
    for (list, _) in pairs() {
        first[list + 1] += 1;
    }
    for l in 0..count {
        first[l + 1] += first[l];
    }
    let mut at = first.clone();
    let mut values = vec![0; first[count]];
    for (list, value) in pairs() {
        values[at[list]] = value;
        at[list] += 1;
    }
    (first, values)
}

/// A graph being run.
struct Flow<F> {
    graph: Graph,
    task: F,
}

impl<F: Fn(usize) + Sync> Flow<F> {
    /// Task t, then the tasks it was the last to wait for (what it changed is seen by them:
    /// each count's decrements form one release sequence, which the last one acquires).
    fn run<'s>(&'s self, scope: &rayon::Scope<'s>, t: usize) {
        (self.task)(t);
        let graph = &self.graph;
        for &u in &graph.next[graph.first[t]..graph.first[t + 1]] {
            if graph.waits[u].fetch_sub(1, AcqRel) == 1 {
                scope.spawn(move |scope| self.run(scope, u));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// `tasks` lists of 1 to `most` keys below `keys`, drawn from a fixed LCG stream.
    fn random_tasks(tasks: usize, keys: usize, most: usize, mut state: u64) -> Vec<Vec<usize>> {
        let mut draw = |below: usize| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 33) as usize % below
        };
        (0..tasks).map(|_| (0..1 + draw(most)).map(|_| draw(keys)).collect()).collect()
    }

    /// Tasks on random keys, each appending its index to the log of every key it reads: on
    /// any pool, each key's log is the list's order of the tasks that read it, and every
    /// task ran once. (A scan of the counts while the first tasks already ran, CCVT's bug
    /// until 2026-11-28, started some tasks twice and logged them twice: many tasks ready at
    /// the start make the scan long enough to be overtaken.)
    #[test]
    fn tasks_that_share_a_key_run_in_the_list_order_and_each_runs_once() {
        let keys = 2000;
        let tasks = random_tasks(20_000, keys, 3, 12345);
        let mut expected = vec![Vec::new(); keys];
        for (t, ks) in tasks.iter().enumerate() {
            let mut ks = ks.clone();
            ks.sort_unstable();
            ks.dedup();
            for k in ks {
                expected[k].push(t);
            }
        }
        // a race detector: the scan's bug was caught in about one run of three at 16 threads
        for threads in [1, 2, 2, 2, 16, 16, 16, 16, 16, 16, 16, 16] {
            let graph = Graph::new(keys, tasks.len(), |t| tasks[t].iter().copied(), |t| tasks[t].iter().copied());
            let logs: Vec<Mutex<Vec<usize>>> = (0..keys).map(|_| Mutex::new(Vec::new())).collect();
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| {
                graph.run(|t| {
                    let mut ks = tasks[t].clone();
                    ks.sort_unstable();
                    ks.dedup();
                    for k in ks {
                        logs[k].lock().unwrap().push(t);
                    }
                })
            });
            let logs: Vec<Vec<usize>> = logs.into_iter().map(|l| l.into_inner().unwrap()).collect();
            assert_eq!(logs, expected, "{threads} threads");
        }
    }

    /// The graph built in parallel is the serial definition's: task by task, each waiting
    /// for the latest earlier owner of each key it reads, then owning its own keys. Each
    /// task owns one key of those it reads (the tiled elimination's turns own their tile and
    /// read its neighbours').
    #[test]
    fn the_graph_is_the_serial_definitions_on_any_pool() {
        let keys = 500;
        let tasks = random_tasks(5000, keys, 4, 987);
        // the serial definition: the latest owner so far of each key
        let mut latest: Vec<Option<usize>> = vec![None; keys];
        let mut next = vec![Vec::new(); tasks.len()];
        let mut waits = Vec::new();
        for (t, ks) in tasks.iter().enumerate() {
            let mut before: Vec<usize> = ks.iter().filter_map(|&k| latest[k]).collect();
            before.sort_unstable();
            before.dedup();
            waits.push(before.len());
            for b in before {
                next[b].push(t);
            }
            latest[ks[0]] = Some(t);
        }
        for threads in [1, 2, 16] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let graph = pool.install(|| Graph::new(keys, tasks.len(), |t| tasks[t].iter().copied(), |t| [tasks[t][0]]));
            let got: Vec<usize> = graph.waits.iter().map(|w| w.load(Relaxed)).collect();
            assert_eq!(got, waits, "{threads} threads");
            for (t, expected) in next.iter().enumerate() {
                assert_eq!(
                    &graph.next[graph.first[t]..graph.first[t + 1]],
                    expected.as_slice(),
                    "task {t}, {threads} threads"
                );
            }
        }
    }
}
