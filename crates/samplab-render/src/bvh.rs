//! A bounding volume hierarchy over the scene's shapes: binned surface-area-heuristic build
//! (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"), flattened
//! depth-first, traversed near child first for the closest hit and in any order for
//! shadow rays.

use glam::DVec3;

use crate::geometry::{Aabb, Ray, Shape};

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
        let objects = order.iter().map(|&i| objects[i as usize]).collect();
        Bvh { nodes: build.nodes, objects }
    }

    /// The objects, in traversal order.
    pub fn objects(&self) -> &[Object] {
        &self.objects
    }

    /// The box around everything.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    /// The ray parameter of the nearest hit in (t_min, t_max) and the object hit.
    pub fn closest(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, &Object)> {
        let mut best = None;
        let leaf = |first: usize, count: usize, t_now: &mut f64| {
            for o in &self.objects[first..first + count] {
                if let Some(t) = o.shape.intersect(ray, t_min, *t_now) {
                    *t_now = t;
                    best = Some((t, o));
                }
            }
            false
        };
        self.walk(ray.origin, ray.dir.recip(), leaf, t_max);
        best
    }

    /// Whether anything blocks the ray in (t_min, t_max).
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64) -> bool {
        let leaf = |first: usize, count: usize, _: &mut f64| {
            self.objects[first..first + count].iter().any(|o| o.shape.intersect(ray, t_min, t_max).is_some())
        };
        self.walk(ray.origin, ray.dir.recip(), leaf, t_max)
    }

    /// Visit the leaves the ray may reach, near child first; `leaf` returns true to stop
    /// and may shrink the search distance. Returns whether a leaf stopped the walk.
    #[inline]
    fn walk(
        &self,
        origin: DVec3,
        inv: DVec3,
        mut leaf: impl FnMut(usize, usize, &mut f64) -> bool,
        t_max: f64,
    ) -> bool {
        let Some(root) = self.nodes.first() else { return false };
        let mut t_max = t_max;
        if root.bounds.hit(origin, inv, t_max).is_none() {
            return false;
        }
        let mut stack = [0u32; 64];
        let mut top = 0;
        let mut at = 0usize;
        loop {
            let node = &self.nodes[at];
            if node.count > 0 {
                if leaf(node.index as usize, node.count as usize, &mut t_max) {
                    return true;
                }
            } else {
                let (a, b) = (at + 1, node.index as usize);
                let ta = self.nodes[a].bounds.hit(origin, inv, t_max);
                let tb = self.nodes[b].bounds.hit(origin, inv, t_max);
                match (ta, tb) {
                    (Some(x), Some(y)) => {
                        let (near, far) = if x <= y { (a, b) } else { (b, a) };
                        stack[top] = far as u32;
                        top += 1;
                        at = near;
                        continue;
                    }
                    (Some(_), None) => {
                        at = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        at = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            if top == 0 {
                return false;
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
    use samplab::seed::{Seed, uniform};

    #[test]
    fn closest_and_occluded_agree_with_testing_every_shape() {
        let mut rng = Seed(7).rng();
        let mut r = || uniform(&mut rng);
        let objects: Vec<Object> = (0..500)
            .map(|k| {
                let p = DVec3::new(r(), r(), r()) * 10.0;
                let shape = if k % 2 == 0 {
                    Shape::Sphere { centre: p, radius: 0.05 + 0.3 * r(), velocity: DVec3::ZERO }
                } else {
                    Shape::Triangle { p, e1: DVec3::new(r(), r(), r()) - 0.5, e2: DVec3::new(r(), r(), r()) - 0.5 }
                };
                Object { shape, material: k }
            })
            .collect();
        let bvh = Bvh::new(objects.clone());
        assert_eq!(bvh.objects().len(), objects.len());
        for _ in 0..2000 {
            let origin = DVec3::new(r(), r(), r()) * 12.0 - 1.0;
            let dir = DVec3::new(r(), r(), r()) - 0.5;
            let ray = Ray { origin, dir, time: 0.0 };
            let t_max = 5.0 + 50.0 * r();
            let brute = objects
                .iter()
                .filter_map(|o| o.shape.intersect(&ray, 0.0, t_max).map(|t| (t, o.material)))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            let fast = bvh.closest(&ray, 0.0, t_max).map(|(t, o)| (t, o.material));
            assert_eq!(brute, fast);
            assert_eq!(bvh.occluded(&ray, 0.0, t_max), brute.is_some());
        }
    }
}
