//! A bounding volume hierarchy over the scene's shapes: binned surface-area-heuristic build
//! (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"), flattened
//! depth-first, traced by packets of rays (crate::packet).

use glam::DVec3;

use crate::geometry::{Aabb, Normal, Shape};
use crate::packet::Packet;

/// A shape and the index of its material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Object {
    /// The geometry.
    pub shape: Shape,
    /// Index into the scene's materials.
    pub material: u32,
}

#[derive(Debug, Clone, Copy)]
struct Node {
    bounds: Aabb,
    /// Leaf: first object; inner: index of the second child (the first follows the node).
    index: u32,
    /// Objects in a leaf; 0 for an inner node.
    count: u32,
}

/// The hierarchy; owns the objects in traversal order.
#[derive(Debug, Clone, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    objects: Vec<Object>,
    /// Each object's normal, prepared.
    normals: Vec<Normal>,
}

const BINS: usize = 16;
const LEAF_SIZE: usize = 4;
/// Cost of one shape test relative to one node visit.
const SHAPE_COST: f64 = 1.0;
const NODE_COST: f64 = 1.0;

struct Build {
    bounds: Vec<Aabb>,
    centres: Vec<DVec3>,
    nodes: Vec<Node>,
}

impl Bvh {
    /// Build the hierarchy (O(n log n)).
    pub fn new(objects: Vec<Object>) -> Bvh {
        if objects.is_empty() {
            return Bvh::default();
        }
        let bounds: Vec<Aabb> = objects.iter().map(|o| o.shape.bounds()).collect();
        let centres = bounds.iter().map(Aabb::centre).collect();
        let mut order: Vec<u32> = (0..objects.len() as u32).collect();
        let mut build = Build { bounds, centres, nodes: Vec::with_capacity(2 * objects.len() / LEAF_SIZE + 1) };
        build.split(&mut order, 0);
        let objects: Vec<Object> = order.iter().map(|&i| objects[i as usize]).collect();
        let normals = objects.iter().map(|o| Normal::of(&o.shape)).collect();
        Bvh { nodes: build.nodes, objects, normals }
    }

    /// The objects, in traversal order.
    pub fn objects(&self) -> &[Object] {
        &self.objects
    }

    /// The unit geometric normal of object `i` (in traversal order) at its surface point
    /// `p` at shutter `time`, not flipped toward any ray.
    #[inline(always)]
    pub fn normal(&self, i: usize, p: DVec3, time: f64) -> DVec3 {
        self.normals[i].at(p, time)
    }

    /// The box around everything.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// Trace a packet: each ray's nearest hit in (t_min, t[i]) sets t[i] and hit[i] (the
    /// index in [`Bvh::objects`]); with `ANY` (shadow rays) any hit sets t[i] = -inf. The
    /// packet descends into a node when any of its rays meets the node's box, nearer child
    /// first along the first ray's direction, and a shadow packet stops when every ray is
    /// blocked.
    #[inline(always)]
    pub(crate) fn trace<const ANY: bool>(&self, p: &Packet, t_min: f64, t: &mut [f64], hit: &mut [u32]) {
        let Some(root) = self.nodes.first() else { return };
        if !p.meets(&root.bounds, t) {
            return;
        }
        let d0 = p.dir(0);
        let mut stack = [0u32; 64];
        let mut top = 0;
        let mut at = 0usize;
        loop {
            let node = &self.nodes[at];
            if node.count > 0 {
                let first = node.index as usize;
                for (k, o) in self.objects[first..first + node.count as usize].iter().enumerate() {
                    p.shape::<ANY>(&o.shape, (first + k) as u32, t_min, t, hit);
                }
                if ANY && t[..p.len()].iter().all(|&x| x == f64::NEG_INFINITY) {
                    return;
                }
            } else {
                let (a, b) = (at + 1, node.index as usize);
                let (na, nb) = (&self.nodes[a].bounds, &self.nodes[b].bounds);
                match (p.meets(na, t), p.meets(nb, t)) {
                    (true, true) => {
                        let (near, far) = if (nb.centre() - na.centre()).dot(d0) >= 0.0 { (a, b) } else { (b, a) };
                        stack[top] = far as u32;
                        top += 1;
                        at = near;
                        continue;
                    }
                    (true, false) => {
                        at = a;
                        continue;
                    }
                    (false, true) => {
                        at = b;
                        continue;
                    }
                    (false, false) => {}
                }
            }
            if top == 0 {
                return;
            }
            top -= 1;
            at = stack[top] as usize;
        }
    }
}

impl Build {
    /// Emit the node for `order` (objects `first..first + order.len()` in the final order).
    fn split(&mut self, order: &mut [u32], first: usize) {
        let bounds = order.iter().fold(Aabb::EMPTY, |b, &i| b.union(self.bounds[i as usize]));
        let at = self.nodes.len();
        self.nodes.push(Node { bounds, index: first as u32, count: order.len() as u32 });
        if order.len() <= LEAF_SIZE {
            return;
        }
        let Some(mid) = self.partition(order, &bounds) else { return };
        let (left, right) = order.split_at_mut(mid);
        self.split(left, first);
        let second = self.nodes.len();
        self.split(right, first + mid);
        self.nodes[at].index = second as u32;
        self.nodes[at].count = 0;
    }

    /// Reorder `order` by the best binned SAH split and return the split position, or None
    /// when a leaf is cheaper.
    fn partition(&self, order: &mut [u32], bounds: &Aabb) -> Option<usize> {
        let cb = order.iter().fold(Aabb::EMPTY, |b, &i| b.grow(self.centres[i as usize]));
        let extent = cb.max - cb.min;
        let mut best: Option<(f64, usize, usize)> = None; // cost, axis, bin boundary
        for axis in 0..3 {
            if extent[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f64 / extent[axis];
            let bin_of = |i: u32| (((self.centres[i as usize][axis] - cb.min[axis]) * scale) as usize).min(BINS - 1);
            let mut boxes = [Aabb::EMPTY; BINS];
            let mut counts = [0usize; BINS];
            for &i in order.iter() {
                let b = bin_of(i);
                boxes[b] = boxes[b].union(self.bounds[i as usize]);
                counts[b] += 1;
            }
            // right-to-left sweep for the right-hand costs, then left-to-right
            let mut right_cost = [0.0; BINS];
            let (mut acc, mut n) = (Aabb::EMPTY, 0);
            for b in (1..BINS).rev() {
                acc = acc.union(boxes[b]);
                n += counts[b];
                right_cost[b] = acc.half_area() * n as f64;
            }
            let (mut acc, mut n) = (Aabb::EMPTY, 0);
            for b in 0..BINS - 1 {
                acc = acc.union(boxes[b]);
                n += counts[b];
                if n == 0 || n == order.len() {
                    continue;
                }
                let cost = acc.half_area() * n as f64 + right_cost[b + 1];
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, axis, b + 1));
                }
            }
        }
        let (cost, axis, boundary) = best?;
        let leaf_cost = order.len() as f64 * SHAPE_COST;
        let split_cost = NODE_COST + SHAPE_COST * cost / bounds.half_area().max(f64::MIN_POSITIVE);
        if split_cost >= leaf_cost && order.len() <= 16 * LEAF_SIZE {
            return None;
        }
        let scale = BINS as f64 / extent[axis];
        let mut mid = 0;
        for k in 0..order.len() {
            let i = order[k];
            let b = (((self.centres[i as usize][axis] - cb.min[axis]) * scale) as usize).min(BINS - 1);
            if b < boundary {
                order.swap(k, mid);
                mid += 1;
            }
        }
        Some(mid)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Ray;
    use crate::packet::{Packet, WIDTH};
    use samplab::seed::{Seed, uniform};
    use samplab::simd::on_each_instruction_set;

    #[test]
    fn packets_find_what_testing_every_shape_finds() {
        let mut rng = Seed(7).rng();
        let mut r = || uniform(&mut rng);
        let objects: Vec<Object> = (0..500)
            .map(|k| {
                let p = DVec3::new(r(), r(), r()) * 10.0;
                let shape = match k % 4 {
                    0 => Shape::Sphere { centre: p, radius: 0.05 + 0.3 * r(), velocity: DVec3::new(r(), 0.0, 0.0) },
                    1 => Shape::Disk { centre: p, normal: DVec3::new(r(), r(), 0.5).normalize(), radius: 0.4 * r() },
                    2 => Shape::Parallelogram { corner: p, u: DVec3::new(r(), 0.0, r()) - 0.5, v: DVec3::Y * r() },
                    _ => {
                        Shape::Triangle { p, e1: DVec3::new(r(), r(), r()) - 0.5, e2: DVec3::new(r(), r(), r()) - 0.5 }
                    }
                };
                Object { shape, material: k }
            })
            .collect();
        let bvh = Bvh::new(objects.clone());
        assert_eq!(bvh.objects().len(), objects.len());
        // packets of 1 to WIDTH rays, some from one point in nearby directions (a pixel's
        // rays), some unrelated, each with its own limit and time
        for size in [1, 3, 17, WIDTH, WIDTH, WIDTH] {
            for coherent in [true, false] {
                let mut rays = Vec::new();
                let mut t_max = Vec::new();
                let (origin, dir) = (DVec3::new(r(), r(), r()) * 12.0 - 1.0, DVec3::new(r(), r(), r()) - 0.5);
                for _ in 0..size {
                    let ray = if coherent {
                        Ray { origin, dir: dir + 0.05 * (DVec3::new(r(), r(), r()) - 0.5), time: r() }
                    } else {
                        Ray {
                            origin: DVec3::new(r(), r(), r()) * 12.0 - 1.0,
                            dir: DVec3::new(r(), r(), r()) - 0.5,
                            time: r(),
                        }
                    };
                    rays.push(ray);
                    t_max.push(5.0 + 50.0 * r());
                }
                let runs = on_each_instruction_set(
                    #[inline(always)]
                    || {
                        let mut p = Packet::default();
                        p.load(&rays);
                        let (mut t, mut hit) = ([0.0; WIDTH], [u32::MAX; WIDTH]);
                        t[..size].copy_from_slice(&t_max);
                        bvh.trace::<false>(&p, 0.0, &mut t, &mut hit);
                        let mut blocked = [0.0; WIDTH];
                        blocked[..size].copy_from_slice(&t_max);
                        bvh.trace::<true>(&p, 0.0, &mut blocked, &mut [0; WIDTH]);
                        (t.map(f64::to_bits), hit, blocked.map(f64::to_bits))
                    },
                );
                // the same bits on every instruction set
                assert!(runs.iter().all(|r| *r == runs[0]));
                let (t, hit, blocked) = (runs[0].0.map(f64::from_bits), runs[0].1, runs[0].2.map(f64::from_bits));
                for i in 0..size {
                    let ray = rays[i];
                    let brute = objects
                        .iter()
                        .filter_map(|o| o.shape.intersect(&ray, 0.0, t_max[i]).map(|t| (t, o.material)))
                        .min_by(|a, b| a.0.total_cmp(&b.0));
                    let fast = (hit[i] != u32::MAX).then(|| (t[i], bvh.objects()[hit[i] as usize].material));
                    assert_eq!(brute, fast);
                    assert_eq!(blocked[i] == f64::NEG_INFINITY, brute.is_some());
                }
            }
        }
    }
}
