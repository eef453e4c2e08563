//! A kinetic segment tree: the maximum over lines s_j t + k c_j at a time t that only
//! increases, with range additions to the integer counts c_j. O(log^2 n) amortized per
//! operation. Used by the exact 2D star discrepancy sweep.

/// Lines s_j t + k c_j over j = 0..m, with c_j integers changed by range additions.
pub(crate) struct KineticTree {
    size: usize,
    k: f64,
    t: f64,
    slope: Vec<f64>, // best line's slope per node
    count: Vec<i64>, // best line's count per node (lazy additions applied)
    melt: Vec<f64>,  // the earliest t at which the best line of the subtree may change
    lazy: Vec<i64>,
}

impl KineticTree {
    /// Lines with the given slopes and zero counts, at time `t0`; value = s t + k c.
    pub(crate) fn new(slopes: &[f64], k: f64, t0: f64) -> Self {
        let size = slopes.len().next_power_of_two();
        let mut tree = KineticTree {
            size,
            k,
            t: t0,
            slope: vec![f64::NEG_INFINITY; 2 * size],
            count: vec![0; 2 * size],
            melt: vec![f64::INFINITY; 2 * size],
            lazy: vec![0; 2 * size],
        };
        tree.slope[size..size + slopes.len()].copy_from_slice(slopes);
        for node in (1..size).rev() {
            tree.pull(node);
        }
        tree
    }

    #[inline]
    fn value(&self, node: usize) -> f64 {
        if self.slope[node] == f64::NEG_INFINITY {
            return f64::NEG_INFINITY; // padding leaf
        }
        self.slope[node] * self.t + self.k * self.count[node] as f64
    }

    fn pull(&mut self, node: usize) {
        let (l, r) = (2 * node, 2 * node + 1);
        let (vl, vr) = (self.value(l), self.value(r));
        let (best, other) = if vl > vr || (vl == vr && self.slope[l] >= self.slope[r]) { (l, r) } else { (r, l) };
        self.slope[node] = self.slope[best];
        self.count[node] = self.count[best];
        let mut melt = self.melt[l].min(self.melt[r]);
        if self.slope[other] > self.slope[best] {
            // the other line overtakes at t* = (b_best - b_other) / (s_other - s_best)
            melt = melt.min(self.t + (self.value(best) - self.value(other)) / (self.slope[other] - self.slope[best]));
        }
        self.melt[node] = melt;
    }

    fn push(&mut self, node: usize) {
        let add = std::mem::take(&mut self.lazy[node]);
        if add != 0 {
            for child in [2 * node, 2 * node + 1] {
                self.count[child] += add;
                self.lazy[child] += add;
            }
        }
    }

    /// Add `delta` to the counts of lines lo..hi.
    pub(crate) fn add(&mut self, lo: usize, hi: usize, delta: i64) {
        if lo < hi {
            self.add_rec(1, 0, self.size, lo, hi, delta);
        }
    }

    fn add_rec(&mut self, node: usize, nl: usize, nr: usize, lo: usize, hi: usize, delta: i64) {
        if hi <= nl || nr <= lo {
            return;
        }
        if lo <= nl && nr <= hi {
            // the same shift for every line keeps the order and the crossing times
            self.count[node] += delta;
            self.lazy[node] += delta;
            return;
        }
        self.push(node);
        let mid = (nl + nr) / 2;
        self.add_rec(2 * node, nl, mid, lo, hi, delta);
        self.add_rec(2 * node + 1, mid, nr, lo, hi, delta);
        self.pull(node);
    }

    /// Advance to time `t` (never backwards) and return the maximum value.
    pub(crate) fn max_at(&mut self, t: f64) -> f64 {
        debug_assert!(t >= self.t);
        self.t = t;
        self.heaten(1);
        self.value(1)
    }

    fn heaten(&mut self, node: usize) {
        if self.melt[node] > self.t || node >= self.size {
            return;
        }
        self.push(node);
        self.heaten(2 * node);
        self.heaten(2 * node + 1);
        self.pull(node);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::{Seed, below, uniform};

    #[test]
    fn matches_brute_force() {
        let mut rng = Seed(9).rng();
        for m in [1usize, 2, 3, 7, 16, 33] {
            let slopes: Vec<f64> = (0..m).map(|_| uniform(&mut rng)).collect();
            let k = -0.01;
            let mut tree = KineticTree::new(&slopes, k, 0.0);
            let mut counts = vec![0i64; m];
            let mut t = 0.0;
            for _ in 0..200 {
                let lo = below(&mut rng, m as u64) as usize;
                let hi = lo + 1 + below(&mut rng, (m - lo) as u64) as usize;
                tree.add(lo, hi, 1);
                counts[lo..hi].iter_mut().for_each(|c| *c += 1);
                t += 0.05 * uniform(&mut rng);
                let want =
                    slopes.iter().zip(&counts).map(|(s, &c)| s * t + k * c as f64).fold(f64::NEG_INFINITY, f64::max);
                assert!((tree.max_at(t) - want).abs() < 1e-12, "m {m}");
            }
        }
    }
}
