//! Blue noise: sets whose points keep their distance, so that their spectrum is low at low
//! frequencies, made by rejection, elimination or optimization.
//!
//! - [`poisson`]: Poisson disks: dart throwing (Cook 1986; Shirley 1991), Bridson's (2007)
//!   fast variant and maximal sampling (Ebeida et al. 2012).
//! - [`elimination`]: weighted sample elimination (Yuksel 2015).
//! - [`lloyd`]: Lloyd relaxation towards a centroidal Voronoi tessellation (Lloyd 1982;
//!   Du, Faber & Gunzburger 1999).
//! - [`ccvt`]: capacity-constrained Voronoi tessellations (Balzer, Schlömer & Deussen 2009).
//! - [`sot`]: sliced optimal transport sampling (Paulin et al. 2020).
//! - [`gbn`]: Gaussian blue noise (Ahmed, Ren & Wonka 2022), and Fattal's (2011) kernel
//!   density model sampled by Langevin steps.
//! - [`step`]: step and single-peak blue noise matched through the pair correlation
//!   function (Heck, Schlömer & Deussen 2013).
//! - [`force_matrix`]: the force matrix (Purgathofer, Tobler & Geiler 1994; Sbert et al.
//!   2006 section 3.3).
//!
//! The optimizers report progress once per iteration and stop between iterations.

use rayon::prelude::*;

crate::registry::registry_files! {
    /// The files of this family, in listing order.
    pub(crate) static FILES: Family<crate::sampler::SamplerEntry> =
        [poisson, elimination, lloyd, ccvt, sot, gbn, kdm, step, force_matrix];
}

/// The items `item(i)` gives for i in `0..len`, in order, into `into` (replacing its
/// contents): in parallel by blocks of `block` indices, each block's count first, then its
/// items written at its offset. Rayon's `filter().collect()` builds a list of pieces and
/// joins them, allocating in every call, and on more threads in more pieces; this allocates
/// nothing beyond `into`. `item` is called twice per index, so it must give the same answer
/// both times.
fn select_in_order<T: Copy + Default + Send + Sync>(
    len: usize,
    block: usize,
    item: impl Fn(usize) -> Option<T> + Sync,
    into: &mut Vec<T>,
) {
    let blocks = len.div_ceil(block);
    let range = |b: usize| b * block..((b + 1) * block).min(len);
    let counts: Vec<usize> =
        (0..blocks).into_par_iter().map(|b| range(b).filter(|&i| item(i).is_some()).count()).collect();
    into.clear();
    into.resize(counts.iter().sum(), T::default());
    crate::memory::split(into, counts).into_par_iter().enumerate().for_each(|(b, part)| {
        for (slot, x) in part.iter_mut().zip(range(b).filter_map(&item)) {
            *slot = x;
        }
    });
}

#[cfg(test)]
mod tests {
    use super::select_in_order;

    #[test]
    fn selecting_in_order_by_blocks_is_a_serial_filter() {
        // lengths around the blocks' edges, none kept, all kept, every third
        let block = 64;
        for len in [0, 1, block - 1, block, block + 1, 3 * block + 17] {
            let from: Vec<u32> = (0..len as u32).map(|i| i.wrapping_mul(2_654_435_761) >> 7).collect();
            for keep in [|_: u32| false, |_: u32| true, |q: u32| q % 3 == 1] {
                let mut into = vec![7; 5];
                select_in_order(len, block, |i| Some(from[i]).filter(|&q| keep(q)), &mut into);
                let want: Vec<u32> = from.iter().copied().filter(|&q| keep(q)).collect();
                assert_eq!(into, want, "{len} items");
            }
        }
    }
}
