//! One module per paper; each lists its experiments and what is not reproduced yet.

use crate::Paper;

pub mod ramamoorthi2012;
pub mod sbert2006;
pub mod shirley1991;
pub mod subr2013;

/// Every paper, in report order.
pub fn all() -> Vec<Paper> {
    vec![shirley1991::paper(), subr2013::paper(), sbert2006::paper(), ramamoorthi2012::paper()]
}

/// The keys of every paper, for `--only`.
pub fn keys() -> Vec<&'static str> {
    all().iter().map(|p| p.key).collect()
}
