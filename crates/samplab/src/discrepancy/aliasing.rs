//! Heck et al.'s (2013) aliasing measures of a 2D set's radial power spectrum, as metrics:
//! the effective Nyquist frequency and the oscillation ([`crate::spectrum::aliasing`]).

use super::MetricEntry;
use crate::registry::About;
use crate::spectrum::aliasing;

/// The metrics this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[
    MetricEntry {
        shift_invariant: true,
        ..MetricEntry::new(
            About::new(
                "nyquist",
                "effective Nyquist frequency (2D): edge of the periodogram's zero region / sqrt(n); 1 for a grid",
            )
            .aliases(&["effective-nyquist"])
            .cite(&["heck2013", "psa2012"]),
            |_, points, _| aliasing::effective_nyquist(points),
        )
    },
    MetricEntry {
        shift_invariant: true,
        ..MetricEntry::new(
            About::new("oscillation", "oscillation (2D): 10 x the RMS of the radial power spectrum about 1 past its rise")
                .cite(&["heck2013", "psa2012"]),
            |_, points, _| aliasing::oscillation(points),
        )
    },
];
