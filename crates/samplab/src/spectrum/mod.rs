//! Spectral statistics of sampling patterns over realizations (Subr & Kautz 2013 section 2).
//!
//! ## Conventions
//!
//! - The spectrum of one set of N points is S(w) = (1/N) sum_i exp(-2 pi i w.x_i), so the
//!   DC value is 1, evaluated at the integer frequencies of a centred grid of even
//!   resolution R: index k on each axis is frequency k - R/2, so index (R/2, R/2) is DC.
//!   Grids are row-major (the first axis varies slowest).
//! - Over M realizations: the periodogram `<|S|^2>`, the expected spectrum `<S>` (complex; its
//!   amplitude `|<S>|` predicts bias, eq. 4/7), and the variance of the spectrum
//!   V(S) = V(Re S) + V(Im S) (eq. 6; sample variance, divisor M - 1). Note
//!   `<|S|^2> = |<S>|^2 + V(S) (M - 1) / M`.
//! - Radial averages: bin r in 1..=R/2 - 1 holds the frequencies with round(|w|) = r (DC,
//!   bin 0, is excluded; the corners beyond R/2 are left out).
//! - Anisotropy (Lagae & Dutre 2008): per annulus, 10 log10(variance / mean^2) of the
//!   statistic's values in it, in dB.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::io::text::JsonObject;
use crate::points::PointSet;
use crate::progress::Progress;

pub mod aliasing;
pub mod nufft;
pub mod pixel_light;
pub mod tree;

pub use tree::{Sets, Spectra};

/// A complex number (re, im).
pub type Complex = [f64; 2];

/// The direct DFT of one set: S(w) for every integer frequency of the centred grid of
/// resolution `res` (even), in 1D or 2D; O(N R^d) with per-axis phase tables (separable).
///
/// # Errors
/// `res` odd or zero, or a set that is not 1D or 2D.
pub fn direct_dft(points: &PointSet, res: usize) -> Result<Vec<Complex>> {
    check_res(res)?;
    let (n, d) = (points.len(), points.dims());
    let half = (res / 2) as f64;
    let phases = |x: f64| -> Vec<Complex> {
        (0..res)
            .map(|k| {
                let (s, c) = (-std::f64::consts::TAU * (k as f64 - half) * x).sin_cos();
                [c, s]
            })
            .collect()
    };
    let inv = 1.0 / n as f64;
    match d {
        1 => {
            let mut out = vec![[0.0; 2]; res];
            for p in points.iter() {
                for (o, e) in out.iter_mut().zip(phases(p[0])) {
                    o[0] += e[0];
                    o[1] += e[1];
                }
            }
            Ok(out.into_iter().map(|c| [c[0] * inv, c[1] * inv]).collect())
        }
        2 => {
            // split real and imaginary parts so the inner loop vectorizes; fixed chunks of
            // points summed in parallel and added in chunk order: the bits do not depend
            // on the thread count
            let chunks: Vec<(Vec<f64>, Vec<f64>)> = points
                .as_slice()
                .par_chunks(2 * DFT_CHUNK)
                .map(|chunk| {
                    let (mut re, mut im) = (vec![0.0; res * res], vec![0.0; res * res]);
                    let (mut ey_re, mut ey_im) = (vec![0.0; res], vec![0.0; res]);
                    for p in chunk.chunks_exact(2) {
                        let ex = phases(p[0]);
                        for (k, e) in phases(p[1]).into_iter().enumerate() {
                            ey_re[k] = e[0];
                            ey_im[k] = e[1];
                        }
                        for (i, a) in ex.iter().enumerate() {
                            let (row_re, row_im) = (&mut re[i * res..(i + 1) * res], &mut im[i * res..(i + 1) * res]);
                            for j in 0..res {
                                row_re[j] += a[0] * ey_re[j] - a[1] * ey_im[j];
                                row_im[j] += a[0] * ey_im[j] + a[1] * ey_re[j];
                            }
                        }
                    }
                    (re, im)
                })
                .collect();
            let mut out = vec![[0.0; 2]; res * res];
            for (re, im) in chunks {
                for ((o, r), i) in out.iter_mut().zip(re).zip(im) {
                    o[0] += r;
                    o[1] += i;
                }
            }
            Ok(out.into_iter().map(|c| [c[0] * inv, c[1] * inv]).collect())
        }
        _ => Err(Error::Dimension { what: "a spectrum".into(), takes: "1D and 2D sets".into(), got: d }),
    }
}

/// Points per parallel chunk of the direct DFT (fixed, for thread-count independence).
const DFT_CHUNK: usize = 2048;

fn check_res(res: usize) -> Result<()> {
    if res == 0 || res % 2 == 1 {
        return Err(Error::Setting {
            name: "res",
            value: res.to_string(),
            reason: "must be even and positive (index R/2 is DC)".into(),
        });
    }
    Ok(())
}

/// The statistics of the spectra of M realizations.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Statistics {
    /// Resolution R of each axis.
    pub res: usize,
    /// Dimensions (1 or 2).
    pub dims: usize,
    /// Points per set.
    pub n: usize,
    /// Realizations M.
    pub sets: usize,
    /// <|S|^2>.
    pub periodogram: Vec<f64>,
    /// `|<S>|`.
    pub expected: Vec<f64>,
    /// V(Re S) + V(Im S), divisor M - 1.
    pub variance: Vec<f64>,
}

/// The names of the three statistics, in the order the outputs list them.
pub const STATISTICS: [&str; 3] = ["periodogram", "expected", "variance"];

impl Statistics {
    /// The values of statistic `name` (one of [`STATISTICS`]; the variance otherwise).
    pub fn values(&self, name: &str) -> &[f64] {
        match name {
            "periodogram" => &self.periodogram,
            "expected" => &self.expected,
            _ => &self.variance,
        }
    }
}

/// A statistic's radial curves: its average and its anisotropy in dB per radial bin
/// (1 .. R/2 - 1), as [`radial`] gives them.
pub type Radial = (Vec<f64>, Vec<f64>);

/// The radial curves of the statistics `names`, in parallel (one per statistic).
pub fn radials(st: &Statistics, names: &[&str]) -> Vec<Radial> {
    names.par_iter().map(|n| radial(st.values(n), st.res, st.dims)).collect()
}

/// `{name: {"anisotropy_db", "grid", "radial"}}` for the statistics `names` with their
/// `curves` (from [`radials`]), names in sorted order, onto `w`: the `statistics` of
/// `samplab spectrum`'s `spectrum.json`, with the bytes serde_json writes for that map
/// (non-finite numbers as `null`), each grid formatted on every thread
/// ([`crate::io::text::write_json_array`]).
///
/// # Errors
/// The writer's.
pub fn write_json(
    w: &mut dyn std::io::Write,
    st: &Statistics,
    names: &[&str],
    curves: &[Radial],
) -> std::io::Result<()> {
    let mut sorted: Vec<(&str, &Radial)> = names.iter().copied().zip(curves).collect();
    sorted.sort_by_key(|&(name, _)| name);
    sorted.dedup_by_key(|&mut (name, _)| name);
    let mut object = JsonObject::new(w)?;
    for (name, (radial, anisotropy_db)) in sorted {
        object.field_with(name, |w| {
            let mut statistic = JsonObject::new(w)?;
            statistic.field("anisotropy_db", anisotropy_db)?;
            statistic.field_with("grid", |w| crate::io::text::write_json_array(w, st.values(name)))?;
            statistic.field("radial", radial)?;
            statistic.end()
        })?;
    }
    object.end()
}

/// `radial.csv` of `samplab spectrum`: per radial bin (1 .. R/2 - 1), each statistic's
/// radial average and anisotropy in dB (numbers as Rust prints them), from `curves` (from
/// [`radials`]).
pub fn radial_csv(st: &Statistics, names: &[&str], curves: &[Radial]) -> String {
    let header = std::iter::once("frequency".to_string())
        .chain(names.iter().flat_map(|n| [n.to_string(), format!("{n}_anisotropy_db")]));
    let mut csv = crate::io::csv_line(header);
    for b in 0..st.res / 2 - 1 {
        let row = std::iter::once(format!("{}", b + 1))
            .chain(curves.iter().flat_map(|(r, a)| [format!("{:?}", r[b]), format!("{:?}", a[b])]));
        csv += &crate::io::csv_line(row);
    }
    csv
}

/// How each set's spectrum is computed.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Method {
    /// The direct DFT, O(N R^d): the reference.
    Direct,
    /// The non-uniform FFT with this tolerance (error relative to DC), O(N w^d + R^d log R).
    Fast {
        /// Relative tolerance in [1e-14, 0.1].
        tol: f64,
    },
}

impl Method {
    /// The direct DFT when `direct`, else the fast path at `tolerance`.
    pub fn of(direct: bool, tolerance: f64) -> Method {
        if direct { Method::Direct } else { Method::Fast { tol: tolerance } }
    }
}

impl Default for Method {
    /// The fast path at 1e-9: figures are indistinguishable from the direct DFT.
    fn default() -> Self {
        Method::Fast { tol: 1e-9 }
    }
}

/// The periodogram |S(w)|^2 of one set (its own anisotropy, as opposed to a strategy's,
/// which averages over realizations: Subr & Kautz 2013 section 5).
///
/// # Errors
/// A bad resolution or tolerance, or a set that is not 1D or 2D.
pub fn periodogram(set: &PointSet, res: usize, method: Method) -> Result<Vec<f64>> {
    let s = match method {
        Method::Direct => direct_dft(set, res)?,
        Method::Fast { tol } => nufft::Nufft::new(res, set.dims(), tol)?.transform(set)?,
    };
    Ok(s.iter().map(|c| c[0] * c[0] + c[1] * c[1]).collect())
}

/// The statistics of `sets` (all of one size and dimension, at least two), in parallel
/// over sets and merged by a fixed tree over blocks of sets ([`tree`]), so the result does
/// not depend on the thread count, nor on how a distributed study splits the sets.
///
/// # Errors
/// Fewer than two sets, sets of different sizes or dimensions, a bad resolution or tolerance.
///
/// ```
/// use samplab::spectrum::{Method, statistics};
/// use samplab::{Seed, sampler};
/// let jitter = sampler::build("jitter").unwrap();
/// let sets = sampler::generate_sets(&jitter, 64, 2, Seed(1), 8).unwrap();
/// let st = statistics(&sets, 32, Method::Direct).unwrap();
/// // S(0) = 1 for every set: the periodogram's DC (index R/2, R/2) is 1
/// assert!((st.periodogram[16 * 32 + 16] - 1.0).abs() < 1e-12);
/// ```
pub fn statistics(sets: &[PointSet], res: usize, method: Method) -> Result<Statistics> {
    statistics_with_progress(sets, res, method, &Progress::SILENT)
}

/// [`statistics`], advancing `progress` by one per set transformed.
///
/// # Errors
/// As [`statistics`], or a stop ([`Error::Interrupted`]).
pub fn statistics_with_progress(
    sets: &[PointSet],
    res: usize,
    method: Method,
    progress: &Progress,
) -> Result<Statistics> {
    statistics_of(Sets::Given(sets), res, method, progress)
}

/// [`statistics`] of sets given or generated block by block (so that only a block's
/// spectra are in memory at once), by the fixed merge tree of [`tree`]; `progress` advances
/// by one per set transformed.
///
/// # Errors
/// As [`statistics`], memory, or a stop ([`Error::Interrupted`]).
pub fn statistics_of(sets: Sets, res: usize, method: Method, progress: &Progress) -> Result<Statistics> {
    if sets.len() < 2 {
        return Err(Error::TooFew {
            what: "the variance of the spectrum".into(),
            least: 2,
            of: "set",
            got: sets.len(),
        });
    }
    let (n, d) = sets.shape()?;
    let spectra = Spectra::new(res, d, method)?;
    spectra.node(&sets, tree::root_level(sets.len()), 0, progress)?.finish(res, d, n)
}

/// Radial average (bins 1..=R/2-1 by rounded |w|, DC excluded) and anisotropy in dB of
/// a statistic on the centred grid. The bins are summed in parallel, each one's values in
/// index order, so the bits are those of one pass over the grid adding each value to its
/// bin (which took about 7 ms a statistic at R = 1024, on one thread each while the others
/// waited: 0.36% of a two-thread `samplab spectrum`'s samples for three statistics).
pub fn radial(values: &[f64], res: usize, dims: usize) -> (Vec<f64>, Vec<f64>) {
    (1..res / 2)
        .into_par_iter()
        .map(|b| {
            let (mut sum, mut sq, mut count) = (0.0, 0.0, 0usize);
            ring(b, res, dims, |idx| {
                let v = values[idx];
                sum += v;
                sq += v * v;
                count += 1;
            });
            let c = count.max(1) as f64;
            let mu = sum / c;
            let var = (sq / c - mu * mu).max(0.0);
            (mu, if mu > 0.0 && count > 1 { 10.0 * (var / (mu * mu)).max(1e-30).log10() } else { f64::NAN })
        })
        .unzip()
}

/// `visit(idx)` for each index of the centred grid (`res` a side, `dims` 1 or 2, index
/// res/2 the zero frequency) whose |w| rounds to `b`, in increasing order.
fn ring(b: usize, res: usize, dims: usize, mut visit: impl FnMut(usize)) {
    let (b, half) = (b as i64, (res / 2) as i64);
    let top = res as i64 - 1 - half;
    let at = |f: i64| (f + half) as usize;
    if dims == 1 {
        for f in [-b, b].into_iter().filter(|f| (-half..=top).contains(f)) {
            visit(at(f));
        }
        return;
    }
    // |w|^2 = s is an integer, and round(sqrt(s)) = b exactly when b (b - 1) < s <= b (b + 1)
    // (no bin boundary k + 1/2 has an integer square, nor is any correctly rounded square
    // root near one)
    let cols = |from: i64, to: i64| from.max(-half)..=to.min(top);
    for i in (-b).max(-half)..=b.min(top) {
        let (inner, outer) = (b * (b - 1) - i * i, b * (b + 1) - i * i);
        let (low, high) = (if inner < 0 { 0 } else { inner.isqrt() + 1 }, outer.isqrt());
        if low > high {
            continue;
        }
        let row = at(i) * res;
        let (left, right) =
            if low == 0 { (cols(-high, high), cols(1, 0)) } else { (cols(-high, -low), cols(low, high)) };
        for j in left.chain(right) {
            visit(row + at(j));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radial_bins_are_one_pass_over_the_grid() {
        // the definition: one pass in index order, each value added to the bin of its
        // rounded |w| (hypot, independently of the integer bounds of `ring`)
        fn one_pass(values: &[f64], res: usize, dims: usize) -> (Vec<f64>, Vec<f64>) {
            let bins = res / 2;
            let (mut sum, mut sq, mut count) = (vec![0.0; bins], vec![0.0; bins], vec![0usize; bins]);
            let half = (res / 2) as f64;
            for (idx, &v) in values.iter().enumerate() {
                let r = if dims == 1 {
                    (idx as f64 - half).abs()
                } else {
                    ((idx / res) as f64 - half).hypot((idx % res) as f64 - half)
                };
                let b = r.round() as usize;
                if b >= 1 && b < bins {
                    sum[b] += v;
                    sq[b] += v * v;
                    count[b] += 1;
                }
            }
            (1..bins)
                .map(|b| {
                    let c = count[b].max(1) as f64;
                    let mu = sum[b] / c;
                    let var = (sq[b] / c - mu * mu).max(0.0);
                    (mu, if mu > 0.0 && count[b] > 1 { 10.0 * (var / (mu * mu)).max(1e-30).log10() } else { f64::NAN })
                })
                .unzip()
        }
        let mut rng = crate::seed::Seed(3).rng();
        for dims in [1, 2] {
            for res in [2usize, 3, 4, 5, 8, 31, 64, 255, 1024] {
                let values: Vec<f64> =
                    (0..res.pow(dims as u32)).map(|_| crate::seed::uniform(&mut rng) * 1e3).collect();
                let bits = |(m, a): (Vec<f64>, Vec<f64>)| m.iter().chain(&a).map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(radial(&values, res, dims)), bits(one_pass(&values, res, dims)), "{dims}D, R = {res}");
            }
        }
    }

    #[test]
    fn dc_is_one_and_single_points_have_unit_modulus() {
        let p = PointSet::new(2, vec![0.3, 0.7]).unwrap();
        let s = direct_dft(&p, 8).unwrap();
        assert!((s[4 * 8 + 4][0] - 1.0).abs() < 1e-15 && s[4 * 8 + 4][1].abs() < 1e-15);
        assert!(s.iter().all(|c| (c[0].hypot(c[1]) - 1.0).abs() < 1e-12));
        // S(w) = exp(-2 pi i (wx 0.3 + wy 0.7)) at w = (1, -2): index (5, 2)
        let w = -std::f64::consts::TAU * (0.3 - 2.0 * 0.7);
        let c = s[5 * 8 + 2];
        assert!((c[0] - w.cos()).abs() < 1e-12 && (c[1] - w.sin()).abs() < 1e-12);
    }

    #[test]
    fn power_decomposes_into_expected_and_variance() {
        let sets: Vec<PointSet> =
            (0..7).map(|k| crate::sampler::build("random").unwrap().generate(20, 2, crate::Seed(k)).unwrap()).collect();
        let st = statistics(&sets, 8, Method::Direct).unwrap();
        let m = 7.0;
        for i in 0..64 {
            let want = st.expected[i].powi(2) + st.variance[i] * (m - 1.0) / m;
            assert!((st.periodogram[i] - want).abs() < 1e-12);
        }
    }
}
