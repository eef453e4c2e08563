//! The SZ generating matrices (Ahmed, Pharr, Ostromoukhov & Huang 2025, "SZ Sequences:
//! Binary-Constructed (0, 2^q)-Sequences"), the case q = 2: a (0, 4)-sequence in base 4
//! written as four binary matrices, of which the first two are Sobol's.
//!
//! The field GF(4) is GF(2)\[x\] / (x^2 + x + 1); each of its elements acts on it (basis 1, x)
//! as a 2 x 2 binary matrix, so a matrix over GF(4) is a binary matrix of 2 x 2 blocks. The
//! matrix of a symbol s is the base-4 Pascal matrix of s (the paper's eq. 24): block (i, j)
//! is s^(j - i) where binom(j, i) is odd and zero elsewhere (Faure's matrices in base 4, whose
//! field has characteristic 2). Each block is multiplied on the left by the 2 x 2 Pascal
//! matrix [[1, 1], [0, 1]]; the factor is block diagonal, so the base-4 structure holds, and
//! it nests a 2D Sobol' set in the sequence (section 4.3): the symbol 1 then gives the
//! binary Pascal matrix, Sobol's second dimension. The four dimensions are the identity
//! (van der Corput), the symbols 1 and alpha (a generator of GF(4)'s multiplicative group),
//! and the third's partner under the pair relation P C_d = C_(d xor 1) (eq. 13), P being
//! Sobol's Pascal matrix.
//!
//! These are the matrices of OpenQMC's `SobolSampler` since its pull request #108
//! ([`crate::pixel`]'s `openqmc.sz`, checked bit for bit against a fixture built from that
//! source), here to 32 columns and rows.

/// A 2 x 2 binary matrix, `[[a, b], [c, d]]`.
type Block = [[u32; 2]; 2];

/// The identity block: the symbol 1.
const ONE: Block = [[1, 0], [0, 1]];

/// The block of x in GF(2)\[x\] / (x^2 + x + 1), a generator of GF(4)'s multiplicative group
/// (its cube is 1, its square is not): x times (a + b x) is b + (a + b) x.
const ALPHA: Block = [[0, 1], [1, 1]];

/// The 2 x 2 binary Pascal matrix each block is multiplied by (the nested 2D Sobol' set).
const PASCAL: Block = [[1, 1], [0, 1]];

const fn times(x: Block, y: Block) -> Block {
    let mut z = [[0; 2]; 2];
    let mut r = 0;
    while r < 2 {
        let mut c = 0;
        while c < 2 {
            z[r][c] = (x[r][0] & y[0][c]) ^ (x[r][1] & y[1][c]);
            c += 1;
        }
        r += 1;
    }
    z
}

/// A binary matrix's 32 columns, row 0 the most significant bit: column k multiplies the
/// index's digit k (the least significant first).
pub(crate) type Columns = [u32; 32];

/// The matrix of a GF(4) symbol (module docs): 16 x 16 blocks.
const fn symbol(s: Block) -> Columns {
    let mut powers = [ONE; 16];
    let mut e = 1;
    while e < 16 {
        powers[e] = times(powers[e - 1], s);
        e += 1;
    }
    let mut columns = [0u32; 32];
    let mut j = 0;
    while j < 16 {
        let mut i = 0;
        while i <= j {
            // Lucas: binom(j, i) is odd when i's bits are among j's
            if i & !j == 0 {
                let block = times(PASCAL, powers[j - i]);
                let mut r = 0;
                while r < 2 {
                    let mut c = 0;
                    while c < 2 {
                        columns[2 * j + c] |= block[r][c] << (31 - (2 * i + r));
                        c += 1;
                    }
                    r += 1;
                }
            }
            i += 1;
        }
        j += 1;
    }
    columns
}

/// The product of two binary matrices given by their columns.
const fn product(lhs: &Columns, rhs: &Columns) -> Columns {
    let mut columns = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        let mut r = 0;
        while r < 32 {
            if rhs[k] >> (31 - r) & 1 == 1 {
                columns[k] ^= lhs[r];
            }
            r += 1;
        }
        k += 1;
    }
    columns
}

const fn identity() -> Columns {
    let mut columns = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        columns[k] = 1 << (31 - k);
        k += 1;
    }
    columns
}

/// The four SZ matrices (q = 2), 32 x 32 bits: a (0, 4)-sequence in base 4 up to 4^16 points.
pub const SZ: [Columns; 4] = {
    let pascal = symbol(ONE);
    let second = symbol(ALPHA);
    [identity(), pascal, second, product(&pascal, &second)]
};

#[cfg(test)]
mod tests {
    use super::*;

    /// Point i's base-4 digits in each dimension: digit r of dimension d is output bits
    /// (2r, 2r + 1), the matrix times the index's bits.
    fn point(m: &[Columns; 4], i: u32) -> [u32; 4] {
        m.map(|c| (0..32).filter(|&k| i >> k & 1 == 1).fold(0, |y, k| y ^ c[k]))
    }

    /// Whether the first 4^k points put one point in every base-4 elementary interval of
    /// volume 4^-k: a (0, k, 4)-net in base 4, counted box by box.
    fn is_net(m: &[Columns; 4], k: u32) -> bool {
        let points: Vec<[u32; 4]> = (0..1u32 << (2 * k)).map(|i| point(m, i)).collect();
        let mut ok = true;
        // every split (a0, a1, a2, a3) of k digits among the dimensions
        for a0 in 0..=k {
            for a1 in 0..=k - a0 {
                for a2 in 0..=k - a0 - a1 {
                    let a = [a0, a1, a2, k - a0 - a1 - a2];
                    let mut seen = vec![false; points.len()];
                    for p in &points {
                        let cell = (0..4).fold(0u64, |cell, d| {
                            let digits = if a[d] == 0 { 0 } else { u64::from(p[d] >> (32 - 2 * a[d])) };
                            (cell << (2 * a[d])) | digits
                        });
                        ok &= !std::mem::replace(&mut seen[cell as usize], true);
                    }
                }
            }
        }
        ok
    }

    #[test]
    fn the_four_matrices_make_a_0_4_sequence_in_base_4() {
        // every prefix of 4^k points is a (0, k, 4)-net; and every base-4 net is one at any
        // start that is a multiple of 4^k, which the digital structure gives with the prefix
        for k in 1..=6 {
            assert!(is_net(&SZ, k), "k = {k}");
        }
    }

    #[test]
    fn a_perturbed_matrix_breaks_the_net() {
        for (d, k) in [(2, 3), (3, 0), (1, 5)] {
            let mut m = SZ;
            m[d][k] ^= 1 << (31 - k.saturating_sub(1));
            assert!(!(1..=4).all(|j| is_net(&m, j)), "flipped dimension {d} column {k}");
        }
    }

    #[test]
    fn the_first_two_dimensions_are_sobols() {
        for (d, columns) in SZ.iter().enumerate().take(2) {
            assert_eq!(*columns, crate::construct::sobol::direction_numbers(d), "dimension {d}");
        }
    }

    #[test]
    fn alpha_generates_the_multiplicative_group_and_the_pair_relation_holds() {
        let square = times(ALPHA, ALPHA);
        assert_ne!(square, ONE);
        assert_eq!(times(square, ALPHA), ONE);
        // eq. 13 both ways: P C_2 = C_3 and P C_3 = C_2, as P P = I (binom(j, i) 2^(j - i)
        // is even off the diagonal)
        assert_eq!(product(&SZ[1], &SZ[1]), identity());
        assert_eq!(product(&SZ[1], &SZ[3]), SZ[2]);
    }
}
