//! Median wall time of `generate` for each (spec, n) given on the command line, on the
//! calling thread; prints one JSON object per line. Used by `bench/compare`.
//!
//! cargo run --release -p samplab --example throughput -- sobol.owen:1000000 poisson.fast:radius=0.002:100000

use std::time::Instant;

use samplab::{Seed, sampler};

fn main() {
    for arg in std::env::args().skip(1) {
        let (spec, n) = arg.rsplit_once(':').expect("arguments are SPEC:N");
        let n: usize = n.parse().expect("N is a whole number");
        let s = sampler::build(spec).unwrap_or_else(|e| panic!("{e}"));
        let mut times = Vec::new();
        let start = Instant::now();
        // at least 5 runs and 1 s, at most 50 runs
        while times.len() < 5 || (start.elapsed().as_secs_f64() < 1.0 && times.len() < 50) {
            let t = Instant::now();
            let p = s.generate(n, 2, Seed(times.len() as u64)).unwrap();
            times.push(t.elapsed().as_secs_f64());
            std::hint::black_box(p);
        }
        times.sort_by(f64::total_cmp);
        let median = times[times.len() / 2];
        println!(
            "{{\"spec\": \"{spec}\", \"n\": {n}, \"seconds\": {median:.6e}, \"points_per_second\": {:.4e}, \"runs\": {}}}",
            n as f64 / median,
            times.len()
        );
    }
}
