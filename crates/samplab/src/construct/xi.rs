//! The xi-sequence (Ahmed, Skopenkov, Hadwiger & Wonka 2023, "Analysis and synthesis of
//! digital dyadic sequences"): a 2D (0, 2)-sequence in base 2 whose generating matrices are
//! built from one 2D vector a, the default one of the authors' supplemental code (`xi.h`).
//!
//! The index is read in base 4: its digit at depth k (bits 2k and 2k + 1) adds a and b, both
//! shifted down by k, to the point. So column 2k of each dimension's matrix is a >> k and
//! column 2k + 1 is b >> k. The vector b is xi times a, xi acting on a 32-bit fraction x as
//! (x >> 1) ^ (x >> 2) ^ (x >> 4) ^ (x >> 8) ^ (x >> 16) (the product by 2 xi of the
//! authors' code), in y with a added: b = (xi a_x, xi a_y ^ a_y). The default a has only the
//! top bit in both coordinates.

/// The product of a 32-bit binary fraction by 2 xi.
const fn xi_times(x: u32) -> u32 {
    (x >> 1) ^ (x >> 2) ^ (x >> 4) ^ (x >> 8) ^ (x >> 16)
}

/// The two generating matrices of the xi-sequence of the vector `a` (both top bits set):
/// column k of dimension d, row 0 the most significant bit.
pub const fn xi_matrices(a: [u32; 2]) -> [[u32; 32]; 2] {
    let b = [xi_times(a[0]), xi_times(a[1]) ^ a[1]];
    let mut c = [[0u32; 32]; 2];
    let mut d = 0;
    while d < 2 {
        let mut k = 0;
        while k < 16 {
            c[d][2 * k] = a[d] >> k;
            c[d][2 * k + 1] = b[d] >> k;
            k += 1;
        }
        d += 1;
    }
    c
}

/// The default xi-sequence's matrices: a = (2^31, 2^31).
pub const XI: [[u32; 32]; 2] = xi_matrices([1 << 31, 1 << 31]);
