//! Random-access draws per second of the pixel samplers on the calling thread, beside
//! `openqmc-rs`'s samplers drawn the same way: 4D draws over 2^16 pixels (256 x 256) x 64
//! dimensions (16 draws per pixel) at one sample index per run, the index changing from
//! run to run; every draw starts from its keys (an OpenQMC draw is
//! `Sampler::new(x, y, frame, index).new_domain(block).draw_sample::<4>()`, generic code, a
//! samplab draw `sample4(pixel, frame, index, dim)` in code generic over the family through
//! `Pixels::visit`, and again through `Pixels::sample4`, "dispatched"); the medians of at
//! least 7 rounds and 2 s, samplab and OpenQMC run in alternation. Prints one JSON object
//! per line.
//! Used by `bench/compare pixels`.
//!
//! cargo run --release -p samplab --example pixel_throughput [FAMILY...]

use std::hint::black_box;
use std::time::Instant;

use openqmc::{LatticeSampler, PmjSampler, Sampler, SamplerImpl, SobolSampler};
use samplab::Seed;
use samplab::pixel::{Film, PIXEL_SAMPLERS, PixelSampler, Visit, prepare};

const SIDE: u32 = 256;
const DIMS: u32 = 64;
const SPP: u32 = 16;

/// The median seconds of `a(index)` and of `b(index)` (when given), run in alternation so
/// that the machine's noise falls on both alike, over at least 7 rounds and 2 s (at most
/// 60 rounds).
fn medians(a: impl Fn(u32) -> f64, b: Option<fn(u32) -> f64>) -> (f64, Option<f64>) {
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    let start = Instant::now();
    while ta.len() < 7 || (start.elapsed().as_secs_f64() < 2.0 && ta.len() < 60) {
        let index = ta.len() as u32 % SPP;
        let t = Instant::now();
        black_box(a(index));
        ta.push(t.elapsed().as_secs_f64());
        if let Some(b) = b {
            let t = Instant::now();
            black_box(b(index));
            tb.push(t.elapsed().as_secs_f64());
        }
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    (median(ta), (!tb.is_empty()).then(|| median(tb)))
}

/// One run of samplab's draws, compiled for the family it visits ([`Pixels::visit`]): what a
/// renderer generic over [`PixelSampler`] does.
struct Draws {
    index: u32,
}

impl Visit for Draws {
    type Output = f64;
    fn visit<S: PixelSampler>(self, s: &S) -> f64 {
        let mut sum = 0.0;
        for y in 0..SIDE {
            for x in 0..SIDE {
                for d in (0..DIMS).step_by(4) {
                    // black_box keeps the pixel's keys from being hoisted out of the loop, as
                    // for OpenQMC below
                    sum += s.sample4([black_box(x), y], 0, self.index, d).iter().sum::<f64>();
                }
            }
        }
        sum
    }
}

/// A samplab family, the OpenQMC sampler it is compared with, and that sampler's run.
type Peer = (&'static str, &'static str, fn(u32) -> f64);

fn openqmc<T: SamplerImpl>(index: u32) -> f64 {
    let mut sum = 0.0;
    for y in 0..SIDE as i32 {
        for x in 0..SIDE as i32 {
            for block in 0..(DIMS / 4) as i32 {
                // random access: every draw starts from its keys, as samplab's do (black_box
                // keeps the compiler from hoisting the pixel's state out of this loop)
                let v = Sampler::<T>::new(black_box(x), y, 0, index as i32).new_domain(block).draw_sample::<4>();
                sum += v.iter().map(|&u| f64::from(u) * (1.0 / 4_294_967_296.0)).sum::<f64>();
            }
        }
    }
    sum
}

fn main() {
    let draws = f64::from(SIDE * SIDE * DIMS / 4);
    let film = Film { width: SIDE, height: SIDE, spp: SPP, dims: DIMS };
    let peers: [Peer; 3] = [
        ("sobol", "SobolSampler", openqmc::<<SobolSampler as Imp>::T>),
        ("pmj02", "PmjSampler", openqmc::<<PmjSampler as Imp>::T>),
        ("lattice", "LatticeSampler", openqmc::<<LatticeSampler as Imp>::T>),
    ];
    // the families named on the command line, or all
    let only: Vec<String> = std::env::args().skip(1).collect();
    for e in PIXEL_SAMPLERS.iter().filter(|e| only.is_empty() || only.iter().any(|o| o == e.about.name)) {
        let p = prepare(e.about.name, film, Seed(1)).unwrap_or_else(|e| panic!("{e}"));
        let ours = |index| p.visit(Draws { index });
        let dispatched = |index| {
            let mut sum = 0.0;
            for y in 0..SIDE {
                for x in 0..SIDE {
                    for d in (0..DIMS).step_by(4) {
                        sum += p.sample4([black_box(x), y], 0, index, d).iter().sum::<f64>();
                    }
                }
            }
            sum
        };
        let peer = peers.iter().find(|(name, ..)| *name == e.about.name);
        let (ours, theirs) = medians(ours, peer.map(|&(_, _, run)| run));
        let (dispatched, _) = medians(dispatched, None);
        let versus = peer.zip(theirs).map_or(String::new(), |((_, name, _), t)| {
            format!(
                ", \"openqmc\": \"{name}\", \"openqmc_draws_per_second\": {:.4e}, \"ratio\": {:.3}",
                draws / t,
                t / ours
            )
        });
        println!(
            "{{\"spec\": \"{}\", \"draws_per_second\": {:.4e}, \"values_per_second\": {:.4e}, \"dispatched_draws_per_second\": {:.4e}{versus}}}",
            p.spec(),
            draws / ours,
            4.0 * draws / ours,
            draws / dispatched
        );
    }
}

/// The implementation type of an OpenQMC sampler alias.
trait Imp {
    type T: SamplerImpl;
}
impl<T: SamplerImpl> Imp for Sampler<T> {
    type T = T;
}
