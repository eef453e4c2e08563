//! Spatial statistics of point sets, distances measured on the unit torus (the unit cube
//! with opposite faces identified, on which blue-noise sets are made and judged) or in the
//! cube: the smallest distance between two points, the relative radius of Lagae & Dutré
//! (2008), and the pair correlation function (PCF) by the Gaussian-kernel estimator of
//! Heck, Schlömer & Deussen (2013) and by the histogram estimator (the radial distribution
//! function, RDF).
//!
//! Pairs closer than a radius are found through a uniform grid of cells, each point
//! compared with the points of the neighbouring cells only: the PCF of 10^5 2D points up to
//! a few spacings visits O(n) pairs. Sums are formed per fixed chunk of points and added in
//! chunk order, so values do not depend on the thread count.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::points::PointSet;

/// Points per unit of parallel work (fixed: the sums' order depends on it alone).
const CHUNK: usize = 512;

/// Indices per block of [`buckets`].
pub(crate) const SORTED: usize = 1 << 15;

/// The first pass of a stable counting sort in parallel: per block of [`SORTED`] indices
/// into `keys`, the block's indices whose key is in each of `count` buckets
/// (`bucket(key)`), increasing.
pub(crate) fn buckets<K: Copy + Sync>(
    keys: &[K],
    count: usize,
    bucket: impl Fn(K) -> usize + Sync,
) -> Vec<Vec<Vec<u32>>> {
    keys.par_chunks(SORTED)
        .enumerate()
        // a task a block (and a run, and a chunk, below): rayon's own split leaves a thread
        // runs of several blocks, which the others cannot share once they are done
        .with_max_len(1)
        .map(|(b, block)| {
            let mut lists = vec![Vec::new(); count];
            for (i, &key) in (b * SORTED..).zip(block) {
                lists[bucket(key)].push(i as u32);
            }
            lists
        })
        .collect()
}

/// x - y for coordinates in [0, 1] on the circle of length 1: the signed gap in [-1/2, 1/2].
#[inline]
pub(crate) fn torus_gap(x: f64, y: f64) -> f64 {
    let t = x - y;
    if t > 0.5 {
        t - 1.0
    } else if t < -0.5 {
        t + 1.0
    } else {
        t
    }
}

/// Squared distance between two points, on the torus or in the cube.
#[inline]
pub(crate) fn distance2(a: &[f64], b: &[f64], torus: bool) -> f64 {
    a.iter()
        .zip(b)
        .map(|(&x, &y)| {
            let t = if torus { torus_gap(x, y) } else { x - y };
            t * t
        })
        .sum()
}

/// Points binned into k^d cells of side 1/k, copied in cell order (neighbours lie close
/// in memory): position q holds the point `ids[q]` of the input.
pub(crate) struct Grid {
    dims: usize,
    k: usize,
    /// The coordinates in cell order.
    coords: Vec<f64>,
    /// The input index of each position.
    pub(crate) ids: Vec<u32>,
    /// Cell c's points are at positions `start[c]..start[c + 1]`.
    start: Vec<usize>,
}

impl Grid {
    fn new(points: &[f64], dims: usize, k: usize) -> Grid {
        let n = points.len() / dims;
        let cells: Vec<usize> = points.par_chunks_exact(dims).map(|p| Grid::cell(k, p)).collect();
        let total = k.pow(dims as u32);
        // a stable counting sort in parallel: the points go by blocks of the input into
        // `ranges` runs of cells, then each run is sorted by cell on its own
        let ranges = (n / SORTED).clamp(1, 64);
        let lists = buckets(&cells, ranges, |c| c * ranges / total);
        // run r's positions in `ids` (from `offset`, in run order) and its cells' entries in
        // `start` (from its first cell on)
        let first = |r: usize| (r * total).div_ceil(ranges);
        let mut ids = vec![0u32; n];
        let mut start = vec![0usize; total + 1];
        start[total] = n;
        let mut runs = Vec::with_capacity(ranges);
        let (mut rest, mut starts, mut offset) = (&mut ids[..], &mut start[..total], 0);
        for r in 0..ranges {
            let size = lists.iter().map(|l| l[r].len()).sum();
            let (part, tail) = rest.split_at_mut(size);
            let (cells_of_run, later) = starts.split_at_mut(first(r + 1) - first(r));
            runs.push((r, part, cells_of_run, offset));
            (rest, starts, offset) = (tail, later, offset + size);
        }
        // per run, on its own: its cells' counts, their running sums (the first position of
        // each cell: points in earlier runs, then in the run's earlier cells), and its points
        // placed cell by cell
        runs.into_par_iter().with_max_len(1).for_each(|(r, part, cells_of_run, offset)| {
            let first = first(r);
            let mut at = vec![0usize; cells_of_run.len() + 1];
            let members = || lists.iter().flat_map(|l| l[r].iter().copied());
            for i in members() {
                at[cells[i as usize] - first + 1] += 1;
            }
            for c in 1..at.len() {
                at[c] += at[c - 1];
            }
            for (s, &a) in cells_of_run.iter_mut().zip(&at) {
                *s = offset + a;
            }
            for i in members() {
                let c = cells[i as usize] - first;
                part[at[c]] = i;
                at[c] += 1;
            }
        });
        let mut coords = vec![0.0; n * dims];
        coords.par_chunks_exact_mut(dims).zip(&ids).for_each(|(c, &i)| {
            c.copy_from_slice(&points[i as usize * dims..(i as usize + 1) * dims]);
        });
        Grid { dims, k, coords, ids, start }
    }

    /// The cell of a point among k^d cells of side 1/k (row-major, the last axis slowest).
    pub(crate) fn cell(k: usize, p: &[f64]) -> usize {
        p.iter().rev().fold(0, |c, &x| c * k + ((x * k as f64) as usize).min(k - 1))
    }

    /// Cells of side at least `reach` (at most about 4n of them): every pair closer than
    /// `reach` lies within one cell of each other.
    pub(crate) fn covering(points: &[f64], dims: usize, reach: f64) -> Grid {
        Grid::within(points, dims, reach, 1)
    }

    /// Cells of side at least `reach` / `ring` (at most about 4n of them): every pair closer
    /// than `reach` lies within `ring` cells of each other. Smaller cells and a wider ring
    /// compare fewer pairs beyond `reach` (in 2D, (2 ring + 1)^2 / ring^2 squares of `reach`
    /// for pi of them within).
    pub(crate) fn within(points: &[f64], dims: usize, reach: f64, ring: usize) -> Grid {
        let n = points.len() / dims;
        let fine = (ring as f64 / reach).floor().max(1.0) as usize;
        let coarse = ((4.0 * n as f64).powf(1.0 / dims as f64).floor() as usize).max(1);
        Grid::new(points, dims, fine.min(coarse))
    }

    /// Cells per axis.
    pub(crate) fn cells(&self) -> usize {
        self.k
    }

    /// How many points.
    pub(crate) fn len(&self) -> usize {
        self.ids.len()
    }

    /// The point at position q.
    #[inline]
    pub(crate) fn point(&self, q: usize) -> &[f64] {
        &self.coords[q * self.dims..(q + 1) * self.dims]
    }

    /// Every cell within `ring` cells of the cell of the point at position q along each
    /// axis, each once (wrapping around on the torus), as ranges of positions, in the order
    /// of the cells (the first axis fastest): the cells that follow one another along the
    /// first axis are consecutive in the positions too, so each such run of cells (one, or
    /// two where the torus wraps) is one range.
    pub(crate) fn near(&self, q: usize, ring: usize, torus: bool, mut visit: impl FnMut(std::ops::Range<usize>)) {
        let k = self.k;
        // per axis: the first cell and how many follow it (mod k on the torus); on the stack
        // up to 8 dimensions
        let (mut stack, mut at_stack) = ([(0usize, 0usize); 8], [0usize; 8]);
        let (mut heap, mut at_heap) = (Vec::new(), Vec::new());
        let (axes, at): (&mut [(usize, usize)], &mut [usize]) = if self.dims <= stack.len() {
            (&mut stack[..self.dims], &mut at_stack[..self.dims])
        } else {
            heap.resize(self.dims, (0, 0));
            at_heap.resize(self.dims, 0);
            (&mut heap, &mut at_heap)
        };
        for (axis, &x) in axes.iter_mut().zip(self.point(q)) {
            let c = ((x * k as f64) as usize).min(k - 1);
            *axis = if torus && 2 * ring + 1 >= k {
                (0, k)
            } else if torus {
                ((c + k - ring) % k, 2 * ring + 1)
            } else {
                let first = c.saturating_sub(ring);
                (first, (c + ring).min(k - 1) + 1 - first)
            };
        }
        // the first axis's cells as runs of consecutive cells: [first, end) and, where the
        // torus wraps, [0, rest)
        let (first, count) = axes[0];
        let runs =
            if first + count <= k { [(first, first + count), (0, 0)] } else { [(first, k), (0, first + count - k)] };
        loop {
            // the cells' index but for the first axis's part
            let row = axes[1..].iter().zip(&at[1..]).rev().fold(0, |c, (&(first, _), &a)| c * k + (first + a) % k) * k;
            for &(from, to) in runs.iter().filter(|(from, to)| from < to) {
                visit(self.start[row + from]..self.start[row + to]);
            }
            let mut axis = 1;
            loop {
                if axis == self.dims {
                    return;
                }
                at[axis] += 1;
                if at[axis] < axes[axis].1 {
                    break;
                }
                at[axis] = 0;
                axis += 1;
            }
        }
    }

    /// Whether `ring` cells around any cell reach every cell.
    fn covers(&self, ring: usize, torus: bool) -> bool {
        if torus { 2 * ring + 1 >= self.k } else { ring + 1 >= self.k }
    }
}

/// `visit(acc, d2)` for every pair of positions q < r whose cells lie within `ring` cells of
/// each other, one accumulator per chunk of q, returned in chunk order.
pub(crate) fn pairs<A: Send>(
    grid: &Grid,
    ring: usize,
    torus: bool,
    init: impl Fn() -> A + Sync,
    visit: impl Fn(&mut A, f64) + Sync,
) -> Vec<A> {
    indexed_pairs(grid, ring, torus, CHUNK, init, |acc, _, _, d2| visit(acc, d2))
}

/// [`pairs`] with the positions: `visit(acc, q, r, d2)`, one accumulator per `chunk`
/// positions q (a fixed size: the sums' order depends on it alone).
pub(crate) fn indexed_pairs<A: Send>(
    grid: &Grid,
    ring: usize,
    torus: bool,
    chunk: usize,
    init: impl Fn() -> A + Sync,
    visit: impl Fn(&mut A, usize, usize, f64) + Sync,
) -> Vec<A> {
    let n = grid.len();
    (0..n.div_ceil(chunk))
        .into_par_iter()
        .with_max_len(1)
        .map(|c| {
            let mut acc = init();
            for q in c * chunk..((c + 1) * chunk).min(n) {
                let p = grid.point(q);
                grid.near(q, ring, torus, |cell| {
                    for r in cell.start.max(q + 1)..cell.end {
                        visit(&mut acc, q, r, distance2(p, grid.point(r), torus));
                    }
                });
            }
            acc
        })
        .collect()
}

/// The smallest distance between two points of the set (infinite for fewer than 2).
///
/// Cells of side 1/k, k = n^(1/d) (all pairs above 4D): every pair within one cell of each
/// other is compared; a smallest distance m above 1/k is confirmed by comparing the pairs
/// within ceil(m k) cells (those farther apart are at least that far).
pub fn min_distance(points: &PointSet, torus: bool) -> f64 {
    let (n, dims) = (points.len(), points.dims());
    let k = if dims > 4 { 1 } else { ((n as f64).powf(1.0 / dims as f64).floor() as usize).max(1) };
    let grid = Grid::new(points.as_slice(), dims, k);
    let mut ring = 1;
    loop {
        let m = pairs(&grid, ring, torus, || f64::INFINITY, |m, d2| *m = m.min(d2))
            .into_iter()
            .fold(f64::INFINITY, f64::min)
            .sqrt();
        if grid.covers(ring, torus) || m <= ring as f64 / k as f64 {
            return m;
        }
        ring = (m * k as f64).ceil() as usize;
    }
}

/// The volume of the unit ball in d dimensions: V_0 = 1, V_1 = 2, V_d = 2 pi V_(d-2) / d.
pub fn unit_ball_volume(dims: usize) -> f64 {
    match dims {
        0 => 1.0,
        1 => 2.0,
        d => 2.0 * std::f64::consts::PI * unit_ball_volume(d - 2) / d as f64,
    }
}

/// The densest known packing densities of equal balls in 1..=8 dimensions (the lattices
/// Z, A2, A3, D4, D5, E6, E7, E8; optimal in 1, 2, 3 and 8 dimensions).
const PACKING_DENSITY: [f64; 8] = {
    use std::f64::consts::PI;
    [
        1.0,
        PI / 3.464_101_615_137_754_6, // pi / sqrt(12)
        PI / 4.242_640_687_119_285,   // pi / sqrt(18)
        PI * PI / 16.0,               // pi^2 / 16
        PI * PI / (15.0 * std::f64::consts::SQRT_2),
        PI * PI * PI / (48.0 * 1.732_050_807_568_877_2), // pi^3 / (48 sqrt 3)
        PI * PI * PI / 105.0,
        PI * PI * PI * PI / 384.0,
    ]
};

/// r_max: the radius of n equal balls packed at the densest known density in the unit
/// volume (Lagae & Dutré 2008; in 2D sqrt(1 / (2 sqrt(3) n)), the hexagonal packing).
///
/// # Errors
/// Dimensions outside 1..=8 (no packing density is tabulated here) or n = 0.
pub fn packing_radius(n: usize, dims: usize) -> Result<f64> {
    let what = || "the packing radius".to_string();
    if !(1..=PACKING_DENSITY.len()).contains(&dims) {
        return Err(Error::Dimension {
            what: what(),
            takes: format!("1 to {} dimensions", PACKING_DENSITY.len()),
            got: dims,
        });
    }
    if n == 0 {
        return Err(Error::TooFew { what: what(), least: 1, of: "point", got: n });
    }
    Ok((PACKING_DENSITY[dims - 1] / (n as f64 * unit_ball_volume(dims))).powf(1.0 / dims as f64))
}

/// Lagae & Dutré's relative radius: half the smallest distance (on the torus) over r_max,
/// in [0, 1] up to the packing bound.
///
/// # Errors
/// As [`packing_radius`], or fewer than 2 points.
pub fn relative_radius(points: &PointSet) -> Result<f64> {
    if points.len() < 2 {
        return Err(Error::TooFew { what: "the relative radius".into(), least: 2, of: "point", got: points.len() });
    }
    Ok(min_distance(points, true) / (2.0 * packing_radius(points.len(), points.dims())?))
}

/// The surface of the unit sphere in d dimensions, d V_d.
fn sphere_surface(dims: usize) -> f64 {
    dims as f64 * unit_ball_volume(dims)
}

/// Check the radii of a PCF: increasing, in (0, 1/2] (on the torus a sphere of radius up
/// to 1/2 does not meet itself; 0 too when `zero`), and a set of at least 2 points.
fn check_radii(points: &PointSet, radii: &[f64], zero: bool) -> Result<()> {
    if points.len() < 2 {
        return Err(Error::TooFew { what: "a pair correlation".into(), least: 2, of: "point", got: points.len() });
    }
    let setting = |value: String, reason: String| Error::Setting { name: "radii", value, reason };
    if let Some(r) = radii.iter().find(|&&r| !((r > 0.0 || (zero && r == 0.0)) && r <= 0.5)) {
        let range = if zero { "[0, 0.5]" } else { "(0, 0.5]" };
        return Err(setting(r.to_string(), format!("outside {range} (distances on the unit torus)")));
    }
    if let Some(w) = radii.windows(2).find(|w| w[0] >= w[1]) {
        return Err(setting(format!("{}, {}", w[0], w[1]), "the radii must increase".into()));
    }
    Ok(())
}

/// The pair correlation function on the torus at each of `radii` by the Gaussian-kernel
/// estimator of Heck, Schlömer & Deussen (2013):
///
///   g(r) = sum_(i != j) k(r - |x_i - x_j|) / (n (n - 1) S_d r^(d-1)),
///   k(t) = exp(-t^2 / sigma^2) / (sqrt(pi) sigma),
///
/// S_d the unit sphere's surface (2 pi in 2D). With n (n - 1) (the count of ordered pairs)
/// the estimate is unbiased for n independent uniform points wherever r > 3 sigma, exactly in
/// 2D (the kernel smooths the linear r^(d-1) without bias), within sigma^2 / (2 r^2) in 3D.
/// The kernel is cut at 6 sigma (a relative weight below 1e-15).
///
/// # Errors
/// Radii outside (0, 1/2] or not increasing, sigma not positive, fewer than 2 points.
pub fn pcf(points: &PointSet, radii: &[f64], sigma: f64) -> Result<Vec<f64>> {
    check_radii(points, radii, false)?;
    if !(sigma > 0.0 && sigma.is_finite()) {
        return Err(Error::Setting {
            name: "sigma",
            value: sigma.to_string(),
            reason: "the kernel width must be positive".into(),
        });
    }
    let Some(&last) = radii.last() else { return Ok(Vec::new()) };
    let cut = 6.0 * sigma;
    let reach = last + cut;
    // coincident points once each, with their counts: a pile of equal points is one point,
    // not n^2 / 2 pairs at distance 0 in one cell
    let distinct = distinct(points);
    let (coords, weights) = match &distinct {
        Some((coords, weights)) => (coords.as_slice(), Some(weights.as_slice())),
        None => (points.as_slice(), None),
    };
    let weight = |i: u32| weights.map_or(1.0, |w| w[i as usize]);
    let grid = Grid::covering(coords, points.dims(), reach);
    let norm = 1.0 / (std::f64::consts::PI.sqrt() * sigma);
    // evenly spaced radii (to 1e-12 of their range): the kernel by a recurrence
    let spacing = if radii.len() > 1 { (last - radii[0]) / (radii.len() - 1) as f64 } else { 0.0 };
    let even = (radii.len() > 2
        && radii.iter().enumerate().all(|(b, &r)| (r - radii[0] - b as f64 * spacing).abs() <= 1e-12 * last))
    .then_some(spacing / sigma);
    let step = even.map_or(1.0, |delta| (-2.0 * delta * delta).exp());
    // a pair at squared distance d2 counted `w` times
    let add = |acc: &mut [f64], d2: f64, w: f64| {
        if d2 >= reach * reach {
            return;
        }
        let d = d2.sqrt();
        let (from, to) = (radii.partition_point(|&r| r < d - cut), radii.partition_point(|&r| r <= d + cut));
        if from == to {
            return;
        }
        match even {
            // exp(-(t + delta)^2) = exp(-t^2) exp(-2 t delta - delta^2): two exponentials
            // per pair, then products
            Some(delta) => {
                let t = (radii[from] - d) / sigma;
                let (mut g, mut q) = ((-t * t).exp(), (-(2.0 * t + delta) * delta).exp());
                for a in &mut acc[from..to] {
                    *a += w * g;
                    g *= q;
                    q *= step;
                }
            }
            None => {
                for (a, &r) in acc[from..to].iter_mut().zip(&radii[from..to]) {
                    let t = (r - d) / sigma;
                    *a += w * (-t * t).exp();
                }
            }
        }
    };
    let mut parts = indexed_pairs(
        &grid,
        1,
        true,
        CHUNK,
        || vec![0.0; radii.len()],
        |acc, q, r, d2| add(acc, d2, weight(grid.ids[q]) * weight(grid.ids[r])),
    );
    if let Some(weights) = weights {
        // the pairs within each pile, at distance 0
        let mut own = vec![0.0; radii.len()];
        add(&mut own, 0.0, weights.iter().map(|&w| w * (w - 1.0) / 2.0).sum());
        parts.push(own);
    }
    let n = points.len() as f64;
    let surface = sphere_surface(points.dims());
    Ok(radii
        .iter()
        .enumerate()
        .map(|(b, &r)| {
            // each unordered pair stands for two ordered ones
            let sum: f64 = parts.iter().map(|p| p[b]).sum();
            2.0 * sum * norm / (n * (n - 1.0) * surface * r.powi(points.dims() as i32 - 1))
        })
        .collect())
}

/// The distinct points of `points` (coordinates, in the order of their first occurrence)
/// and how many times each occurs; `None` when no two are equal.
fn distinct(points: &PointSet) -> Option<(Vec<f64>, Vec<f64>)> {
    let (data, dims) = (points.as_slice(), points.dims());
    let point = |i: usize| &data[i * dims..(i + 1) * dims];
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.par_sort_by(|&a, &b| {
        point(a)
            .iter()
            .zip(point(b))
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
            .then(a.cmp(&b))
    });
    let same = |a: usize, b: usize| point(a).iter().zip(point(b)).all(|(x, y)| x.to_bits() == y.to_bits());
    if order.windows(2).all(|w| !same(w[0], w[1])) {
        return None;
    }
    // each point's first occurrence, then the piles in that order
    let mut first = vec![0usize; points.len()];
    let mut start = 0;
    for (at, &i) in order.iter().enumerate() {
        if at > 0 && !same(order[at - 1], i) {
            start = at;
        }
        first[i] = order[start];
    }
    let (mut coords, mut weights, mut slot) = (Vec::new(), Vec::new(), vec![usize::MAX; points.len()]);
    for &f in &first {
        if slot[f] == usize::MAX {
            slot[f] = weights.len();
            coords.extend_from_slice(point(f));
            weights.push(0.0);
        }
        weights[slot[f]] += 1.0;
    }
    Some((coords, weights))
}

/// The radial distribution function on the torus: the histogram estimator of the PCF over
/// the shells between consecutive `edges`, each the count of ordered pairs at a distance in
/// [e_b, e_(b+1)) over n (n - 1) times the shell's volume (1 for independent uniform points).
///
/// # Errors
/// Edges outside [0, 1/2] or not increasing (fewer than 2 give no shells), fewer than 2 points.
pub fn rdf(points: &PointSet, edges: &[f64]) -> Result<Vec<f64>> {
    check_radii(points, edges, true)?;
    if edges.len() < 2 {
        return Ok(Vec::new());
    }
    let reach = edges[edges.len() - 1];
    let grid = Grid::covering(points.as_slice(), points.dims(), reach);
    let parts = pairs(
        &grid,
        1,
        true,
        || vec![0u64; edges.len() - 1],
        |acc, d2| {
            let d = d2.sqrt();
            let b = edges.partition_point(|&e| e <= d);
            if b >= 1 && b < edges.len() {
                acc[b - 1] += 1;
            }
        },
    );
    let n = points.len() as f64;
    let dims = points.dims() as i32;
    let ball = unit_ball_volume(points.dims());
    Ok(edges
        .windows(2)
        .enumerate()
        .map(|(b, w)| {
            let count: u64 = parts.iter().map(|p| p[b]).sum();
            2.0 * count as f64 / (n * (n - 1.0) * ball * (w[1].powi(dims) - w[0].powi(dims)))
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The grid of a parallel counting sort in runs against one stable sort of the
    /// indices by cell: positions, cell starts and coordinates, on 1 and 3 threads.
    #[test]
    fn grids_are_one_stable_sort_by_cell() {
        for (dims, n, k) in [(2, 3 * SORTED + 17, 300), (3, 2 * SORTED + 5, 37), (1, SORTED / 3, 1000), (2, 5, 1)] {
            let points = crate::sampler::build("random").unwrap().generate(n, dims, crate::Seed(n as u64)).unwrap();
            let points = points.as_slice();
            let cells: Vec<usize> = points.chunks_exact(dims).map(|p| Grid::cell(k, p)).collect();
            let mut order: Vec<u32> = (0..n as u32).collect();
            order.sort_by_key(|&i| cells[i as usize]);
            let total = k.pow(dims as u32);
            let mut start = vec![0; total + 1];
            cells.iter().for_each(|&c| start[c + 1] += 1);
            (1..=total).for_each(|c| start[c] += start[c - 1]);
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let grid = pool.install(|| Grid::new(points, dims, k));
                assert_eq!(grid.ids, order, "{dims}D, {n} points, {threads} threads");
                assert_eq!(grid.start, start, "{dims}D, {n} points, {threads} threads");
                for (q, &i) in order.iter().enumerate() {
                    assert_eq!(grid.point(q), &points[i as usize * dims..(i as usize + 1) * dims]);
                }
            }
        }
    }
}
