//! Lighting the ends of paths: shadow rays to each light sample, in vector lanes, with the
//! visibility, direct and unoccluded (quadrature) estimators.

use super::dealing::{Scratch, light_samples};
use super::integrator::obscure_ends;
use super::{Mode, Pattern, Pixel, Prepared, QUADRATURE, Setup};
use crate::light::{DiskMap, Light, LightPoint, geometry};
use crate::packet::{Packet, WIDTH};
use crate::scene::Scene;
use glam::DVec3;
use samplab::simd::wide;
use std::f64::consts::PI;

/// The midpoint rule over the light's square (interval), through the concentric map for
/// disks (area-preserving, so equal weights).
pub(super) fn quadrature(light: &Light) -> Vec<LightPoint> {
    let k = QUADRATURE;
    let mid = |i: usize| (i as f64 + 0.5) / k as f64;
    if light.dims() == 1 {
        (0..k * k)
            .filter_map(|i| light.sample_with(&[(i as f64 + 0.5) / (k * k) as f64], DiskMap::Concentric))
            .collect()
    } else {
        (0..k * k).filter_map(|i| light.sample_with(&[mid(i % k), mid(i / k)], DiskMap::Concentric)).collect()
    }
}

/// The unoccluded shading of the light at `x` (normal `n`) by its midpoint rule: the mean of
/// the weighted geometric factor, summed in 8 interleaved partial sums (a fixed order, the
/// same value on every thread count and instruction set) so that the loop vectorizes.
pub(super) fn unoccluded(p: &Prepared, x: DVec3, n: DVec3) -> f64 {
    const LANES: usize = 8;
    #[inline(always)]
    fn sum(points: &[LightPoint], f: impl Fn(&LightPoint) -> f64) -> [f64; LANES] {
        let mut acc = [0.0; LANES];
        let mut chunks = points.chunks_exact(LANES);
        for c in &mut chunks {
            for (a, q) in acc.iter_mut().zip(c) {
                *a += f(q);
            }
        }
        for (a, q) in acc.iter_mut().zip(chunks.remainder()) {
            *a += f(q);
        }
        acc
    }
    let q = &p.quadrature;
    // the light's normal (or none) fixed outside the loop, so that each loop is branch-free
    let acc = wide(
        #[inline(always)]
        || match p.normal {
            Some(ny) => sum(q, |q| q.weight * geometry(Some(ny), x, n, q.position)),
            None => sum(q, |q| q.weight * geometry(None, x, n, q.position)),
        },
    );
    acc.iter().sum::<f64>() / q.len() as f64
}

/// Up to [`WIDTH`] paths ended on a diffuse surface, lit together when full: per lane, the
/// estimate, position, normal facing the path, throughput x albedo and shutter time, in
/// structure-of-arrays form so that their lighting runs in vector lanes.
pub(super) struct Ends {
    pub(super) len: usize,
    pub(super) estimate: [u32; WIDTH],
    pub(super) position: Lanes3,
    pub(super) normal: Lanes3,
    pub(super) albedo: Lanes3,
    pub(super) time: [f64; WIDTH],
}

/// Three coordinates in lanes.
pub(super) type Lanes3 = [[f64; WIDTH]; 3];

/// Lanes of zeros (arrays as wide as [`WIDTH`] have no `Default`).
pub(super) const ZEROS: [f64; WIDTH] = [0.0; WIDTH];

impl Default for Ends {
    fn default() -> Ends {
        Ends { len: 0, estimate: [0; WIDTH], position: [ZEROS; 3], normal: [ZEROS; 3], albedo: [ZEROS; 3], time: ZEROS }
    }
}

impl Default for Shadows {
    fn default() -> Shadows {
        Shadows {
            len: 0,
            end: [0; WIDTH],
            point: [ZEROS; 3],
            weight: ZEROS,
            kept: [false; WIDTH],
            packet: Packet::default(),
        }
    }
}

impl Default for Sums {
    fn default() -> Sums {
        Sums { unoccluded: ZEROS, accepted: [0; WIDTH], weight: ZEROS, shade: ZEROS, seen: ZEROS }
    }
}

/// Vector `k` of `lanes`.
#[inline(always)]
pub(super) fn lane(lanes: &Lanes3, k: usize) -> DVec3 {
    DVec3::new(lanes[0][k], lanes[1][k], lanes[2][k])
}

/// Put `v` in lane `k`.
#[inline(always)]
pub(super) fn set_lane(lanes: &mut Lanes3, k: usize, v: DVec3) {
    for (c, x) in lanes.iter_mut().zip(v.to_array()) {
        c[k] = x;
    }
}

/// Up to [`WIDTH`] light samples waiting for their shadow rays, traced as one packet: per
/// lane, the end it belongs to (a lane of [`Ends`]), the light point, its falloff weight and
/// whether it is kept (a lane not kept is dead: no ray).
pub(super) struct Shadows {
    pub(super) len: usize,
    pub(super) end: [u32; WIDTH],
    pub(super) point: Lanes3,
    pub(super) weight: [f64; WIDTH],
    pub(super) kept: [bool; WIDTH],
    pub(super) packet: Packet,
}

/// One light's sums over the samples of each lane of [`Ends`].
pub(super) struct Sums {
    /// Unoccluded shading (visibility mode; 1 in direct mode).
    pub(super) unoccluded: [f64; WIDTH],
    /// Samples the disk map kept, and their summed falloff weight.
    pub(super) accepted: [u32; WIDTH],
    pub(super) weight: [f64; WIDTH],
    /// Over the unblocked samples: weight x geometric factor, and weight.
    pub(super) shade: [f64; WIDTH],
    pub(super) seen: [f64; WIDTH],
}

/// What a light's samples need of it and of the ends they light.
pub(super) struct Lighting<'a> {
    pub(super) scene: &'a Scene,
    pub(super) ends: &'a Ends,
    /// Each end's shadow-ray origin, moved off its surface.
    pub(super) origin: &'a Lanes3,
    /// The light's normal (None: a segment); whether the geometric factor weighs samples.
    pub(super) normal: Option<DVec3>,
    pub(super) direct: bool,
}

impl Shadows {
    /// Queue light point `y` of weight `weight` for end `end`.
    #[inline(always)]
    pub(super) fn push(&mut self, end: usize, y: DVec3, weight: f64) {
        let i = self.len;
        self.set(i, end, y, weight, true);
        self.len = i + 1;
    }

    /// Lane `i`: light point `y` of weight `weight` for end `end`, kept or not.
    #[inline(always)]
    pub(super) fn set(&mut self, i: usize, end: usize, y: DVec3, weight: f64, kept: bool) {
        self.end[i] = end as u32;
        set_lane(&mut self.point, i, y);
        self.weight[i] = weight;
        self.kept[i] = kept;
    }

    /// Lanes `0..n` of the packet: the shadow ray of each queued sample, whose end is
    /// `end(j)`, with its geometric factor and whether the sample is kept with a positive
    /// factor.
    #[inline(always)]
    pub(super) fn rays(
        &mut self,
        at: &Lighting,
        n: usize,
        end: impl Fn(usize) -> usize,
        factor: &mut [f64; WIDTH],
        live: &mut [bool; WIDTH],
    ) {
        for j in 0..n {
            let k = end(j);
            let (x, y) = (lane(&at.ends.position, k), lane(&self.point, j));
            let g = if at.direct { geometry(at.normal, x, lane(&at.ends.normal, k), y) } else { 1.0 };
            factor[j] = g;
            live[j] = self.kept[j] && g > 0.0;
            self.packet.set(j, &Scene::shadow_ray(lane(at.origin, k), y, at.ends.time[k]));
        }
    }

    /// Trace the queued samples' shadow rays and add each unblocked one to its end's sums,
    /// in the order queued: the rays and geometric factors made in vector lanes, a sample not
    /// kept or whose factor is not positive left out (a dead lane). Returns the rays traced.
    #[inline(always)]
    pub(super) fn trace(&mut self, at: &Lighting, sums: &mut Sums) -> u64 {
        let n = self.len;
        if n == 0 {
            return 0;
        }
        let (mut factor, mut live) = ([0.0; WIDTH], [false; WIDTH]);
        let end = self.end;
        // one sample per end (the usual case) puts end j in lane j: no gathers, and the loop
        // vectorizes
        if end[..n].iter().enumerate().all(|(j, &k)| k as usize == j) {
            self.rays(at, n, |j| j, &mut factor, &mut live);
        } else {
            self.rays(at, n, |j| end[j] as usize, &mut factor, &mut live);
        }
        self.packet.seal(n);
        let blocked = at.scene.occluded(&self.packet, &live);
        for (j, _) in blocked[..n].iter().enumerate().filter(|(_, b)| !**b) {
            let k = self.end[j] as usize;
            sums.shade[k] += self.weight[j] * factor[j];
            sums.seen[k] += self.weight[j];
        }
        self.len = 0;
        live[..n].iter().filter(|&&l| l).count() as u64
    }
}

/// Light the waiting ends: for each light in turn, each end's light samples, their shadow
/// rays traced by packets, and the end's share added to its estimate; then each estimate's
/// visible fraction. The per-end arithmetic runs in vector lanes. Returns the shadow rays
/// traced.
#[inline(always)]
pub(super) fn light_ends(setup: &Setup, px: Pixel, s: &mut Scratch) -> u64 {
    let Setup { scene, options: o, lights, keys, plans, .. } = *setup;
    let (ends, m) = (&s.ends, s.ends.len);
    if m == 0 {
        return 0;
    }
    if o.mode == Mode::Obscurance {
        return obscure_ends(setup, px, s);
    }
    let mut origin = [ZEROS; 3];
    for k in 0..m {
        set_lane(&mut origin, k, Scene::offset(lane(&ends.position, k), lane(&ends.normal, k)));
    }
    let mut traced = 0;
    let mut visible = [0.0; WIDTH];
    for (l, p) in lights.iter().enumerate() {
        let at = Lighting { scene, ends, origin: &origin, normal: p.normal, direct: o.mode == Mode::Direct };
        let mut sums = Sums::default();
        for k in 0..m {
            sums.unoccluded[k] = match o.mode {
                Mode::Visibility => unoccluded(p, lane(&ends.position, k), lane(&ends.normal, k)),
                Mode::Direct | Mode::Obscurance | Mode::Path { .. } => 1.0,
            };
        }
        if o.pattern() == Pattern::PerPixel && o.n == 1 {
            // one sample per end (Cook's pairing of a pixel's samples): end k's in lane k, a
            // rejected or unlit one a dead lane
            let (dealt, points) = (&s.shared[l], &s.shared_points[l]);
            for k in 0..m {
                let y = points.get(dealt.start(ends.estimate[k] as usize, 1));
                let kept = sums.unoccluded[k] > 0.0 && y.is_some();
                let y = y.unwrap_or(LightPoint { position: DVec3::ZERO, weight: 0.0 });
                sums.accepted[k] = u32::from(kept);
                sums.weight[k] = if kept { y.weight } else { 0.0 };
                s.shadows.set(k, k, y.position, y.weight, kept);
            }
            s.shadows.len = m;
        } else {
            for k in 0..m {
                let e = ends.estimate[k] as usize;
                if sums.unoccluded[k] <= 0.0 {
                    continue;
                }
                let (points, range) = match o.pattern() {
                    Pattern::PerEstimate => {
                        let (dims, key) = (p.light.dims(), keys.light.derive(px.index).derive(l as u64));
                        match o.pixel_sampler().map(|(p, _)| p) {
                            Some(pixels) => light_samples(pixels, px, e, l, o.n, dims, &mut s.light),
                            None => {
                                s.light.resize(o.n * dims, 0.0);
                                if let Err(e) = plans.light[l].fill(key.derive(e as u64), &mut s.light) {
                                    s.failed.get_or_insert(e);
                                }
                            }
                        }
                        s.light_points.fill(&p.light, &s.light);
                        (&s.light_points, 0..o.n)
                    }
                    Pattern::PerPixel => {
                        let b = s.shared[l].start(e, o.n);
                        (&s.shared_points[l], b..b + o.n)
                    }
                };
                for i in range {
                    let Some(y) = points.get(i) else { continue };
                    sums.accepted[k] += 1;
                    sums.weight[k] += y.weight;
                    s.shadows.push(k, y.position, y.weight);
                    if s.shadows.len == WIDTH {
                        traced += s.shadows.trace(&at, &mut sums);
                    }
                }
            }
        }
        traced += s.shadows.trace(&at, &mut sums);
        let mut share = [ZEROS; 3];
        for (k, v) in visible[..m].iter_mut().enumerate() {
            let fraction = sums.seen[k] / sums.weight[k];
            *v += if sums.accepted[k] > 0 { fraction } else { 0.0 };
            let integral = match o.mode {
                Mode::Visibility => sums.unoccluded[k] * fraction,
                Mode::Direct | Mode::Obscurance | Mode::Path { .. } => sums.shade[k] / sums.accepted[k] as f64,
            };
            set_lane(&mut share, k, lane(&ends.albedo, k) / PI * p.light.radiance * p.area * integral);
        }
        for k in (0..m).filter(|&k| sums.accepted[k] > 0) {
            s.radiance[ends.estimate[k] as usize] += lane(&share, k);
        }
    }
    // a scene without lights is all "visible" (nothing to shadow)
    for v in &mut visible[..m] {
        *v = if lights.is_empty() { 1.0 } else { *v / lights.len() as f64 };
    }
    for (&e, &v) in ends.estimate[..m].iter().zip(&visible) {
        s.visible[e as usize] += v;
    }
    s.ends.len = 0;
    traced
}
