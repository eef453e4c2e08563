//! Space-filling orders of the screen's pixels beside pbrt's Morton order
//! ([`super::pbrt::morton2`]): the Hilbert curve (Hilbert 1891), which visits every aligned
//! 2^k x 2^k block of pixels as one run of 4^k consecutive indices, as Morton order does,
//! and moves between neighbouring pixels only.

/// The index of pixel (x, y) along the Hilbert curve over the 2^order x 2^order grid
/// (x, y below 2^order): the quadrant digits from the top level down, each sub-square
/// turned so that the curve enters it where the last one left off.
pub fn hilbert2(order: u32, x: u32, y: u32) -> u64 {
    let (mut x, mut y) = (x, y);
    let mut index = 0u64;
    for level in (0..order).rev() {
        let s = 1u32 << level;
        let (right, up) = (u32::from(x & s != 0), u32::from(y & s != 0));
        // quadrants in curve order: lower left, upper left, upper right, lower right
        index = (index << 2) | u64::from((3 * right) ^ up);
        if up == 0 {
            if right == 1 {
                // the lower right quadrant runs backwards: reflect the digits below this level
                (x, y) = (!x, !y);
            }
            (x, y) = (y, x);
        }
    }
    index
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_curve_is_a_bijection_steps_to_neighbours_and_keeps_blocks_together() {
        for order in 0..=6u32 {
            let side = 1u32 << order;
            let mut at = vec![None; (side * side) as usize];
            for y in 0..side {
                for x in 0..side {
                    let i = hilbert2(order, x, y) as usize;
                    assert!(at[i].replace((x, y)).is_none(), "order {order}: index {i} twice");
                }
            }
            let at: Vec<(u32, u32)> = at.into_iter().map(Option::unwrap).collect();
            for w in at.windows(2) {
                let (a, b) = (w[0], w[1]);
                assert_eq!(a.0.abs_diff(b.0) + a.1.abs_diff(b.1), 1, "order {order}: {a:?} to {b:?}");
            }
            // every aligned 2^k block: the run of 4^k indices from a multiple of 4^k
            for k in 0..=order {
                for (run, chunk) in at.chunks(1 << (2 * k)).enumerate() {
                    let (bx, by) = (chunk[0].0 >> k, chunk[0].1 >> k);
                    assert!(
                        chunk.iter().all(|p| (p.0 >> k, p.1 >> k) == (bx, by)),
                        "order {order}, block {k}, run {run}"
                    );
                }
            }
        }
        // Morton order keeps blocks together too, but jumps
        let z = |i: u64| {
            (0..32).fold((0u32, 0u32), |(x, y), b| {
                (x | ((i >> (2 * b) & 1) as u32) << b, y | ((i >> (2 * b + 1) & 1) as u32) << b)
            })
        };
        assert_ne!(z(1).0.abs_diff(z(2).0) + z(1).1.abs_diff(z(2).1), 1);
    }
}
