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

crate::registry::registry_files! {
    /// The files of this family, in listing order.
    pub(crate) static FILES: Family<crate::sampler::SamplerEntry> =
        [poisson, elimination, lloyd, ccvt, sot, gbn, kdm, step, force_matrix];
}
