//! Quasi-Monte Carlo: deterministic low-discrepancy constructions, each with the
//! randomizations of [`crate::sampler::randomize`] that keep its structure.
//!
//! - [`sobol`]: the Sobol' sequence (Sobol' 1967) with the Joe & Kuo (2008) direction
//!   numbers, in Gray-code order.
//! - [`halton`]: radical inverses in prime bases: the Halton sequence (Halton 1960) and the
//!   Hammersley set (Hammersley & Handscomb 1964).
//! - [`larcher`]: the Larcher–Pillichshammer set (Larcher & Pillichshammer 2003), a 2D
//!   digital net of the least star discrepancy.
//! - [`net`]: digital nets and sequences in a prime base from generating matrices
//!   (Niederreiter 1992): a file's, Faure's (1982) and Niederreiter's (1988).
//! - [`kronecker`]: Kronecker sequences frac(i alpha) (Weyl 1916), Roberts' R_d by default.
//! - [`lattice`]: rank-1 lattices (Sloan & Joe 1994): Fibonacci, Korobov (Korobov 1959),
//!   component-by-component ([`crate::construct::cbc`]) and the embedded lattice sequence
//!   (Hickernell et al. 2000; Cools, Kuo & Nuyens 2006).
//!
//! Every one of them is progressive or planned from tables built once per plan, and the
//! sequences give random access equal to the batch ([`crate::sampler::Plan::access`]).

crate::registry::registry_files! {
    /// The files of this family, in listing order.
    pub(crate) static FILES: Family<crate::sampler::SamplerEntry> = [sobol, halton, larcher, net, kronecker, lattice];
}
