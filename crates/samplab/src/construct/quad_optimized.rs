//! The quad-optimized low-discrepancy sequences in base 3 (Ostromoukhov, Bonneel, Coeurjolly
//! & Iehl 2024): Sobol's construction carried to GF(3), each dimension from a monic
//! irreducible polynomial over GF(3) and initial numbers the authors chose by optimization
//! (`data/quad-optimized-gf3.txt`, their published table, 48 dimensions).
//!
//! Dimension j with polynomial x^s + p_{s-1} x^{s-1} + ... + p_0 and initial numbers
//! m_1 .. m_s (m_k has k base-3 digits) continues them by Sobol's recurrence in base 3, digit
//! by digit without carries (the authors' `generate_mkGF3`):
//! m_k = m_{k-s} + sum_{i=1..s} 3^i (-p_{s-i}) m_{k-i}  (mod 3 in every digit).
//! Column k of the generating matrix holds the digits of m_{k+1}: row r the digit of weight
//! 3^(k-r), so row 0 is the most significant and the diagonal the last digit (never 0).
//! The authors' code stops at 10 columns, 3^10 = 59,049 points, and so does samplab: each pair
//! of dimensions (2k, 2k + 1) is a (0, m, 2)-net in base 3 for every m up to 10, and the same
//! recurrence carried further loses that for most pairs (measured to 20 columns: t up to 4).

/// The authors' table, as published.
const TABLE: &str = include_str!("../../data/quad-optimized-gf3.txt");

/// How many dimensions the table holds.
pub const QUAD_OPTIMIZED_MAX_DIMS: usize = 48;

/// The columns (and rows) of each matrix: 3^10 points, as far as the authors built them.
pub const QUAD_OPTIMIZED_COLUMNS: usize = 10;

/// The generating matrices of the first `dims` dimensions: entry `[j][k][r]` is the digit in
/// row r, column k of dimension j, [`QUAD_OPTIMIZED_COLUMNS`] of each.
///
/// # Panics
/// When `dims` exceeds [`QUAD_OPTIMIZED_MAX_DIMS`] (the table itself is checked by the tests).
pub fn matrices(dims: usize) -> Vec<Vec<Vec<u8>>> {
    let cols = QUAD_OPTIMIZED_COLUMNS;
    assert!(dims <= QUAD_OPTIMIZED_MAX_DIMS, "{dims} dimensions: the table holds {QUAD_OPTIMIZED_MAX_DIMS}");
    TABLE
        .lines()
        .filter(|l| !l.starts_with('#') && !l.starts_with('d'))
        .take(dims)
        .map(|line| {
            let f: Vec<u64> = line.split_whitespace().map(|t| t.parse().expect("the table's numbers")).collect();
            let (s, a) = (f[1] as usize, f[2]);
            // p_0 .. p_s, the polynomial's coefficients
            let p: Vec<u8> = (0..=s).map(|k| (a / 3u64.pow(k as u32) % 3) as u8).collect();
            // m_k's digits, least significant first (m[k - 1] is m_k)
            let mut m: Vec<Vec<u8>> = (0..s.min(cols))
                .map(|k| (0..=k).map(|d| (f[3 + k] / 3u64.pow(d as u32) % 3) as u8).collect())
                .collect();
            for k in s + 1..=cols {
                let mut next = m[k - s - 1].clone();
                next.resize(k, 0);
                for i in 1..=s {
                    let c = (3 - p[s - i]) % 3;
                    for (d, &digit) in m[k - i - 1].iter().enumerate() {
                        next[d + i] = (next[d + i] + c * digit) % 3;
                    }
                }
                m.push(next);
            }
            // column k: row r is the digit of weight 3^(k - r)
            m.iter()
                .enumerate()
                .map(|(k, digits)| (0..cols).map(|r| if r <= k { digits[k - r] } else { 0 }).collect())
                .collect()
        })
        .collect()
}
