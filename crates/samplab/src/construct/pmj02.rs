//! Progressive multi-jittered (0,2) sequences (Christensen, Kensler & Kilpatrick 2018),
//! pmj02: every prefix of 2^m points is a (0,m,2)-net in base 2, and so is every later
//! block of 2^m points.
//!
//! Stochastic construction (Helmer et al. 2021, section 4): point 0 is uniform; point i
//! in [2^m, 2^(m+1)) copies the first m binary digits of an earlier "partner" point per
//! axis, takes the opposite (m+1)-th digit, and draws every later digit at random. The
//! x partner is i - 2^m (van der Corput structure); the y partner is i - 2^m XOR t_m,
//! where t_m solves the Sobol' dimension-2 generator restricted to its first m digits
//! (so that the new point fills the unoccupied half of each elementary interval). The
//! result has the distribution of an Owen-scrambled (0,2)-sequence; it is O(n), uses no
//! occupancy structure, and needs no rejection. 32-bit resolution, 2D, n <= 2^32.

use rand_core::Rng as _;

use super::sobol::SOBOL_DIRECTIONS;
use crate::seed::Seed;

/// t_m for m = 0..32: the index j < 2^m whose first m Sobol' dimension-2 digits equal
/// those of the direction number v_m.
fn partner_masks() -> [u32; 32] {
    let v = &SOBOL_DIRECTIONS[1];
    std::array::from_fn(|m| {
        let top = if m == 0 { 0 } else { !0u32 << (32 - m) };
        let mut target = v[m] & top;
        let mut j = 0u32;
        // v_k has its lowest set bit at 31-k, so solve from the lowest digit up
        for k in (0..m).rev() {
            if target & (1 << (31 - k)) != 0 {
                target ^= v[k] & top;
                j |= 1 << k;
            }
        }
        debug_assert_eq!(target, 0);
        j
    })
}

/// The first `n` points of the pmj02 sequence of `seed`, as 32-bit fixed-point digits.
pub(crate) fn pmj02_digits(n: usize, seed: Seed) -> Vec<[u32; 2]> {
    let t = partner_masks();
    let mut rng = seed.rng();
    let mut xy: Vec<[u32; 2]> = Vec::with_capacity(n);
    xy.push([rng.next_u32(), rng.next_u32()]);
    for i in 1..n {
        let m = i.ilog2() as usize;
        let px = i ^ (1 << m);
        let py = px ^ t[m] as usize;
        let keep = if m == 0 { 0 } else { !0u32 << (32 - m) };
        let flip = 1u32 << (31 - m);
        let fresh = flip - 1;
        let child = |parent: u32, r: u32| (parent & keep) | (!parent & flip) | (r & fresh);
        let r = rng.next_u64();
        xy.push([child(xy[px][0], r as u32), child(xy[py][1], (r >> 32) as u32)]);
    }
    xy.truncate(n);
    xy
}
