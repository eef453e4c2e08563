//! 2D pixel-light Fourier analysis (Ramamoorthi et al. 2012 section 5): a scanline of
//! pixels x in [0,1), N samples y_k(x) of a linear light y in [0,1) per pixel, and the
//! canonical visibility V(x, y) = G(x / beta + y (1 - 1/beta)) of a blocker pattern G at
//! depth ratio beta > 1 (eq. 22). Uniform sampling's error is periodic in x with period
//! (beta - 1) / N: it bands at the spatial frequencies k N / (beta - 1) (eq. 25).

use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::seed::{Seed, uniform};
use crate::spectrum::Complex;
use crate::spectrum::nufft::Nufft;

/// How each pixel's N light samples are placed (Ramamoorthi et al. section 4; the paper's four, a closed set).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pattern {
    /// Stratum centres (k - 1/2)/N, the same in every pixel ("uniform").
    Uniform,
    /// One random offset per pixel shared by its strata ("uniform jitter").
    UniformJitter,
    /// An independent offset per stratum and pixel ("stratified").
    Stratified,
}

/// A blocker: G(u) = 0 inside any of the bars [a, b) (u on the blocker's axis), 1 elsewhere.
#[derive(Debug, Clone)]
pub struct Blocker {
    bars: Vec<(f64, f64)>,
}

impl Blocker {
    /// `count` bars of width `width` at uniform random positions in [1/beta,
    /// (beta - 1)/beta - width]: an edge at u stays in view of the light over the whole
    /// scanline exactly when u lies in [1/beta, (beta - 1)/beta], so every edge bands over
    /// the whole scanline (for beta <= 2, or bars too wide, the bars fall anywhere in [0, 1)).
    pub fn random(count: usize, width: f64, beta: f64, seed: Seed) -> Blocker {
        let mut rng = seed.rng();
        let (mut lo, mut hi) = (1.0 / beta, (beta - 1.0) / beta - width);
        if hi <= lo {
            (lo, hi) = (0.0, 1.0);
        }
        let mut bars: Vec<(f64, f64)> =
            (0..count).map(|_| lo + uniform(&mut rng) * (hi - lo)).map(|a| (a, a + width)).collect();
        bars.sort_by(|a, b| a.0.total_cmp(&b.0));
        Blocker { bars }
    }

    /// G(u).
    pub fn g(&self, u: f64) -> f64 {
        if self.bars.iter().any(|&(a, b)| a <= u && u < b) { 0.0 } else { 1.0 }
    }

    /// The integral of G over [lo, hi].
    fn integral(&self, lo: f64, hi: f64) -> f64 {
        // union of bars clipped to [lo, hi]
        let mut covered = 0.0;
        let mut end = lo;
        for &(a, b) in &self.bars {
            let (a, b) = (a.max(end), b.min(hi));
            if b > a {
                covered += b - a;
                end = b;
            }
        }
        (hi - lo) - covered
    }
}

/// The canonical visibility and its exact integral over the light.
#[derive(Debug, Clone)]
pub struct Scene {
    /// Depth ratio beta > 1 (distance light-receiver over light-blocker).
    pub beta: f64,
    /// The blocker.
    pub blocker: Blocker,
}

impl Scene {
    /// V(x, y), eq. 22.
    pub fn visibility(&self, x: f64, y: f64) -> f64 {
        self.blocker.g(x / self.beta + y * (1.0 - 1.0 / self.beta))
    }

    /// The exact integral over y in [0, 1] of V(x, y).
    pub fn exact(&self, x: f64) -> f64 {
        let s = 1.0 - 1.0 / self.beta;
        let lo = x / self.beta;
        self.blocker.integral(lo, lo + s) / s
    }
}

/// The banding frequencies k N / (beta - 1) up to `max` (eq. 25).
pub fn banding_frequencies(n: usize, beta: f64, max: f64) -> Vec<f64> {
    (1..).map(|k| k as f64 * n as f64 / (beta - 1.0)).take_while(|&f| f <= max).collect()
}

/// The sample positions of `pixels` pixels (at their centres) with `n` light samples each.
///
/// # Panics
/// Never for counts the samplers can make: the positions are finite by construction.
pub fn pattern_points(pattern: Pattern, pixels: usize, n: usize, seed: Seed) -> PointSet {
    let mut rng = seed.rng();
    let mut data = Vec::with_capacity(2 * pixels * n);
    for p in 0..pixels {
        let x = (p as f64 + 0.5) / pixels as f64;
        let shared = uniform(&mut rng);
        for k in 0..n {
            let offset = match pattern {
                Pattern::Uniform => 0.5,
                Pattern::UniformJitter => shared,
                Pattern::Stratified => uniform(&mut rng),
            };
            data.extend([x, ((k as f64 + offset) / n as f64).min(crate::numeric::BELOW_ONE)]);
        }
    }
    PointSet::new(2, data).expect("finite coordinates")
}

/// What the analysis produces for one pattern.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// |spectrum| of the sampling pattern over (pixel, light) frequencies, res x res.
    pub pattern: Vec<f64>,
    /// |spectrum| of visibility times the pattern, res x res.
    pub product: Vec<f64>,
    /// Per pixel: the estimate minus the exact integral.
    pub error: Vec<f64>,
    /// |DFT| of the error along the scanline at integer frequencies 0..pixels/2.
    pub error_spectrum: Vec<f64>,
}

impl Analysis {
    /// The error's banding: (share, fraction) where `share` is the part of the error energy
    /// at non-zero frequencies that lies at the banding frequencies `bands`, and `fraction`
    /// the part of those frequencies that are banding frequencies. Noise spread evenly has
    /// share near fraction; pure banding has share 1. Both are in [0, 1], so neither is a
    /// ratio of two values near zero (uniform sampling's error off the bands is about
    /// zero).
    pub fn banding_share(&self, bands: &[f64]) -> (f64, f64) {
        let is_band = |w: usize| bands.iter().any(|&f| f as usize == w);
        let (mut band, mut all, mut nb, mut n) = (0.0, 0.0, 0.0, 0.0);
        for (w, e) in self.error_spectrum.iter().enumerate().skip(1) {
            all += e * e;
            n += 1.0;
            if is_band(w) {
                band += e * e;
                nb += 1.0;
            }
        }
        (if all > 0.0 { band / all } else { 0.0 }, nb / n)
    }
}

/// |spectrum| of the visibility alone over (pixel, light) frequencies, `res` x `res`, from
/// V sampled at the centres of a `grid` x `grid` lattice and weighted by a separable Hann
/// window sin^2(pi x) sin^2(pi y): the square's edges then leak no energy along the axes,
/// so what is left is the sheared line of eq. 23 (Ramamoorthi et al. 2012, Fig. 10(a)).
///
/// # Errors
/// An odd resolution or an empty grid.
///
/// # Panics
/// Never: the lattice's coordinates are finite.
pub fn visibility_spectrum(scene: &Scene, grid: usize, res: usize) -> Result<Vec<f64>> {
    if grid == 0 {
        return Err(Error::TooFew { what: "a visibility spectrum".into(), least: 1, of: "grid cell", got: 0 });
    }
    let centre = |i: usize| (i as f64 + 0.5) / grid as f64;
    let data: Vec<f64> = (0..grid * grid).flat_map(|k| [centre(k / grid), centre(k % grid)]).collect();
    let pts = PointSet::new(2, data).expect("finite coordinates");
    let hann = |t: f64| (std::f64::consts::PI * t).sin().powi(2);
    let weights: Vec<f64> = pts.iter().map(|p| scene.visibility(p[0], p[1]) * hann(p[0]) * hann(p[1])).collect();
    let spectrum = Nufft::new(res, 2, 1e-9)?.transform_weighted(&pts, Some(&weights))?;
    Ok(spectrum.into_iter().map(|c| c[0].hypot(c[1])).collect())
}

/// Analyse `pattern` on `scene` with `pixels` pixels and `n` samples each; 2D spectra at
/// `res` x `res` integer frequencies (first axis: pixel frequency, second: light).
///
/// # Errors
/// beta <= 1, an odd resolution, or no pixels.
pub fn analyse(scene: &Scene, pattern: Pattern, pixels: usize, n: usize, res: usize, seed: Seed) -> Result<Analysis> {
    if scene.beta <= 1.0 || scene.beta.is_nan() {
        return Err(Error::Setting {
            name: "beta",
            value: scene.beta.to_string(),
            reason: "a pixel-light analysis needs beta > 1".into(),
        });
    }
    if let Some((of, got)) = [("pixel", pixels), ("sample", n)].into_iter().find(|&(_, c)| c == 0) {
        return Err(Error::TooFew { what: "a pixel-light analysis".into(), least: 1, of, got });
    }
    let pts = pattern_points(pattern, pixels, n, seed);
    let vis: Vec<f64> = pts.iter().map(|p| scene.visibility(p[0], p[1])).collect();
    let plan = Nufft::new(res, 2, 1e-9)?;
    let modulus = |s: Vec<Complex>| s.into_iter().map(|c| c[0].hypot(c[1])).collect::<Vec<f64>>();
    let pattern_spec = modulus(plan.transform(&pts)?);
    let product = modulus(plan.transform_weighted(&pts, Some(&vis))?);
    let error: Vec<f64> = (0..pixels)
        .map(|p| {
            let x = (p as f64 + 0.5) / pixels as f64;
            vis[p * n..(p + 1) * n].iter().sum::<f64>() / n as f64 - scene.exact(x)
        })
        .collect();
    let error_spectrum = (0..=pixels / 2)
        .map(|w| {
            let (mut re, mut im) = (0.0, 0.0);
            for (p, e) in error.iter().enumerate() {
                let a = -std::f64::consts::TAU * w as f64 * (p as f64 + 0.5) / pixels as f64;
                re += e * a.cos();
                im += e * a.sin();
            }
            re.hypot(im) / pixels as f64
        })
        .collect();
    Ok(Analysis { pattern: pattern_spec, product, error, error_spectrum })
}
