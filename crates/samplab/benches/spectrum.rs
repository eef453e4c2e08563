//! Spectrum statistics (periodogram and mean spectrum, tolerance 1e-9) on random sets at the
//! cells of the speed issue's goal table: 2 sets of 10^5 points at 256^2, 20 sets of 4096 at
//! 512^2, and 2 sets of 65536 at 128^2 (where the spreading is the whole cost).
//! `RAYON_NUM_THREADS=1 cargo bench -p samplab --bench spectrum`; against FINUFFT, side by
//! side: `bench/compare spectrum` (or `bench/compare goals`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use samplab::spectrum::{self, Method};
use samplab::{Seed, sampler};

fn statistics(c: &mut Criterion) {
    let mut g = c.benchmark_group("spectrum");
    g.sample_size(10);
    for (n, m, res) in [(100_000usize, 2usize, 256usize), (4096, 20, 512), (65536, 2, 128)] {
        let sets = sampler::generate_sets(&sampler::build("random").unwrap(), n, 2, Seed(1), m).unwrap();
        g.bench_with_input(BenchmarkId::new(format!("{m}x{n}"), res), &sets, |b, sets| {
            b.iter(|| spectrum::statistics(sets, res, Method::Fast { tol: 1e-9 }).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, statistics);
criterion_main!(benches);
