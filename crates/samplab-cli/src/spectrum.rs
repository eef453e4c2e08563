//! `samplab spectrum`: periodogram, amplitude of the expected spectrum and variance of
//! the spectrum over realizations, with radial averages, anisotropy and theory.

use std::path::PathBuf;

use std::io::Write;

use anyhow::{Context as _, bail};
use rayon::prelude::*;
use samplab::PointSet;
use samplab::io::text::{self, JsonObject};
use samplab::spectrum::{self, Statistics};
use samplab_report::plot::{self as draw, HeatMap, LineChart, Series};

use crate::bar::Bar;

/// Compute spectral statistics.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  samplab spectrum --sampler jitter -n 256 --sets 20 --res 128 -o spec/\n  samplab spectrum --sampler jitter.gaussian:sigma=0.25 -n 256 --sets 50 --theory -o gj/\n  samplab spectrum sets.txt --stat expected,variance -o spec/\n\nWrites DIR/spectrum.json (each statistic's R x R grid, row-major, index (R/2, R/2) = DC,\nfrequency = index - R/2 on both axes, and its radial curve), CSV files, log-scale heat maps\n(PNG) and radial plots (PNG and SVG). S(w) = (1/N) sum exp(-2 pi i w.x), so DC = 1."
)]
pub struct Args {
    /// A point-set file with at least two sets (instead of --sampler)
    file: Option<PathBuf>,
    #[command(flatten)]
    source: crate::sets::SetSource,
    /// Frequencies per axis (even; DC at R/2)
    #[arg(long, default_value_t = 128)]
    res: usize,
    /// Statistics to write: periodogram, expected, variance
    #[arg(long, value_delimiter = ',', default_value = "periodogram,expected,variance")]
    stat: Vec<String>,
    /// Tolerance of the fast path (non-uniform FFT), relative to DC
    #[arg(long, default_value_t = 1e-9, conflicts_with = "direct")]
    tolerance: f64,
    /// Use the direct DFT (the reference, O(N R^2)) instead of the fast path
    #[arg(long)]
    direct: bool,
    /// Overlay the closed forms for Gaussian and box jitter (Subr & Kautz eqs. 8-11)
    #[arg(long)]
    theory: bool,
    /// Output folder (replaced when complete; an existing folder only if samplab made it)
    #[arg(short, long)]
    output: PathBuf,
    /// Replace the output folder even when it holds files samplab did not write
    #[arg(long)]
    force: bool,
}

const STATS: [&str; 3] = ["periodogram", "expected", "variance"];

pub fn run(a: &Args) -> anyhow::Result<()> {
    for s in &a.stat {
        if !STATS.contains(&s.as_str()) {
            bail!("--stat: unknown statistic '{s}' (periodogram, expected, variance)");
        }
    }
    let replace = if a.force { samplab::io::Replace::Force } else { samplab::io::Replace::IfOurs };
    samplab::io::check_folder(&a.output, replace)?;
    {
        use samplab::io::Role;
        let file = a.file.as_deref().map(|f| Role::Input("the point file", f));
        let roles: Vec<Role<'_>> = file.into_iter().chain([Role::Folder("-o", &a.output)]).collect();
        let specs: Vec<&str> = a.source.sampler.iter().map(String::as_str).collect();
        crate::refuse_overlap(&specs, &roles)?;
    }
    let crate::sets::Loaded { sets, source, spec } = a.source.load(a.file.as_deref(), 20, &samplab::io::ANY)?;
    // the closed form, before the spectra: a --theory that has none is refused, not dropped
    let theory_curves = match (a.theory, spec.as_deref()) {
        (false, _) => None,
        (true, None) => bail!("--theory needs --sampler: a file's sets have no closed form"),
        (true, Some(s)) => Some(theory_for(s, &sets[0]).with_context(|| {
            format!("--theory: {s} has no closed-form spectrum here (jitter.gaussian and jitter.box have)")
        })?),
    };
    let method = spectrum::Method::of(a.direct, a.tolerance);
    let bar = Bar::new(sets.len() as u64, "spectra");
    let st = spectrum::statistics_with_progress(&sets, a.res, method, &bar.progress())?;
    drop(bar);
    samplab::io::write_folder(&a.output, replace, |dir| write(dir, &st, a, &source, theory_curves.as_ref()))?;
    crate::say!("spectrum of {} sets of {} points at {}^{}: {}", st.sets, st.n, st.res, st.dims, a.output.display());
    Ok(())
}

/// (label, per radial bin: predicted variance) where the sampler has a closed form.
fn theory_for(spec: &str, set: &PointSet) -> Option<(String, Vec<f64>)> {
    let theory = samplab::sampler::build(spec).ok()?.spectrum_theory(set.len(), set.dims())?;
    let curve = (1..=4096).map(|w| theory.at(w as f64)).collect();
    Some((theory.label, curve))
}

/// A file of the output folder: its name and a way to write its bytes.
type File<'a> = (String, Box<dyn Fn(&mut dyn Write) -> anyhow::Result<()> + Send + Sync + 'a>);

/// Write the output folder's files, each in its own parallel task, its grids formatted
/// part by part on every thread too (a 1024^2 grid's numbers were most of a run's serial
/// time), streamed through a buffer (a whole file's text in memory cost more in page
/// faults than its formatting, on two threads).
fn write(
    dir: &std::path::Path,
    st: &Statistics,
    a: &Args,
    source: &str,
    theory: Option<&(String, Vec<f64>)>,
) -> anyhow::Result<()> {
    let names: Vec<&str> = a.stat.iter().map(String::as_str).collect();
    let curves = spectrum::radials(st, &names);
    let mut series = Vec::new();
    for (name, (radial, _)) in a.stat.iter().zip(&curves) {
        series.push(Series {
            colour_key: Some(name.clone()),
            ..Series::line(name.clone(), radial.iter().enumerate().map(|(i, &y)| ((i + 1) as f64, y)).collect())
        });
    }
    if let Some((label, curve)) = theory {
        let bins = st.res / 2 - 1;
        series.push(Series {
            dashed: true,
            colour_key: Some("variance".into()),
            ..Series::line(
                label.clone(),
                curve.iter().take(bins).enumerate().map(|(i, &y)| ((i + 1) as f64, y)).collect(),
            )
        });
    }
    let chart = LineChart {
        title: format!("Radial averages — {source}"),
        x_label: "radial frequency (cycles per unit)".into(),
        y_label: "statistic".into(),
        series,
        log_y: true,
        log_x: false,
        polar: false,
    };
    let mut files: Vec<File> = vec![(
        "spectrum.json".into(),
        Box::new(|w| {
            // the keys in sorted order, as a serde_json map prints them
            let mut object = JsonObject::new(w)?;
            object.field("dims", &st.dims)?;
            object.field("layout", &"row-major; index (R/2, R/2) is DC; frequency = index - R/2 on each axis")?;
            object.field("n", &st.n)?;
            object.field("normalization", &"S(w) = (1/N) sum exp(-2 pi i w.x); variance divides by M - 1; radial bins r = 1..R/2-1 by rounded |w|, DC excluded")?;
            object.field("res", &st.res)?;
            object.field("sets", &st.sets)?;
            object.field("source", &source)?;
            object.field_with("statistics", |w| spectrum::write_json(w, st, &names, &curves))?;
            Ok(object.end()?)
        }),
    )];
    for name in &a.stat {
        let v = st.values(name);
        let row = if st.dims == 2 { st.res } else { v.len() };
        files.push((format!("{name}.csv"), Box::new(move |w| Ok(text::write_csv_rows(w, v, row)?))));
        if st.dims == 2 {
            let label = match name.as_str() {
                "periodogram" => "<|S|^2>",
                "expected" => "|<S>|",
                _ => "V(S)",
            };
            files.push((
                format!("{name}.png"),
                Box::new(move |w| {
                    let map = HeatMap::centred(format!("{name} — {source}"), label.into(), v.to_vec(), st.res);
                    Ok(w.write_all(&draw::png(&map, (820, 700))?)?)
                }),
            ));
        }
    }
    files.push((
        "radial.csv".into(),
        Box::new(|w| Ok(w.write_all(spectrum::radial_csv(st, &names, &curves).as_bytes())?)),
    ));
    files.push(("radial.png".into(), Box::new(|w| Ok(w.write_all(&draw::png(&chart, (900, 560))?)?))));
    files.push(("radial.svg".into(), Box::new(|w| Ok(w.write_all(draw::svg(&chart, (900, 560))?.as_bytes())?))));
    // the folder is a staging one, renamed into place once complete
    files.par_iter().try_for_each(|(name, make)| {
        let path = dir.join(name);
        let context = || format!("cannot write '{}'", path.display());
        let mut w = std::io::BufWriter::with_capacity(1 << 16, std::fs::File::create(&path).with_context(context)?);
        make(&mut w).with_context(context)?;
        w.flush().with_context(context)
    })
}
