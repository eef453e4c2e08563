//! Cascaded Sobol' (Paulin, Coeurjolly, Iehl, Bonneel, Keller & Ostromoukhov 2021): 2^m
//! points whose every pair of consecutive dimensions is a (0, m, 2)-net in base 2.
//!
//! Dimension 0 is a 1D Sobol' net of the point's index. Each later dimension is a 1D
//! Sobol' net too, drawn not at the point's index but at the previous coordinate's first m
//! digits read as an index, its first digit the most significant: the coordinate is
//! x_d = C_d idx_d with idx_d = R_m (x_(d-1) truncated to m digits), R_m reversing m digits.
//! Every step is linear over GF(2), so dimension d is a digital net whose matrix is
//! G_d = C_d R_m G_(d-1), G_0 = C_0: a net of its own for each m (the points are not a
//! sequence). A pair (d - 1, d) is a (0, m, 2)-net whenever the 1D matrices' top-left
//! blocks are invertible (upper unit-triangular, as every Sobol' matrix is): the first k
//! digits of x_(d-1) and the first m - k of x_d then determine every digit of x_(d-1).
//! The paper's contribution is the choice of the 1D generators C_d (its published table),
//! which make the projections beyond consecutive pairs good as well; any table of
//! direction numbers gives the construction, Joe & Kuo's by default.

/// The generating matrices of the cascade of `generators` at 2^m points: dimension d's
/// 32 columns (column k multiplies the index's digit k, row 0 the most significant bit;
/// the columns from m on are zero, as no index below 2^m reaches them). Each generator is
/// a dimension's 32 direction numbers.
///
/// # Panics
/// When `m` exceeds 32.
pub fn matrices(generators: impl IntoIterator<Item = [u32; 32]>, m: usize) -> Vec<[u32; 32]> {
    assert!(m <= 32, "2^{m} points: at most 2^32");
    let mut out: Vec<[u32; 32]> = Vec::new();
    for c in generators {
        let g = match out.last() {
            // the first dimension draws at the index itself
            None => std::array::from_fn(|k| if k < m { c[k] } else { 0 }),
            // the next: C times the previous column's first m digits, reversed
            Some(previous) => previous
                .map(|column| (0..m).filter(|&j| column >> (31 - (m - 1 - j)) & 1 == 1).fold(0, |x, j| x ^ c[j])),
        };
        out.push(g);
    }
    out
}
