//! The Sobol' sequence's generating matrices (Sobol' 1967) with the Joe-Kuo direction
//! numbers (Joe & Kuo 2008, new-joe-kuo-6.21201, first 1024 dimensions, baked in by
//! `build.rs`), and the byte tables that draw one point's digits in four lookups.

use super::scramble::owen_scramble_reversed;

include!(concat!(env!("OUT_DIR"), "/sobol_directions.rs"));

/// How many dimensions the baked-in table holds.
pub const SOBOL_MAX_DIMS: usize = SOBOL_DIRECTIONS.len();

/// The unscrambled 32-bit digits of coordinate `dim` of Sobol' point `index` in natural
/// (not Gray-code) order.
#[inline]
pub fn sobol_u32(index: u32, dim: usize) -> u32 {
    let v = &SOBOL_DIRECTIONS[dim];
    let mut x = 0;
    let mut i = index;
    let mut k = 0;
    while i != 0 {
        if i & 1 == 1 {
            x ^= v[k];
        }
        i >>= 1;
        k += 1;
    }
    x
}

/// The 32 direction numbers of dimension `dim` (column k of its generating matrix, row 0
/// the most significant bit).
///
/// # Panics
/// When `dim` is not below [`SOBOL_MAX_DIMS`].
pub fn direction_numbers(dim: usize) -> [u32; 32] {
    SOBOL_DIRECTIONS[dim]
}

/// The byte tables of one dimension's generator, bit-reversed: entry [b][v] is the XOR of
/// the reversed columns that byte b of the index selects when it equals v. Reversed digits
/// are what the Owen scramble of Burley 2020 works on, so a value costs one reversal.
/// Column k has k + 1 significant digits, so the low index bytes' entries fit 16 bits:
/// they are kept so, halving the tables that every draw below 2^16 reads.
#[derive(Debug, Clone)]
pub(crate) struct ByteTables {
    low: [[u16; 256]; 2],
    high: [[u32; 256]; 2],
}

pub(crate) fn byte_tables(dim: usize) -> ByteTables {
    let c = direction_numbers(dim).map(u32::reverse_bits);
    let table = |b: usize| -> [u32; 256] {
        std::array::from_fn(|v| (0..8).filter(|k| v >> k & 1 == 1).fold(0, |x, k| x ^ c[8 * b + k]))
    };
    // the reversed columns 0..16 lie in the low 16 bits: the cast drops only zeros
    ByteTables { low: [table(0).map(|x| x as u16), table(1).map(|x| x as u16)], high: [table(2), table(3)] }
}

/// The unscrambled 32 digits of point `index`, bit-reversed, from its dimension's byte
/// tables (the index's high half looked up only when it is not zero: pixels draw from the
/// first 2^16 points unless their sample count is larger).
#[inline(always)]
pub(crate) fn reversed_digits(t: &ByteTables, index: u32) -> u32 {
    let low = u32::from(t.low[0][(index & 0xFF) as usize] ^ t.low[1][(index >> 8 & 0xFF) as usize]);
    if index >> 16 == 0 {
        low
    } else {
        low ^ t.high[0][(index >> 16 & 0xFF) as usize] ^ t.high[1][(index >> 24) as usize]
    }
}

/// The Owen-scrambled digits (Burley 2020) of reversed digits, in their natural order.
#[inline(always)]
pub(crate) fn owen_digits(reversed: u32, seed: u32) -> u32 {
    owen_scramble_reversed(reversed, seed).reverse_bits()
}

/// One dimension's [`ByteTables`] for an index whose low 16 digits come bit-reversed: the
/// low tables re-indexed by reversed bytes (entry [0][v] is `low[1][reverse(v)]`, entry
/// [1][v] is `low[0][reverse(v)]`), the high ones unchanged. The per-pixel shuffle
/// (`pixel` sampler `sobol`) computes the index reversed, so a draw looks its digits up without reversing it back.
#[derive(Debug, Clone)]
pub(crate) struct ReversedLow(ByteTables);

impl ReversedLow {
    pub(crate) fn new(dim: usize) -> ReversedLow {
        let t = byte_tables(dim);
        let by_reversed = |b: usize| std::array::from_fn(|v: usize| t.low[b][(v as u8).reverse_bits() as usize]);
        ReversedLow(ByteTables { low: [by_reversed(1), by_reversed(0)], high: t.high })
    }

    /// The reversed digits of the point `high | reverse16(low)` (`low` below 2^16).
    #[inline(always)]
    pub(crate) fn digits(&self, high: u32, low: u32) -> u32 {
        let t = &self.0;
        let digits = u32::from(t.low[0][(low & 0xFF) as usize] ^ t.low[1][(low >> 8 & 0xFF) as usize]);
        if high == 0 {
            digits
        } else {
            digits ^ t.high[0][(high >> 16 & 0xFF) as usize] ^ t.high[1][(high >> 24) as usize]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_tables_equal_the_column_walk() {
        let t = byte_tables(5);
        for index in [0u32, 1, 255, 256, 0xFFFF, 0x1_0000, 0x1234_5678, u32::MAX] {
            assert_eq!(reversed_digits(&t, index), sobol_u32(index, 5).reverse_bits());
        }
    }
}
