//! Memory limits and stops (their own test binary: the memory limit is process-wide).

use std::sync::atomic::AtomicBool;

use samplab::memory::{available, set_limit, zeroed};
use samplab::progress::Progress;
use samplab::{Error, Seed, sampler};

#[test]
fn a_limit_refuses_before_allocating() {
    set_limit(Some(1 << 20));
    let e = zeroed::<f64>(|| "a test buffer".into(), 1 << 20).unwrap_err();
    assert_eq!(e.to_string(), "a test buffer needs 8.0 MiB of memory, over the 1.0 MiB available");
    assert_eq!(zeroed::<f64>(|| "small".into(), 1000).unwrap().len(), 1000);
    // realizations that do not fit are refused whole, in one line, before any is made
    let random = sampler::build("random").unwrap();
    let plan = random.plan(1 << 14, 2).unwrap();
    let e = plan.generate_sets(Seed(1), 8, &Progress::new(&|_| panic!("no set may start"))).unwrap_err();
    assert_eq!(e.to_string(), "8 sets of 16384 2D points needs 2.0 MiB of memory, over the 1.0 MiB available");
    assert!(matches!(plan.stack(Seed(1), 0..8, &Progress::SILENT), Err(Error::Memory { .. })));
    // a count whose buffer overflows the address space is the same one-line error
    assert!(matches!(plan.stack(Seed(1), 0..u64::MAX, &Progress::SILENT), Err(Error::Memory { .. })));
    set_limit(None);
    assert!(available() > 1 << 20);
}

#[test]
fn stacked_sets_are_the_sets_and_a_raised_flag_stops_them() {
    let sobol = sampler::build("sobol.owen").unwrap();
    let plan = sobol.plan(64, 3).unwrap();
    let sets = plan.generate_sets(Seed(9), 5, &Progress::SILENT).unwrap();
    let stack = plan.stack(Seed(9), 0..5, &Progress::SILENT).unwrap();
    assert_eq!(stack, sets.iter().flat_map(|s| s.as_slice().to_vec()).collect::<Vec<_>>());
    // a range of sets is the same sets
    let tail = plan.stack(Seed(9), 2..5, &Progress::SILENT).unwrap();
    assert_eq!(tail, sets[2..].iter().flat_map(|s| s.as_slice().to_vec()).collect::<Vec<_>>());
    let stop = AtomicBool::new(true);
    let stopped = Progress::until(&stop);
    assert_eq!(plan.generate_sets(Seed(9), 5, &stopped), Err(Error::Interrupted));
    assert_eq!(plan.stack(Seed(9), 0..5, &stopped), Err(Error::Interrupted));
}
