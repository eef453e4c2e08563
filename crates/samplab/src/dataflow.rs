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

use std::sync::atomic::{AtomicUsize, Ordering::AcqRel};

/// A list of tasks and what each waits for.
pub(crate) struct Graph {
    /// Per task, how many earlier tasks it waits for.
    waits: Vec<usize>,
    /// Per task, the later tasks that wait for it.
    next: Vec<Vec<usize>>,
    /// Per key, its latest owner so far.
    latest: Vec<Option<usize>>,
}

impl Graph {
    /// No task yet, over keys 0..keys.
    pub(crate) fn new(keys: usize) -> Graph {
        Graph { waits: Vec::new(), next: Vec::new(), latest: vec![None; keys] }
    }

    /// The next task: it waits for the latest owner so far of each key of `reads`, then owns
    /// each key of `owns` (which `reads` should hold too).
    pub(crate) fn push(&mut self, reads: impl IntoIterator<Item = usize>, owns: impl IntoIterator<Item = usize>) {
        let task = self.waits.len();
        let mut before: Vec<usize> = reads.into_iter().filter_map(|k| self.latest[k]).collect();
        before.sort_unstable();
        before.dedup();
        self.waits.push(before.len());
        for b in before {
            self.next[b].push(task);
        }
        self.next.push(Vec::new());
        for k in owns {
            self.latest[k] = Some(task);
        }
    }

    /// Run `task` on every task, each once, as soon as the tasks it waits for are done.
    pub(crate) fn run(self, task: impl Fn(usize) + Sync) {
        // the tasks that wait for none, listed before any runs: once one runs, it may bring
        // a later task's count to zero and start it itself, and a scan of the counts then
        // would start that task a second time
        let ready: Vec<usize> = (0..self.waits.len()).filter(|&t| self.waits[t] == 0).collect();
        let flow = Flow { waits: self.waits.into_iter().map(AtomicUsize::new).collect(), next: self.next, task };
        rayon::scope(|scope| {
            let flow = &flow;
            for t in ready {
                scope.spawn(move |scope| flow.run(scope, t));
            }
        });
    }
}

/// A graph being run.
struct Flow<F> {
    waits: Vec<AtomicUsize>,
    next: Vec<Vec<usize>>,
    task: F,
}

impl<F: Fn(usize) + Sync> Flow<F> {
    /// Task t, then the tasks it was the last to wait for (what it changed is seen by them:
    /// each count's decrements form one release sequence, which the last one acquires).
    fn run<'s>(&'s self, scope: &rayon::Scope<'s>, t: usize) {
        (self.task)(t);
        for &u in &self.next[t] {
            if self.waits[u].fetch_sub(1, AcqRel) == 1 {
                scope.spawn(move |scope| self.run(scope, u));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// Tasks on random keys, each appending its index to the log of every key it reads: on
    /// any pool, each key's log is the list's order of the tasks that read it, and every
    /// task ran once. (A scan of the counts while the first tasks already ran, CCVT's bug
    /// until 2026-11-28, started some tasks twice and logged them twice: many tasks ready at
    /// the start make the scan long enough to be overtaken.)
    #[test]
    fn tasks_that_share_a_key_run_in_the_list_order_and_each_runs_once() {
        let keys = 2000;
        let mut state = 12345u64;
        let mut draw = |below: usize| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 33) as usize % below
        };
        let tasks: Vec<Vec<usize>> = (0..20_000).map(|_| (0..1 + draw(3)).map(|_| draw(keys)).collect()).collect();
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
            let mut graph = Graph::new(keys);
            for ks in &tasks {
                graph.push(ks.iter().copied(), ks.iter().copied());
            }
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
}
