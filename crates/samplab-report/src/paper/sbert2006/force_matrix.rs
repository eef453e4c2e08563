//! Section 3.3: the force matrix, a well-spread subset of the systematic grid (Fig. 2).

use samplab::sampler;

use crate::criteria;
use crate::plot::Scatter;
use crate::{Claim, Ctx, Error, Figure, Output};

/// Fig. 2: force matrices of different sparseness, and the limit where every cell is
/// chosen.
pub(super) fn force_matrix(ctx: &Ctx) -> Result<Output, Error> {
    let grid = 32usize;
    ctx.set_length(3);
    let mut figures = Vec::new();
    for (label, n) in [("a", 256usize), ("b", 64)] {
        let spec = format!("force-matrix:grid={grid}");
        let set = sampler::build(&spec)?.generate(n, 2, ctx.seed.derive(n as u64))?;
        figures.push(Figure::render(
            &format!("sbert2006-fig2-{label}"),
            &format!("Fig. 2({label}): a force matrix of {n} of the {grid} x {grid} grid's cells (s = 0.5, p = 2)"),
            &Scatter {
                set: &set,
                axes: [0, 1],
                grid: None,
                title: format!("force matrix, {n} of {} cells", grid * grid),
            },
            (560, 560),
        )?);
        ctx.advance(1)?;
    }
    // the limit: all G^2 cells chosen is the systematic grid, one offset inside the cells
    let full = sampler::build(&format!("force-matrix:grid={grid}"))?.generate(grid * grid, 2, ctx.seed)?;
    let g = grid as f64;
    let cells: std::collections::BTreeSet<(usize, usize)> =
        full.iter().map(|p| ((p[0] * g) as usize, (p[1] * g) as usize)).collect();
    let first = full.point(0);
    let offset = |x: f64| (x * g).fract();
    let shared = full
        .iter()
        .all(|p| (offset(p[0]) - offset(first[0])).abs() < 1e-9 && (offset(p[1]) - offset(first[1])).abs() < 1e-9);
    ctx.advance(1)?;
    Ok(Output {
        tables: Vec::new(),
        figures,
        claims: vec![Claim {
            id: "force-matrix-limit".into(),
            statement: "In the limiting case (every cell chosen) the force matrix reverts to the full systematic grid"
                .into(),
            published: "section 3.3".into(),
            ours: format!(
                "{} distinct cells of {}, {} offset",
                cells.len(),
                grid * grid,
                if shared { "one shared" } else { "not one" }
            ),
            theory: String::new(),
            decision: criteria::exactly(
                cells.len() == grid * grid && shared,
                "every cell holds one point and all share one offset within their cell",
            ),
            derived: true,
            ..Claim::default()
        }],
        notes: vec![],
    })
}
