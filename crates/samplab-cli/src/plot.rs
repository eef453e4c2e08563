//! `samplab plot`: a scatter plot of one set with its two 1D marginal histograms, or its
//! pair correlation function (`--pcf`).

use std::path::PathBuf;

use anyhow::bail;
use samplab::io::{self, Format};
use samplab_report::plot::{self as draw, Scatter};

/// Plot a point set.
#[derive(clap::Args)]
#[command(
    after_help = "Examples:\n  samplab generate jitter -n 256 -o j.txt && samplab plot j.txt -o j.png --grid 16\n  samplab generate elimination -n 4096 -o e.txt && samplab plot e.txt --pcf -o e-pcf.png"
)]
pub struct Args {
    /// Point-set file (text, csv, npy or json)
    file: PathBuf,
    /// Output image: .png or .svg
    #[arg(short, long)]
    output: PathBuf,
    /// Input format (default: from the extension)
    #[arg(long)]
    format: Option<String>,
    /// Which set of the file to plot (0-based)
    #[arg(long, default_value_t = 0)]
    set: usize,
    /// The two coordinates to plot, e.g. 0,2
    #[arg(long, default_value = "0,1", value_delimiter = ',', num_args = 2)]
    axes: Vec<usize>,
    /// Draw a k x k grid of strata lines
    #[arg(long)]
    grid: Option<usize>,
    /// Image size in pixels (square)
    #[arg(long, default_value_t = 900)]
    size: u32,
    /// Plot the pair correlation function instead (on the torus, over r from 0.05 to 3 d_max,
    /// d_max = 2 r_max the densest packing's spacing): the Gaussian-kernel estimate (sigma =
    /// d_max / 8) and the shell histogram (width d_max / 10), white noise's 1 dashed
    #[arg(long)]
    pcf: bool,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    use samplab::io::Role;
    samplab::io::check_file(&a.output)?;
    samplab::io::refuse_overlap(&[Role::Input("the point file", &a.file), Role::File("-o", &a.output)])?;
    let format = a.format.as_deref().map(Format::from_name).transpose()?;
    let sets = io::read(&a.file, format)?;
    let Some(set) = sets.get(a.set) else {
        bail!("--set {}: {} holds {} set(s)", a.set, a.file.display(), sets.len());
    };
    if let Some(&bad) = a.axes.iter().find(|&&d| d >= set.dims()) {
        bail!("--axes: coordinate {bad} does not exist in {}D points", set.dims());
    }
    if !(200..=8000).contains(&a.size) {
        bail!("--size {}: expected 200..=8000 pixels", a.size);
    }
    if a.grid.is_some_and(|k| k == 0 || k > 1024) {
        bail!("--grid: expected 1..=1024 strata per axis");
    }
    let title = format!(
        "{} — {} points{}",
        a.file.file_name().unwrap_or_default().to_string_lossy(),
        set.len(),
        if sets.len() > 1 { format!(", set {}", a.set) } else { String::new() }
    );
    let size = (a.size, a.size);
    let svg = match a.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("svg") => true,
        Some("png") => false,
        _ => bail!("-o {}: the output must end in .png or .svg", a.output.display()),
    };
    let bytes = if a.pcf {
        let chart = pcf_chart(set, title)?;
        if svg { draw::svg(&chart, size)?.into_bytes() } else { draw::png(&chart, size)? }
    } else {
        let chart = Scatter { set, axes: [a.axes[0], a.axes[1]], grid: a.grid, title };
        if svg { draw::svg(&chart, size)?.into_bytes() } else { draw::png(&chart, size)? }
    };
    Ok(samplab::io::write_atomic(&a.output, &bytes)?)
}

/// The PCF and RDF of a set against r / d_max.
fn pcf_chart(set: &samplab::PointSet, title: String) -> anyhow::Result<draw::LineChart> {
    use samplab::spatial;
    let d_max = 2.0 * spatial::packing_radius(set.len(), set.dims())?;
    let top = (3.0 * d_max).min(0.5);
    let radii: Vec<f64> = (1..=300).map(|k| 0.05 * d_max + (top - 0.05 * d_max) * (k - 1) as f64 / 299.0).collect();
    let g = spatial::pcf(set, &radii, d_max / 8.0)?;
    let edges: Vec<f64> = (0..).map(|k| k as f64 * d_max / 10.0).take_while(|&e| e <= top).collect();
    let h = spatial::rdf(set, &edges)?;
    let scaled = |r: f64| r / d_max;
    let mut histogram = draw::Series::line(
        "shell histogram (RDF)",
        edges.windows(2).zip(&h).map(|(w, &v)| (scaled(0.5 * (w[0] + w[1])), v)).collect(),
    );
    histogram.markers = true;
    let mut white = draw::Series::line("white noise", vec![(scaled(radii[0]), 1.0), (scaled(top), 1.0)]);
    white.dashed = true;
    Ok(draw::LineChart {
        title: format!("{title}: pair correlation"),
        x_label: "r / d_max".into(),
        y_label: "g(r)".into(),
        series: vec![
            draw::Series::line("Gaussian kernel (PCF)", radii.iter().map(|&r| scaled(r)).zip(g).collect()),
            histogram,
            white,
        ],
        log_y: false,
        log_x: false,
        polar: false,
    })
}
