//! Stratified constructions: the unit cube cut into cells, and one point placed in each.
//!
//! - [`grid`]: n = k^d cells of a regular grid, the point at the centre (regular), anywhere
//!   in it (jittered: Cook 1986; Shirley 1991), in its middle half, displaced by a box or
//!   a Gaussian (Subr & Kautz 2013), or one offset shared by every cell (uniform jitter,
//!   the systematic sampling of Sbert et al. 2006 and Ramamoorthi et al. 2012); the
//!   randomly rotated grid and the hexagonal lattice (Petersen & Middleton 1962).
//! - [`nrooks`]: one point in each of the n slabs of every axis: N-rooks / Latin hypercube
//!   sampling (McKay et al. 1979; Shirley 1991), centred, and on an orthogonal array
//!   (Owen 1992; Tang 1993).
//! - [`pmj`]: both at once, progressively: progressive multi-jittered (0,2) sequences
//!   (Christensen, Kensler & Kilpatrick 2018, by the construction of Helmer, Christensen &
//!   Kensler 2021) and correlated multi-jittered sampling (Kensler 2013).

crate::registry::registry_files! {
    /// The files of this family, in listing order.
    pub(crate) static FILES: Family<crate::sampler::SamplerEntry> = [grid, nrooks, pmj];
}
