//! Randomizations: what makes a deterministic construction a random one while keeping its
//! structure, and the stage that moves any set's points.
//!
//! - [`scramble`]: the randomizations of the digital sequences (random digit scrambling
//!   after Matoušek 1998, Owen's 1995 nested scrambling by hashing after Burley 2020, and
//!   the Cranley & Patterson 1976 shift) and the hash-based permutations they use.
//! - [`micro_jitter`]: `+micro-jitter` after any spec: every point moved by a small uniform
//!   offset (after Roberts 2018).

pub mod scramble;

crate::registry::registry_files! {
    /// The files of this family, in listing order.
    pub(crate) static FILES: Family<crate::sampler::SamplerEntry> = [micro_jitter];
}
