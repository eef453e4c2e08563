//! Median wall time of the fast CBC construction for n = 2^16, s = 32 (the target:
//! under 1 s), and of the embedded construction for 2^20 points; one thread.
//!
//! cargo run --release -p samplab --example cbc_timing

use std::time::Instant;

fn main() {
    for (n, s, embedded) in [(1usize << 16, 32usize, false), (65521, 32, false), (1 << 20, 32, true)] {
        let mut times: Vec<f64> = (0..5)
            .map(|_| {
                let t = Instant::now();
                std::hint::black_box(
                    samplab::construct::cbc::construct(n, s, samplab::construct::cbc::Weights::decaying(2.0), embedded)
                        .unwrap(),
                );
                t.elapsed().as_secs_f64()
            })
            .collect();
        times.sort_by(f64::total_cmp);
        println!("{{\"n\": {n}, \"s\": {s}, \"embedded\": {embedded}, \"seconds\": {:.4}}}", times[2]);
    }
}
