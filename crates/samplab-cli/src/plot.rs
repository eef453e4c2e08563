//! `samplab plot`: a scatter plot of one set with its two 1D marginal histograms.

use std::path::PathBuf;

use anyhow::bail;
use samplab::io::{self, Format};
use samplab_report::plot::{self as draw, Scatter};

/// Plot a point set.
#[derive(clap::Args)]
#[command(after_help = "Example:\n  samplab generate jitter -n 256 -o j.txt && samplab plot j.txt -o j.png --grid 16")]
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
}

pub fn run(a: &Args) -> anyhow::Result<()> {
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
    let chart = Scatter { set, axes: [a.axes[0], a.axes[1]], grid: a.grid, title };
    let size = (a.size, a.size);
    let bytes = match a.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("svg") => draw::svg(&chart, size)?.into_bytes(),
        Some("png") => draw::png(&chart, size)?,
        _ => bail!("-o {}: the output must end in .png or .svg", a.output.display()),
    };
    Ok(samplab::io::write_atomic(&a.output, &bytes)?)
}
