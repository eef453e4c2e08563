//! The spacing metrics: the smallest distance, the relative radius, and the pair
//! correlation function (Gaussian kernel) and radial distribution function (histogram) at a
//! distance or at their highest peak ([`crate::spatial`]). Distances r, kernel and bin widths
//! are given in units of d_max = 2 r_max, the nearest-neighbour distance of the densest
//! packing of n points ([`spatial::packing_radius`]), so one setting serves every n.

use super::{Limits, MetricEntry};
use crate::error::Result;
use crate::points::PointSet;
use crate::registry::About;
use crate::spatial;
use crate::spec::{Default, Kind, ParamSpec, Params};

const TORUS: ParamSpec = ParamSpec {
    name: "torus",
    kind: Kind::Choice(&["yes", "no"]),
    default: Default::Word("yes"),
    doc: "measure on the torus (opposite faces identified) or in the cube",
};

const R: ParamSpec = ParamSpec {
    name: "r",
    kind: Kind::Real { min: 0.01, max: 1000.0 },
    default: Default::Auto("the highest value over r from 3 sigma (or 0) to 3 d_max"),
    doc: "the distance, in units of d_max = 2 r_max (at most 1/2 in absolute terms)",
};

const SIGMA: ParamSpec = ParamSpec {
    name: "sigma",
    kind: Kind::Real { min: 0.001, max: 10.0 },
    default: Default::Number(0.125),
    doc: "the Gaussian kernel's width, in units of d_max",
};

const WIDTH: ParamSpec = ParamSpec {
    name: "width",
    kind: Kind::Real { min: 0.001, max: 10.0 },
    default: Default::Number(0.1),
    doc: "the shells' width, in units of d_max",
};

/// The distances, absolute, at which a peak is looked for: from `from` to 3 d_max (at most
/// 1/2) in steps of `step`, all in units of d_max.
fn scan(d_max: f64, from: f64, step: f64) -> Vec<f64> {
    (0..).map(|i| (from + i as f64 * step) * d_max).take_while(|&r| r <= (3.0 * d_max).min(0.5)).collect()
}

fn pcf(p: &Params, points: &PointSet, _: Limits) -> Result<f64> {
    let d_max = 2.0 * spatial::packing_radius(points.len(), points.dims())?;
    let sigma = p.real("sigma") * d_max;
    let radii = match p.real_or_auto("r") {
        Some(r) => vec![r * d_max],
        None => scan(d_max, 3.0 * p.real("sigma"), 0.01),
    };
    Ok(spatial::pcf(points, &radii, sigma)?.into_iter().fold(f64::NEG_INFINITY, f64::max))
}

fn rdf(p: &Params, points: &PointSet, _: Limits) -> Result<f64> {
    let d_max = 2.0 * spatial::packing_radius(points.len(), points.dims())?;
    let width = p.real("width");
    let values = match p.real_or_auto("r") {
        Some(r) => spatial::rdf(points, &[(r - width / 2.0).max(0.0) * d_max, (r + width / 2.0) * d_max])?,
        None => spatial::rdf(points, &scan(d_max, 0.0, width))?,
    };
    Ok(values.into_iter().fold(f64::NEG_INFINITY, f64::max))
}

/// The metrics this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[
    MetricEntry {
        shift_invariant: true,
        ..MetricEntry::new(
            About::new("min-distance", "the smallest distance between two points (on the torus by default)")
                .aliases(&["dmin"])
                .params(&[TORUS])
                .cite(&["lagae2008"]),
            |p, points, _| Ok(spatial::min_distance(points, p.word("torus") == "yes")),
        )
    },
    MetricEntry {
        shift_invariant: true,
        ..MetricEntry::new(
            About::new("relative-radius", "half the smallest toroidal distance over r_max of the densest packing")
                .aliases(&["rho"])
                .cite(&["lagae2008"]),
            |_, points, _| spatial::relative_radius(points),
        )
    },
    MetricEntry {
        shift_invariant: true,
        ..MetricEntry::new(
            About::new("pcf", "pair correlation function (Gaussian kernel) at r, or its highest peak")
                .params(&[R, SIGMA])
                .cite(&["heck2013"]),
            pcf,
        )
    },
    MetricEntry {
        shift_invariant: true,
        ..MetricEntry::new(
            About::new("rdf", "radial distribution function (shell histogram) at r, or its highest bin")
                .params(&[R, WIDTH])
                .cite(&["heck2013"]),
            rdf,
        )
    },
];
