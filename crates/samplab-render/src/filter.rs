//! Where in (or around) a pixel the camera rays go: its centre, its area, or a reconstruction
//! filter's footprint.
//!
//! A filter is sampled exactly, by inverting its integral: each estimate's film position
//! has the filter's density, clipped to the image, so the plain mean of the estimates
//! converges to the filtered image, sum f(x - c) L(x) / sum f(x - c) over the image, the
//! value Mitsuba 3's film reaches by splatting every sample with the filter's weights
//! (Mitsuba keeps samples inside the image unless its film's `sample_border` is set).

/// Where in the pixel the camera rays go.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Footprint {
    /// Every estimate through the pixel centre.
    Centre,
    /// Over the pixel's area (antialiasing, a box filter) by the pixel strategy.
    Area,
    /// Over Mitsuba 3's windowed Gaussian reconstruction filter about the pixel centre, by
    /// the pixel strategy: f(x, y) = g(x) g(y), g(x) = max(0, exp(-x^2 / 2 s^2) -
    /// exp(-r^2 / 2 s^2)) with radius r = 4 s, in pixels.
    Gaussian {
        /// The standard deviation s, in pixels (Mitsuba's default 0.5).
        stddev: f64,
    },
}

impl Footprint {
    /// Mitsuba 3's default reconstruction filter (its `hdrfilm`'s `rfilter`).
    pub const MITSUBA: Footprint = Footprint::Gaussian { stddev: 0.5 };

    /// Its name, as `--pixel` takes it (a Gaussian of another width with its stddev).
    pub fn name(self) -> String {
        match self {
            Footprint::Centre => "center".into(),
            Footprint::Area => "area".into(),
            Footprint::Gaussian { .. } if self == Footprint::MITSUBA => "gaussian".into(),
            Footprint::Gaussian { stddev } => format!("gaussian (stddev {stddev})"),
        }
    }

    /// Whether the estimates' film positions are drawn (a pixel sample each).
    pub fn spreads(self) -> bool {
        self != Footprint::Centre
    }

    /// The film position of an estimate of pixel (`col`, `row`) of a `width` x `height`
    /// image, in pixels from the pixel's corner, for the pixel sample `u` in the unit square.
    #[inline(always)]
    pub fn offset(self, u: [f64; 2], col: usize, row: usize, width: usize, height: usize) -> [f64; 2] {
        match self {
            Footprint::Centre => [0.5, 0.5],
            Footprint::Area => u,
            Footprint::Gaussian { stddev } => {
                let g = WindowedGaussian::new(stddev);
                [0.5 + g.sample(u[0], col, width), 0.5 + g.sample(u[1], row, height)]
            }
        }
    }
}

/// One axis of [`Footprint::Gaussian`].
struct WindowedGaussian {
    stddev: f64,
    radius: f64,
    /// exp(-r^2 / 2 s^2), the window's offset.
    bias: f64,
}

impl WindowedGaussian {
    fn new(stddev: f64) -> WindowedGaussian {
        let radius = 4.0 * stddev;
        WindowedGaussian { stddev, radius, bias: (-0.5 * (radius / stddev).powi(2)).exp() }
    }

    fn density(&self, x: f64) -> f64 {
        ((-0.5 * (x / self.stddev).powi(2)).exp() - self.bias).max(0.0)
    }

    /// The integral of the density from 0 to `x`, |x| <= r.
    fn integral(&self, x: f64) -> f64 {
        let s = self.stddev;
        s * (0.5 * std::f64::consts::PI).sqrt() * libm::erf(x / (s * std::f64::consts::SQRT_2)) - self.bias * x
    }

    /// The offset from the centre of pixel `i` of an axis of `n` pixels with the density
    /// clipped to the axis ([0, n] in pixels), for `u` in [0, 1]: the inverse of the
    /// integral by Newton's steps kept inside a shrinking bracket.
    fn sample(&self, u: f64, i: usize, n: usize) -> f64 {
        let centre = i as f64 + 0.5;
        let (mut lo, mut hi) = ((-centre).max(-self.radius), (n as f64 - centre).min(self.radius));
        let base = self.integral(lo);
        let target = u * (self.integral(hi) - base);
        let mut x = 0.0f64.clamp(lo, hi);
        for _ in 0..200 {
            let f = self.integral(x) - base - target;
            if f == 0.0 {
                break;
            }
            if f > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            let newton = x - f / self.density(x);
            let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
            if next == x || hi - lo <= 1e-13 {
                break;
            }
            x = next;
        }
        x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sampled offsets have the filter's clipped distribution: a sweep of u over the
    /// midpoints of `draws` equal steps puts into each bin its share of the filter's mass
    /// (midpoint rule on a fine grid), give or take one draw at each bin edge, since the
    /// inverse is increasing.
    #[test]
    fn gaussian_offsets_follow_the_clipped_filter() {
        let g = WindowedGaussian::new(0.5);
        for (i, n) in [(5, 10), (0, 10), (9, 10), (0, 1)] {
            let centre = i as f64 + 0.5;
            let (lo, hi) = ((-centre).max(-2.0), (n as f64 - centre).min(2.0));
            let bins = 16;
            let draws = 200_000;
            let mut counts = vec![0usize; bins];
            for k in 0..draws {
                let x = g.sample((k as f64 + 0.5) / draws as f64, i, n);
                assert!((lo..=hi).contains(&x), "{x} outside [{lo}, {hi}]");
                counts[(((x - lo) / (hi - lo) * bins as f64) as usize).min(bins - 1)] += 1;
            }
            let fine = 4000;
            let mass: Vec<f64> = (0..bins)
                .map(|b| {
                    (0..fine)
                        .map(|j| {
                            let x = lo + (hi - lo) * (b as f64 + (j as f64 + 0.5) / fine as f64) / bins as f64;
                            g.density(x)
                        })
                        .sum::<f64>()
                })
                .collect();
            let total: f64 = mass.iter().sum();
            for b in 0..bins {
                let p = mass[b] / total;
                let expected = p * draws as f64;
                assert!(
                    (counts[b] as f64 - expected).abs() <= 2.0 + 1e-6 * draws as f64,
                    "pixel {i} of {n}, bin {b}: {} vs {expected:.1}",
                    counts[b]
                );
            }
        }
    }

    #[test]
    fn the_window_matches_mitsubas_gaussian() {
        // Mitsuba 3.9.1's gaussian rfilter (stddev 0.5): radius 2, eval(0.5) = 0.6064,
        // eval(1) = 0.1350, eval(1.5) = 0.01076 (by its fast exp, within 0.2%)
        let g = WindowedGaussian::new(0.5);
        assert_eq!(g.radius, 2.0);
        for (x, v) in [(0.5, 0.6064), (1.0, 0.1350), (1.5, 0.01076)] {
            assert!((g.density(x) / v - 1.0).abs() < 2e-3, "{x}: {}", g.density(x));
        }
        assert_eq!(g.density(2.0), 0.0);
    }
}
