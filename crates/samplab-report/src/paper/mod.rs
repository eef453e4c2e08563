//! One module per paper; each lists its experiments and what is not reproduced yet.

use crate::Paper;

pub mod prediction;
pub mod ramamoorthi2012;
pub mod renderer;
pub mod sbert2006;
pub mod sequences2020;
pub(crate) mod shadows;
pub mod shirley1991;
pub mod subr2013;

/// Every paper, in report order.
pub fn all() -> Vec<Paper> {
    vec![
        shirley1991::paper(),
        subr2013::paper(),
        sbert2006::paper(),
        ramamoorthi2012::paper(),
        renderer::paper(),
        prediction::paper(),
        sequences2020::paper(),
    ]
}

/// The keys of every paper, for `--only`.
pub fn keys() -> Vec<&'static str> {
    all().iter().map(|p| p.key).collect()
}

use samplab::experiment::{Row, Study, UnitStats};
use samplab::integrand::Family;
use samplab::progress::Progress;
use samplab::{Sampler, Seed, sampler};

use crate::{Ctx, Error};

/// Run an integration study for the report, advancing the experiment's progress bar.
pub(crate) fn study(
    ctx: &Ctx,
    samplers: &[&str],
    integrand: &str,
    ns: &[usize],
    sets: usize,
    instances: usize,
    seed: Seed,
) -> Result<Vec<Row>, Error> {
    Ok(study_units(ctx, samplers, integrand, ns, (sets, instances), seed)?.1)
}

/// [`study`], with the statistics of each of its units (sampler, count, instance; in the
/// order of [`samplab::experiment::Prepared::units`]) beside its rows.
pub(crate) fn study_units(
    ctx: &Ctx,
    samplers: &[&str],
    integrand: &str,
    ns: &[usize],
    (sets, instances): (usize, usize),
    seed: Seed,
) -> Result<(Vec<UnitStats>, Vec<Row>), Error> {
    let s: Vec<Sampler> = samplers.iter().map(|x| sampler::build(x)).collect::<Result<_, _>>()?;
    let family = Family::parse(integrand)?;
    let report = |k| ctx.tick(k);
    let progress = Progress::new(&report).stopped_by(ctx.stop);
    let study = Study { samplers: &s, family: (&family).into(), ns, sets, instances, seed };
    let prepared = study.prepare()?;
    let units = prepared.every_unit(&progress)?;
    let rows = prepared.rows(&units)?;
    Ok((units, rows))
}
