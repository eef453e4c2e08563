//! Direct DFT against the fast path (tolerance 1e-9) on the benchmark
//! configurations; one JSON object per line. Used by `bench/compare`.

use std::time::Instant;

use samplab::spectrum::{self, Method};
use samplab::{Seed, sampler};

fn main() {
    for (n, m, res) in [(4096usize, 20usize, 512usize), (100_000, 2, 256)] {
        let sets =
            sampler::generate_sets(sampler::build("jitter").unwrap().as_ref(), n, 2, Seed(1), m).unwrap_or_else(|_| {
                sampler::generate_sets(sampler::build("random").unwrap().as_ref(), n, 2, Seed(1), m).unwrap()
            });
        let time = |method| {
            let t = Instant::now();
            let st = spectrum::statistics(&sets, res, method).unwrap();
            (t.elapsed().as_secs_f64(), st)
        };
        let (fast_s, fast) = time(Method::Fast { tol: 1e-9 });
        let (direct_s, direct) = time(Method::Direct);
        let err = fast.periodogram.iter().zip(&direct.periodogram).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
        println!(
            "{{\"n\": {n}, \"sets\": {m}, \"res\": {res}, \"direct_seconds\": {direct_s:.4}, \"fast_seconds\": {fast_s:.4}, \"ratio\": {:.1}, \"max_periodogram_error\": {err:.2e}}}",
            direct_s / fast_s
        );
    }
}
