//! Rays traced together (Wald et al. 2001, "Interactive rendering with coherent ray
//! tracing"): runs of up to [`WIDTH`] rays in structure-of-arrays form, each query (a BVH
//! box, a shape, a plane) one loop over the lanes that the compiler vectorizes. One pixel's
//! rays leave from nearly one point in nearly one direction, so they visit nearly the same
//! nodes, and a node or shape is tested once for all of them.
//!
//! The queries are compiled for AVX-512 or AVX2 where the processor has them, chosen at run
//! time (`samplab::simd::wide`), with the same bits on each.

use glam::DVec3;

use samplab::simd::wide;

use crate::geometry::{Aabb, Ray, Shape, disk_hit, edge_hit, sphere_hit};

/// Most rays in one packet, and the lanes of the renderer's camera, end and shadow stages:
/// on sphere-box.xml at 64 estimates per pixel, 64 rendered 4% faster than 32 (one camera
/// packet per pixel, half the shadow packets) and 16 was 11% slower than 32; a
/// 1-million-triangle mesh at 16 estimates per pixel takes the same time at 32 and 64.
pub(crate) const WIDTH: usize = 64;

/// `f(start, packet)` for the packets of `rays[start..start + WIDTH]` in turn, compiled wide
/// ([`wide`]; `f` must be `#[inline(always)]`).
#[inline(always)]
pub(crate) fn packets(rays: &[Ray], mut f: impl FnMut(usize, &Packet)) {
    wide(
        #[inline(always)]
        || {
            // one packet refilled: lanes past a short chunk's length are never read
            let mut p = Packet::default();
            for (k, chunk) in rays.chunks(WIDTH).enumerate() {
                p.load(chunk);
                f(k * WIDTH, &p);
            }
        },
    );
}

/// Up to [`WIDTH`] rays in structure-of-arrays form, with their inverse directions for the
/// box tests: lanes are [`Packet::set`], then the packet is [`Packet::seal`]ed.
pub(crate) struct Packet {
    len: usize,
    o: [[f64; WIDTH]; 3],
    d: [[f64; WIDTH]; 3],
    inv: [[f64; WIDTH]; 3],
    time: [f64; WIDTH],
}

impl Default for Packet {
    /// A packet of no rays.
    #[inline(always)]
    fn default() -> Packet {
        Packet { len: 0, o: [[0.0; WIDTH]; 3], d: [[0.0; WIDTH]; 3], inv: [[0.0; WIDTH]; 3], time: [0.0; WIDTH] }
    }
}

impl Packet {
    /// Put `ray` in lane `i` (below [`WIDTH`]).
    #[inline(always)]
    pub(crate) fn set(&mut self, i: usize, ray: &Ray) {
        for k in 0..3 {
            self.o[k][i] = ray.origin[k];
            self.d[k][i] = ray.dir[k];
        }
        self.time[i] = ray.time;
    }

    /// Make the packet lanes `0..len` (each [`Packet::set`] since the last seal) and compute
    /// their inverse directions.
    #[inline(always)]
    pub(crate) fn seal(&mut self, len: usize) {
        self.len = len.min(WIDTH);
        // whole rows, so that the divisions run in vector lanes
        for (inv, d) in self.inv.iter_mut().zip(&self.d) {
            for (a, b) in inv[..self.len].iter_mut().zip(d) {
                *a = 1.0 / b;
            }
        }
    }

    /// Make this the packet of `rays` (at most [`WIDTH`]).
    #[inline(always)]
    pub(crate) fn load(&mut self, rays: &[Ray]) {
        let rays = &rays[..rays.len().min(WIDTH)];
        for (i, ray) in rays.iter().enumerate() {
            self.set(i, ray);
        }
        self.seal(rays.len());
    }

    /// Ray `i`.
    #[inline(always)]
    pub(crate) fn ray(&self, i: usize) -> Ray {
        Ray { origin: self.origin(i), dir: self.dir(i), time: self.time[i] }
    }

    /// The number of rays.
    #[inline(always)]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    #[inline(always)]
    fn origin(&self, i: usize) -> DVec3 {
        DVec3::new(self.o[0][i], self.o[1][i], self.o[2][i])
    }

    /// Direction of ray `i`.
    #[inline(always)]
    pub(crate) fn dir(&self, i: usize) -> DVec3 {
        DVec3::new(self.d[0][i], self.d[1][i], self.d[2][i])
    }

    /// Whether any ray meets the box before its own `t[i]` (slab test; a ray with
    /// t[i] = -inf meets nothing).
    #[inline(always)]
    pub(crate) fn meets(&self, b: &Aabb, t: &[f64]) -> bool {
        let m = self.len();
        let t = &t[..m];
        let (ix, iy, iz) = (&self.inv[0][..m], &self.inv[1][..m], &self.inv[2][..m]);
        let (ox, oy, oz) = (&self.o[0][..m], &self.o[1][..m], &self.o[2][..m]);
        let mut any = false;
        for i in 0..m {
            let (x0, x1) = ((b.min.x - ox[i]) * ix[i], (b.max.x - ox[i]) * ix[i]);
            let (y0, y1) = ((b.min.y - oy[i]) * iy[i], (b.max.y - oy[i]) * iy[i]);
            let (z0, z1) = ((b.min.z - oz[i]) * iz[i], (b.max.z - oz[i]) * iz[i]);
            let near = x0.min(x1).max(y0.min(y1)).max(z0.min(z1)).max(0.0);
            let far = x0.max(x1).min(y0.max(y1)).min(z0.max(z1)).min(t[i]);
            any |= near <= far;
        }
        any
    }

    /// Test every ray against `shape` (index `index`) in (t_min, t[i]): a nearer hit sets
    /// t[i] and hit[i], or with `ANY` (shadow rays) sets t[i] = -inf, "blocked".
    #[inline(always)]
    pub(crate) fn shape<const ANY: bool>(&self, shape: &Shape, index: u32, t_min: f64, t: &mut [f64], hit: &mut [u32]) {
        match *shape {
            Shape::Sphere { centre, radius, velocity } => self.each::<ANY>(index, t, hit, |o, d, time, t_max| {
                sphere_hit(centre, radius, velocity, o, d, time, t_min, t_max)
            }),
            Shape::Parallelogram { corner, u, v } => {
                self.each::<ANY>(index, t, hit, |o, d, _, t_max| edge_hit(corner, u, v, true, o, d, t_min, t_max))
            }
            Shape::Disk { centre, normal, radius } => {
                self.each::<ANY>(index, t, hit, |o, d, _, t_max| disk_hit(centre, normal, radius, o, d, t_min, t_max))
            }
            Shape::Triangle { p, e1, e2 } => {
                self.each::<ANY>(index, t, hit, |o, d, _, t_max| edge_hit(p, e1, e2, false, o, d, t_min, t_max))
            }
        }
    }

    /// For each ray, `f(origin, dir, time, t[i])` (a hit in (t_min, t[i]) or infinity),
    /// kept as [`Packet::shape`] says.
    #[inline(always)]
    pub(crate) fn each<const ANY: bool>(
        &self,
        index: u32,
        t: &mut [f64],
        hit: &mut [u32],
        f: impl Fn(DVec3, DVec3, f64, f64) -> f64,
    ) {
        let m = self.len();
        let (t, hit, time) = (&mut t[..m], &mut hit[..m], &self.time[..m]);
        for i in 0..m {
            let c = f(self.origin(i), self.dir(i), time[i], t[i]);
            if c < t[i] {
                if ANY {
                    t[i] = f64::NEG_INFINITY;
                } else {
                    t[i] = c;
                    hit[i] = index;
                }
            }
        }
    }
}
