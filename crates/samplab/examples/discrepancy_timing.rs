//! Median wall time of a discrepancy metric on a fixed set: METRIC:N[:D[:SAMPLER]] arguments
//! (the sampler defaults to random);
//! one JSON object per line. Used by `bench/compare`.
//!
//! cargo run --release -p samplab --example discrepancy_timing -- star:100000 l2-star:1000000

use std::time::Instant;

use samplab::discrepancy::{self, Limits, Metric};
use samplab::{Seed, sampler};

fn main() {
    for arg in std::env::args().skip(1) {
        let mut parts = arg.split(':');
        let (name, n, d) = (parts.next().unwrap(), parts.next().unwrap(), parts.next().unwrap_or("2"));
        let spec = parts.next().unwrap_or("random");
        let (n, d): (usize, usize) = (n.parse().unwrap(), d.parse().unwrap());
        let metric = Metric::parse(name).unwrap_or_else(|e| panic!("{e}"));
        let set = sampler::build(spec).unwrap().generate(n, d, Seed(1)).unwrap();
        let limits = Limits { max_work: f64::INFINITY, ..Limits::default() };
        let mut times = Vec::new();
        let mut value = 0.0;
        let start = Instant::now();
        while times.len() < 3 || (start.elapsed().as_secs_f64() < 1.0 && times.len() < 20) {
            let t = Instant::now();
            value = discrepancy::compute(&metric, &set, limits).unwrap();
            times.push(t.elapsed().as_secs_f64());
        }
        times.sort_by(f64::total_cmp);
        println!(
            "{{\"metric\": \"{name}\", \"n\": {n}, \"dims\": {d}, \"seconds\": {:.6e}, \"value\": {value:.17e}, \"runs\": {}}}",
            times[times.len() / 2],
            times.len()
        );
    }
}
