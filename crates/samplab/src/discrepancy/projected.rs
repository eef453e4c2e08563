//! Projected discrepancy (Shirley 1991 section 3.1, Tables 5-7's "projected" reading): the
//! 1D discrepancy of the projections of a 2D set onto a direction, against the exact
//! distribution of the projection of a uniform point of the square.

use super::{Limits, MetricEntry, extreme, star};
use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::registry::About;
use crate::spec::{Default, Kind, ParamSpec, Params};

/// The metric this file registers.
pub(crate) static ENTRIES: &[MetricEntry] = &[MetricEntry::new(
    About::new("projected", "1D discrepancy of the projections onto a direction (2D)")
        .params(&[
            ParamSpec {
                name: "angle",
                kind: Kind::Real { min: -360.0, max: 360.0 },
                default: Default::Number(0.0),
                doc: "direction, degrees from the x axis",
            },
            ParamSpec {
                name: "kind",
                kind: Kind::Choice(&["star", "extreme"]),
                default: Default::Word("star"),
                doc: "half-lines or intervals",
            },
        ])
        .cite(&["shirley1991"]),
    projected,
)];

fn projected(params: &Params, points: &PointSet, _: Limits) -> Result<f64> {
    if points.dims() != 2 {
        return Err(Error::Dimension { what: "projected discrepancy".into(), takes: "2D points".into(), got: points.dims() });
    }
    let u = projected_uniform(points, params.real("angle"));
    Ok(if params.word("kind") == "extreme" { extreme::extreme_1d(&u) } else { star::star_1d(&u) })
}

/// The projections t = x cos(angle) + y sin(angle), mapped through the exact CDF of the
/// projection of a uniform point of the square (a trapezoid), so that the generalized 1D
/// discrepancy of t equals the ordinary 1D discrepancy of the mapped values.
pub fn projected_uniform(points: &PointSet, angle_degrees: f64) -> Vec<f64> {
    let (s, c) = angle_degrees.to_radians().sin_cos();
    let (a, b) = (c.abs().max(s.abs()), c.abs().min(s.abs()));
    let offset = c.min(0.0) + s.min(0.0);
    let cdf = |z: f64| -> f64 {
        let z = z - offset;
        if b < 1e-15 {
            return (z / a).clamp(0.0, 1.0);
        }
        if z <= 0.0 {
            0.0
        } else if z <= b {
            z * z / (2.0 * a * b)
        } else if z <= a {
            (2.0 * z - b) / (2.0 * a)
        } else if z < a + b {
            1.0 - (a + b - z).powi(2) / (2.0 * a * b)
        } else {
            1.0
        }
    };
    points.iter().map(|p| cdf(p[0] * c + p[1] * s)).collect()
}
