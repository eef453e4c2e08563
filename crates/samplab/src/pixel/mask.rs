//! Blue-noise masks by the void-and-cluster method (Ulichney 1993): tileable (the torus),
//! any size from 4 to 256, one to four independent values per pixel.
//!
//! Each channel ranks the pixels of a `size` x `size` torus: a random initial pattern of
//! about a tenth of the pixels is relaxed (the tightest cluster, the one with the highest
//! Gaussian energy, moves to the largest void, the empty pixel with the lowest, until the
//! move would undo itself); its pixels are ranked down by removing tightest clusters one
//! by one, the rest up by filling the largest void one by one. (Ulichney's third phase,
//! the tightest cluster of the empty pixels, picks the same pixel as the largest void: on
//! the torus the energies of the full and of the empty pixels add up to the same
//! constant everywhere.) Rank r becomes the value (r + 1/2) / size^2.
//!
//! The energy filter is Ulichney's Gaussian of standard deviation 1.5 pixels, truncated at
//! a window of 11 x 11 (its weight beyond is below 1e-5 of the centre's). Each row keeps
//! its tightest cluster and largest void, and a pixel set or cleared changes the energy of
//! 11 rows only, so each of the size^2 steps rescans 11 rows and then compares the rows'
//! candidates: O(size^3) in all, where a scan of every pixel per step was O(size^4)
//! (the same pixels: rows in order, the first on ties, as one scan in index order).

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::seed::Seed;

/// The largest mask side.
pub const MAX_SIZE: usize = 256;

/// The filter's standard deviation, in pixels (Ulichney 1993).
const SIGMA: f64 = 1.5;

/// The filter's half width.
const RADIUS: usize = 5;

/// A blue-noise mask: `channels` values in (0, 1) per pixel of a `size` x `size` torus.
#[derive(Debug, Clone, PartialEq)]
pub struct Mask {
    size: usize,
    channels: usize,
    /// Value of channel c at (x, y): `values[(y * size + x) * channels + c]`.
    values: Vec<f64>,
}

impl Mask {
    /// Make a mask of `size` x `size` pixels with `channels` independent channels; channel
    /// c is seeded by `seed.derive(c)`.
    ///
    /// # Errors
    /// [`Error::Setting`] for a size outside 4..=[`MAX_SIZE`] or channels outside 1..=4.
    pub fn void_and_cluster(size: usize, channels: usize, seed: Seed) -> Result<Mask> {
        if !(4..=MAX_SIZE).contains(&size) {
            return Err(Error::Setting {
                name: "size",
                value: size.to_string(),
                reason: format!("a mask side is 4 to {MAX_SIZE} pixels"),
            });
        }
        if !(1..=4).contains(&channels) {
            return Err(Error::Setting {
                name: "channels",
                value: channels.to_string(),
                reason: "1 to 4 values per pixel".into(),
            });
        }
        let n = size * size;
        // the channels are independent: side by side
        let ranks: Vec<Vec<u32>> = (0..channels).into_par_iter().map(|c| ranks(size, seed.derive(c as u64))).collect();
        let mut values = vec![0.0; n * channels];
        for (c, r) in ranks.iter().enumerate() {
            for (p, &rank) in r.iter().enumerate() {
                values[p * channels + c] = (f64::from(rank) + 0.5) / n as f64;
            }
        }
        Ok(Mask { size, channels, values })
    }

    /// The side in pixels.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Values per pixel.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// Channel `c` at pixel (x, y), read on the torus (x and y taken modulo the size).
    #[inline]
    pub fn value(&self, x: u32, y: u32, c: usize) -> f64 {
        let (x, y) = (x as usize % self.size, y as usize % self.size);
        self.values[(y * self.size + x) * self.channels + c]
    }

    /// Every value, row-major, channels last: shape (size, size, channels).
    pub fn values(&self) -> &[f64] {
        &self.values
    }
}

/// The energy of every pixel of a torus under the Gaussian filter, kept as pixels are
/// set and cleared.
#[derive(Clone)]
struct Energy {
    size: usize,
    /// The filter's half width and its (2 half + 1)^2 weights, row by row.
    half: usize,
    kernel: Vec<f64>,
    energy: Vec<f64>,
    on: Vec<bool>,
    /// Per row, its set pixel of highest energy and its empty pixel of lowest (the first
    /// on ties; `NONE` when it has none).
    rows: Vec<[usize; 2]>,
}

/// No pixel.
const NONE: usize = usize::MAX;

/// The candidates a row keeps: its tightest cluster (a set pixel) and its largest void (an
/// empty one).
const CLUSTER: usize = 0;
const VOID: usize = 1;

/// Whether energy a beats b for the candidates `k`: a cluster by being higher, a void by
/// being lower.
fn beats(k: usize, a: f64, b: f64) -> bool {
    if k == CLUSTER { a > b } else { a < b }
}

impl Energy {
    fn new(size: usize) -> Energy {
        let half = RADIUS.min((size - 1) / 2);
        let (r, w) = (half as isize, 2 * half + 1);
        let kernel = (0..w * w)
            .map(|k| {
                let (dx, dy) = ((k % w) as isize - r, (k / w) as isize - r);
                (-((dx * dx + dy * dy) as f64) / (2.0 * SIGMA * SIGMA)).exp()
            })
            .collect();
        let mut e = Energy {
            size,
            half,
            kernel,
            energy: vec![0.0; size * size],
            on: vec![false; size * size],
            rows: vec![[NONE; 2]; size],
        };
        (0..size).for_each(|y| e.rescan(y));
        e
    }

    /// Row y's tightest cluster and largest void.
    fn rescan(&mut self, y: usize) {
        let mut best = [NONE; 2];
        for p in y * self.size..(y + 1) * self.size {
            let k = if self.on[p] { CLUSTER } else { VOID };
            if best[k] == NONE || beats(k, self.energy[p], self.energy[best[k]]) {
                best[k] = p;
            }
        }
        self.rows[y] = best;
    }

    fn toggle(&mut self, p: usize, on: bool) {
        self.on[p] = on;
        let sign = if on { 1.0 } else { -1.0 };
        let (r, w) = (self.half, 2 * self.half + 1);
        let (px, py) = (p % self.size, p / self.size);
        for (k, g) in self.kernel.iter().enumerate() {
            let x = (px + self.size + k % w - r) % self.size;
            let y = (py + self.size + k / w - r) % self.size;
            self.energy[y * self.size + x] += sign * g;
        }
        for dy in 0..w {
            self.rescan((py + self.size + dy - r) % self.size);
        }
    }

    /// The set pixel of highest energy (the first on ties).
    fn tightest_cluster(&self) -> usize {
        self.extreme(CLUSTER)
    }

    /// The empty pixel of lowest energy (the first on ties).
    fn largest_void(&self) -> usize {
        self.extreme(VOID)
    }

    /// The best of the rows' candidates `k`, rows in order (the first on ties).
    fn extreme(&self, k: usize) -> usize {
        let mut best = NONE;
        for p in self.rows.iter().map(|r| r[k]).filter(|&p| p != NONE) {
            if best == NONE || beats(k, self.energy[p], self.energy[best]) {
                best = p;
            }
        }
        best
    }
}

/// The void-and-cluster ranks of one channel.
fn ranks(size: usize, seed: Seed) -> Vec<u32> {
    let n = size * size;
    let ones = (n / 10).max(1);
    let mut rng = seed.rng();
    let mut initial = Energy::new(size);
    for &p in crate::seed::permutation(&mut rng, n).iter().take(ones) {
        initial.toggle(p as usize, true);
    }
    // relax: move the tightest cluster to the largest void until that undoes itself
    for _ in 0..n {
        let cluster = initial.tightest_cluster();
        initial.toggle(cluster, false);
        let void = initial.largest_void();
        initial.toggle(void, true);
        if void == cluster {
            break;
        }
    }
    let mut rank = vec![0u32; n];
    let mut down = initial.clone();
    for r in (0..ones).rev() {
        let p = down.tightest_cluster();
        down.toggle(p, false);
        rank[p] = r as u32;
    }
    let mut up = initial;
    for r in ones..n {
        let p = up.largest_void();
        up.toggle(p, true);
        rank[p] = r as u32;
    }
    rank
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mean periodogram of channel 0 over the frequencies of radius in (0, `radius`]
    /// cycles per pixel, by a direct DFT, relative to white noise's (the variance, 1/12).
    fn low_frequency_power(m: &Mask, radius: f64) -> f64 {
        let s = m.size() as i64;
        let mean = m.values().iter().sum::<f64>() / (s * s) as f64;
        let (mut total, mut count) = (0.0, 0);
        for ky in -s / 2..s / 2 {
            for kx in -s / 2..s / 2 {
                let r = ((kx * kx + ky * ky) as f64).sqrt() / s as f64;
                if r == 0.0 || r > radius {
                    continue;
                }
                let (mut re, mut im) = (0.0, 0.0);
                for y in 0..s {
                    for x in 0..s {
                        let v = m.value(x as u32, y as u32, 0) - mean;
                        let a = -std::f64::consts::TAU * (kx * x + ky * y) as f64 / s as f64;
                        re += v * a.cos();
                        im += v * a.sin();
                    }
                }
                total += (re * re + im * im) / (s * s) as f64;
                count += 1;
            }
        }
        total / count as f64 * 12.0
    }

    #[test]
    fn each_channel_ranks_every_pixel_once() {
        let m = Mask::void_and_cluster(16, 3, Seed(4)).unwrap();
        for c in 0..3 {
            let mut r: Vec<u32> = (0..256).map(|p| (m.value(p % 16, p / 16, c) * 256.0 - 0.5).round() as u32).collect();
            r.sort_unstable();
            assert_eq!(r, (0..256).collect::<Vec<_>>());
        }
        assert_ne!(m.value(0, 0, 0), m.value(0, 0, 1), "channels are independent");
        assert_eq!(m.value(16, 33, 2), m.value(0, 1, 2), "the mask tiles");
    }

    #[test]
    fn the_mask_is_blue_its_low_frequencies_nearly_empty() {
        // the criterion, fixed before measuring: below 0.15 cycles per pixel the mask's
        // power is under 1% of white noise's
        let m = Mask::void_and_cluster(64, 1, Seed(9)).unwrap();
        let p = low_frequency_power(&m, 0.15);
        assert!(p < 0.01, "low-frequency power {p} of white noise's");
        // and the test can fail: a random ranking is white
        let mut rng = Seed(9).rng();
        let white = Mask {
            size: 64,
            channels: 1,
            values: crate::seed::permutation(&mut rng, 4096).iter().map(|&r| (f64::from(r) + 0.5) / 4096.0).collect(),
        };
        assert!(low_frequency_power(&white, 0.15) > 0.5);
    }

    /// The rows' candidates give the pixels one scan of every pixel in index order gives
    /// (the first on ties), after every toggle, on tori of 4 to 17 pixels a side (windows
    /// narrower than 11 included) with ties (a pattern and its translate).
    #[test]
    fn the_rows_candidates_are_a_whole_scans() {
        let scan = |e: &Energy, on: bool, better: fn(f64, f64) -> bool| {
            (0..e.energy.len())
                .filter(|&p| e.on[p] == on)
                .fold(NONE, |best, p| if best == NONE || better(e.energy[p], e.energy[best]) { p } else { best })
        };
        let mut rng = Seed(3).rng();
        for size in [4, 5, 9, 11, 12, 17] {
            let mut e = Energy::new(size);
            let n = size * size;
            for step in 0..3 * n {
                let p = crate::seed::below(&mut rng, n as u64) as usize;
                e.toggle(p, !e.on[p]);
                assert_eq!(e.tightest_cluster(), scan(&e, true, |a, b| a > b), "size {size}, step {step}");
                assert_eq!(e.largest_void(), scan(&e, false, |a, b| a < b), "size {size}, step {step}");
            }
        }
        // ties: two copies of one pattern, half a torus apart along x, have equal energies
        let mut e = Energy::new(16);
        for p in [0, 3, 17, 36] {
            e.toggle(p, true);
            e.toggle(p + 8, true);
        }
        assert_eq!(e.tightest_cluster(), scan(&e, true, |a, b| a > b));
        assert_eq!(e.largest_void(), scan(&e, false, |a, b| a < b));
    }

    #[test]
    fn sizes_and_channels_out_of_range_are_refused() {
        assert!(Mask::void_and_cluster(3, 1, Seed(1)).unwrap_err().to_string().starts_with("size = 3"));
        assert!(Mask::void_and_cluster(8, 5, Seed(1)).unwrap_err().to_string().starts_with("channels = 5"));
    }
}
