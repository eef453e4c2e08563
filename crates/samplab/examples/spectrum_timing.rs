//! Spectrum statistics timed: with no arguments, the direct DFT against the fast path
//! (tolerance 1e-9) on the two configurations; with arguments `N:SETS:RES ...`,
//! the fast path alone on random sets (one JSON object per line; `bench/compare spectrum`
//! runs FINUFFT on the same points beside it). Seeds: Seed(1) for every set list.

use std::time::Instant;

use samplab::spectrum::{self, Method};
use samplab::{PointSet, Seed, sampler};

fn sets(spec: &str, n: usize, m: usize) -> Vec<PointSet> {
    sampler::generate_sets(&sampler::build(spec).unwrap(), n, 2, Seed(1), m).unwrap()
}

fn main() {
    let cells: Vec<(usize, usize, usize)> = std::env::args()
        .skip(1)
        .map(|a| {
            let v: Vec<usize> = a.split(':').map(|x| x.parse().expect("N:SETS:RES")).collect();
            (v[0], v[1], v[2])
        })
        .collect();
    if !cells.is_empty() {
        for (n, m, res) in cells {
            let sets = sets("random", n, m);
            let mut times: Vec<f64> = (0..3)
                .map(|_| {
                    let t = Instant::now();
                    spectrum::statistics(&sets, res, Method::Fast { tol: 1e-9 }).unwrap();
                    t.elapsed().as_secs_f64()
                })
                .collect();
            times.sort_by(f64::total_cmp);
            println!("{{\"n\": {n}, \"sets\": {m}, \"res\": {res}, \"fast_seconds\": {:.5}}}", times[1]);
        }
        return;
    }
    for (n, m, res) in [(4096usize, 20usize, 512usize), (100_000, 2, 256)] {
        let sets = if n == 4096 { sets("jitter", n, m) } else { sets("random", n, m) };
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
