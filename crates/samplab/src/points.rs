//! [`PointSet`]: n points in d dimensions, f64, row-major.

use crate::error::{Error, Result};

/// `n` points of `dims` coordinates each, stored row-major (point i is `data[i*dims..(i+1)*dims]`).
///
/// Samplers produce points in the half-open unit cube [0,1)^d; warped sets live in the
/// warp's own domain (a disk, a hemisphere, the real line), so the type itself only
/// guarantees that every coordinate is finite.
#[derive(Debug, Clone, PartialEq)]
pub struct PointSet {
    dims: usize,
    data: Vec<f64>,
}

impl PointSet {
    /// A point set from row-major coordinates.
    ///
    /// # Errors
    /// `dims` is zero, `data.len()` is not a multiple of `dims`, or a coordinate is not finite.
    pub fn new(dims: usize, data: Vec<f64>) -> Result<Self> {
        if dims == 0 {
            return Err(Error::TooFew { what: "a point set".into(), least: 1, of: "dimension", got: 0 });
        }
        if !data.len().is_multiple_of(dims) {
            return Err(Error::Mismatch {
                what: format!("{} coordinates", data.len()),
                expected: format!("whole {dims}D points (a multiple of {dims})"),
                got: format!("{} over", data.len() % dims),
            });
        }
        if let Some(i) = data.iter().position(|x| !x.is_finite()) {
            return Err(Error::NotFinite {
                what: format!("point {} coordinate {}", i / dims, i % dims),
                value: data[i],
            });
        }
        Ok(PointSet { dims, data })
    }

    /// Internal constructor for data already known to be valid.
    pub(crate) fn from_raw(dims: usize, data: Vec<f64>) -> Self {
        debug_assert!(dims > 0 && data.len().is_multiple_of(dims));
        PointSet { dims, data }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.data.len() / self.dims
    }

    /// True when the set holds no point.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// Number of coordinates per point.
    pub fn dims(&self) -> usize {
        self.dims
    }

    /// Point `i` as a slice of `dims` coordinates. Panics if `i >= len()`.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.data[i * self.dims..(i + 1) * self.dims]
    }

    /// Iterate over the points.
    pub fn iter(&self) -> std::slice::ChunksExact<'_, f64> {
        self.data.chunks_exact(self.dims)
    }

    /// All coordinates, row-major.
    pub fn as_slice(&self) -> &[f64] {
        &self.data
    }

    /// Consume the set, returning its row-major coordinates.
    pub fn into_vec(self) -> Vec<f64> {
        self.data
    }

    /// Coordinate `k` of every point.
    pub fn column(&self, k: usize) -> Vec<f64> {
        self.iter().map(|p| p[k]).collect()
    }

    /// True when every coordinate lies in [0, 1).
    pub fn in_unit_cube(&self) -> bool {
        self.data.iter().all(|x| (0.0..1.0).contains(x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_shapes_and_values() {
        assert!(PointSet::new(0, vec![]).is_err());
        assert!(PointSet::new(2, vec![0.1, 0.2, 0.3]).is_err());
        let e = PointSet::new(2, vec![0.1, f64::NAN]).unwrap_err();
        assert!(e.to_string().contains("point 0 coordinate 1"), "{e}");
        assert!(PointSet::new(2, vec![0.1, f64::INFINITY]).is_err());
    }

    #[test]
    fn row_major_access() {
        let p = PointSet::new(2, vec![0.1, 0.2, 0.3, 0.4]).unwrap();
        assert_eq!(p.len(), 2);
        assert_eq!(p.point(1), &[0.3, 0.4]);
        assert_eq!(p.column(0), vec![0.1, 0.3]);
        assert!(p.in_unit_cube());
    }
}
