//! Heck, Schlömer & Deussen's (2013) two numbers for the aliasing a 2D pattern lets
//! through, read off its periodogram P(k) = |sum_i exp(-2 pi i k.x_i)|^2 / n at the integer
//! frequencies k of the torus (E P(k) = 1 for white noise, exactly, at every k != 0):
//!
//! - **effective Nyquist frequency**: the mean of P over the disk |k| <= v (DC left out)
//!   stays near zero up to the edge of the pattern's zero region and climbs towards 1 past
//!   it. Going out from sqrt(n)/2 to the first radius where that mean exceeds 0.5, then back
//!   to the last radius where it is below 0.1, the next radius out is v_zero, the edge of
//!   the zero region; a signal band-limited to v_zero / 2 is sampled without aliasing into
//!   low frequencies, and the value reported is (v_zero / 2) / (sqrt(n) / 2) = v_zero /
//!   sqrt(n), the fraction of a sqrt(n) x sqrt(n) grid's Nyquist frequency: exactly 1 for
//!   that grid, 0 for white noise (no zero region).
//! - **oscillation**: 10 times the root mean square of (radial mean of P - 1) over the
//!   frequencies of the annulus from v_osc, the first ring whose radial mean reaches 0.98,
//!   out 10 grid Nyquist frequencies (5 sqrt(n)); every frequency weighs the same, so
//!   the ring at radius r weighs ~ 2 pi r, as in the paper's area-weighted integral.
//!
//! Thresholds (0.1, 0.5, 0.98), the window and the factor 10 follow the point set analysis
//! tool of Schlömer & Heck (psa), so that values compare with the figures quoted with it;
//! the sums over integer frequencies replace its curves derived from the radial
//! distribution function. Heck et al. average spectra over realizations; one set's
//! oscillation carries the periodogram's own scatter: for white noise, E Omega^2 = 200 (1 -
//! 1/n) B / M exactly for a window of B rings holding M frequencies (tested).

use super::{Method, periodogram};
use crate::error::{Error, Result};
use crate::points::PointSet;

/// The power P(k) = n |S(k)|^2 of one 2D set at every integer k with 0 < |k| <= `reach`,
/// sorted by |k|^2: (|k|^2, P) pairs.
fn powers(set: &PointSet, reach: usize) -> Result<Vec<(u64, f64)>> {
    if set.dims() != 2 {
        return Err(Error::Dimension {
            what: "the effective Nyquist frequency and oscillation".into(),
            takes: "2D sets".into(),
            got: set.dims(),
        });
    }
    let res = 2 * (reach + 1);
    // the periodogram, its NUFFT's oversampled grid and the sorted list: about 64 bytes a
    // frequency
    crate::memory::check(
        || format!("the {res}^2 periodogram of {} points", set.len()),
        64 * (res as u128) * (res as u128),
    )?;
    let values = periodogram(set, res, Method::default())?;
    let n = set.len() as f64;
    let half = (res / 2) as i64;
    let mut out: Vec<(u64, f64)> = values
        .iter()
        .enumerate()
        .filter_map(|(idx, &v)| {
            let (i, j) = ((idx / res) as i64 - half, (idx % res) as i64 - half);
            let r2 = (i * i + j * j) as u64;
            (r2 > 0 && r2 <= (reach * reach) as u64).then_some((r2, n * v))
        })
        .collect();
    out.sort_by_key(|&(r2, _)| r2);
    Ok(out)
}

/// The effective Nyquist frequency of a 2D set, in units of sqrt(n) (module doc).
///
/// # Errors
/// A set that is not 2D, or whose mean power stays below 0.5 out to 2 sqrt(n).
pub fn effective_nyquist(set: &PointSet) -> Result<f64> {
    let root = (set.len() as f64).sqrt();
    let reach = (2.0 * root).ceil() as usize + 2;
    // the mean power over each disk, at every distinct radius
    let mut disks: Vec<(u64, f64)> = Vec::new();
    let (mut sum, mut count) = (0.0, 0usize);
    let p = powers(set, reach)?;
    for (i, &(r2, v)) in p.iter().enumerate() {
        sum += v;
        count += 1;
        if p.get(i + 1).is_none_or(|next| next.0 != r2) {
            disks.push((r2, sum / count as f64));
        }
    }
    let start = disks.partition_point(|&(r2, _)| (r2 as f64) < root * root / 4.0);
    let Some(high) = disks[start..].iter().position(|&(_, mean)| mean > 0.5).map(|i| i + start) else {
        return Err(Error::Infeasible {
            what: "the effective Nyquist frequency".into(),
            reason: format!("the mean power stays below 0.5 out to |k| = {reach} (2 sqrt(n))"),
        });
    };
    let edge = match disks[..high].iter().rposition(|&(_, mean)| mean < 0.1) {
        Some(low) => (disks[low + 1].0 as f64).sqrt(),
        None => 0.0,
    };
    Ok(edge / root)
}

/// The oscillation Omega of a 2D set's radial power spectrum (module doc).
///
/// # Errors
/// A set that is not 2D, or whose radial mean power stays below 0.98 out to 2 sqrt(n).
pub fn oscillation(set: &PointSet) -> Result<f64> {
    let root = (set.len() as f64).sqrt();
    let (first, span) = ((2.0 * root).ceil() as usize, (5.0 * root).ceil() as usize);
    let reach = first + span + 1;
    // rings of rounded radius: sum of P and count
    let mut rings = vec![(0.0, 0usize); reach + 1];
    for (r2, v) in powers(set, reach)? {
        let b = (r2 as f64).sqrt().round() as usize;
        if b <= reach {
            rings[b].0 += v;
            rings[b].1 += 1;
        }
    }
    let mean = |b: usize| rings[b].0 / rings[b].1 as f64;
    let Some(start) = (1..=first).find(|&b| mean(b) >= 0.98) else {
        return Err(Error::Infeasible {
            what: "the oscillation window".into(),
            reason: format!("the radial mean power stays below 0.98 out to |k| = {first} (2 sqrt(n))"),
        });
    };
    let window = start..=start + span;
    let total: usize = window.clone().map(|b| rings[b].1).sum();
    let square: f64 = window.map(|b| rings[b].1 as f64 * (mean(b) - 1.0).powi(2)).sum();
    Ok(10.0 * (square / total as f64).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Seed;
    use crate::sampler;

    fn grid(side: usize) -> PointSet {
        let coords = (0..side * side)
            .flat_map(|i| [((i / side) as f64 + 0.5) / side as f64, ((i % side) as f64 + 0.5) / side as f64]);
        PointSet::new(2, coords.collect()).unwrap()
    }

    #[test]
    fn a_regular_grid_has_its_own_nyquist_frequency() {
        // P(k) = n on the reciprocal lattice side Z^2 and 0 elsewhere: the zero region ends
        // at |k| = side = sqrt(n) exactly
        for side in [8, 16, 31] {
            assert!((effective_nyquist(&grid(side)).unwrap() - 1.0).abs() < 1e-12, "side {side}");
        }
    }

    #[test]
    fn white_noise_has_no_zero_region_and_its_closed_form_oscillation() {
        // E P(k) = 1 and Var P(k) = 1 - 1/n, P(k) = P(-k), other pairs uncorrelated: a ring of
        // m frequencies has Var(mean) = 2 (1 - 1/n) / m, so E Omega^2 = 200 (1 - 1/n) B / M
        let n = 1024;
        let random = sampler::build("random").unwrap();
        let (mut ratio, sets) = (0.0, 24);
        for s in 0..sets {
            let set = random.generate(n, 2, Seed(100 + s)).unwrap();
            assert!(effective_nyquist(&set).unwrap() < 0.1);
            let root = (n as f64).sqrt();
            let reach = (7.0 * root).ceil() as usize + 1;
            let p = powers(&set, reach).unwrap();
            let ring = |b: usize| p.iter().filter(move |(r2, _)| (*r2 as f64).sqrt().round() as usize == b);
            let start = (1..).find(|&b| ring(b).map(|x| x.1).sum::<f64>() / ring(b).count() as f64 >= 0.98).unwrap();
            let span = (5.0 * root).ceil() as usize;
            let total: usize = (start..=start + span).map(|b| ring(b).count()).sum();
            let expected = 200.0 * (1.0 - 1.0 / n as f64) * (span + 1) as f64 / total as f64;
            ratio += oscillation(&set).unwrap().powi(2) / expected / sets as f64;
        }
        assert!((ratio - 1.0).abs() < 0.1, "mean Omega^2 / closed form = {ratio}");
    }

    #[test]
    fn blue_noise_has_a_wide_zero_region_and_oscillates() {
        let set = sampler::build("lloyd").unwrap().generate(1024, 2, Seed(3)).unwrap();
        let nu = effective_nyquist(&set).unwrap();
        assert!(nu > 0.6, "Lloyd's effective Nyquist frequency {nu}");
        let white = sampler::build("random").unwrap().generate(1024, 2, Seed(3)).unwrap();
        assert!(oscillation(&set).unwrap() > 2.0 * oscillation(&white).unwrap());
    }

    #[test]
    fn other_dimensions_are_refused() {
        let set = PointSet::new(3, vec![0.1, 0.2, 0.3]).unwrap();
        assert!(effective_nyquist(&set).unwrap_err().to_string().contains("2D"));
    }
}
