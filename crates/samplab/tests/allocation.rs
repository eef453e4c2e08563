//! A plan owns its prepared state, so filling a set allocates nothing for the samplers that
//! build no per-seed tables (its own test binary: the counting allocator is process-wide).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use samplab::Seed;
use samplab::sampler::{self, SAMPLERS};

/// The system allocator, counting the allocations made on each thread.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|a| a.set(a.get() + 1));
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|a| a.set(a.get() + 1));
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static COUNTING: Counting = Counting;

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

/// Whether the entry's fill in `dims` dimensions still builds per-seed tables on the heap
/// (and why). The test also fails when one of them stops allocating, so this only shrinks.
fn per_seed_tables(name: &str, dims: usize) -> bool {
    // a permuted digit table per base and seed (the permutations are the randomization);
    // Owen's nested scramble in a prime base tabulates its first digits per seed
    let radical = matches!(name, "halton.xor" | "hammersley.xor" | "halton.owen" | "hammersley.owen");
    // the digital nets in an odd prime base (Faure's base is the least prime >= d) build
    // their columns and digit states per seed; base 2 walks them on the stack
    let prime_net = name.starts_with("faure") && dims > 2;
    radical || prime_net
}

/// The samplers that make their sets by search or optimization (dart throwing, elimination,
/// relaxation, permutation searches): their working memory is the algorithm's.
const SEARCHING: &[&str] = &[
    "nrooks",
    "lhs.centered",
    "lhs.oa",
    "poisson",
    "poisson.fast",
    "poisson.maximal",
    "elimination",
    "elimination.tiled",
    "lloyd",
    "ccvt",
    "sot",
    "gbn",
    "kdm",
    "step",
    "single-peak",
    "pmj02",
    "cmj",
    "force-matrix",
    "micro-jitter",
];

#[test]
fn fills_allocate_nothing_once_planned() {
    let (mut checked, mut wrong) = (0, Vec::new());
    for entry in SAMPLERS.iter() {
        let name = entry.about.name;
        if SEARCHING.contains(&name) {
            continue;
        }
        // a saved set's file is a parameter it requires
        let spec = match name {
            "file" => concat!("file:path=", env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/saved16.txt").into(),
            name => name.to_string(),
        };
        let s = sampler::build(&spec).unwrap();
        // two and five dimensions (the few-dimension paths and the general one), at the
        // first count from 16 on that each makes
        for dims in [2, 5] {
            if !s.dims().contains(&dims) {
                continue;
            }
            let Some(plan) = (16..=4096).find_map(|n| s.plan(n, dims).ok()) else {
                panic!("{name}: no count plans in {dims}D");
            };
            let mut out = vec![0.0; plan.n() * dims];
            let before = allocations();
            plan.fill(Seed(3), &mut out).unwrap();
            let made = allocations() - before;
            let expected_free = !per_seed_tables(name, dims);
            if (made == 0) != expected_free {
                wrong.push(format!("{name} in {dims}D: {made} allocations in one fill"));
            }
            checked += 1;
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // the registry's sequences, lattices, grids and random were all reached
    assert!(checked >= 30, "{checked}");
}
