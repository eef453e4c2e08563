//! `samplab plot`: a scatter plot of one set with its two 1D marginal histograms.

use std::path::PathBuf;

use anyhow::{Context as _, bail};
use plotters::coord::Shift;
use plotters::prelude::*;
use samplab::PointSet;
use samplab::io::{self, Format};

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

const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

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
    let (w, h) = (a.size, a.size);
    // both backends lay text out with the bundled font, whatever family plotters asks for
    for family in ["sans-serif", "serif", "monospace"] {
        plotters::style::register_font(family, FontStyle::Normal, FONT)
            .map_err(|_| anyhow::anyhow!("the bundled font is invalid"))?;
    }
    let ext = a.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    let bytes = match ext.as_deref() {
        Some("svg") => {
            let mut svg = String::new();
            draw(SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area(), set, a, &title)?;
            svg.into_bytes()
        }
        Some("png") => {
            // the bitmap backend draws text with the bundled font for every family plotters asks for
            for family in ["sans-serif", "serif", "monospace"] {
                plotters::style::register_font(family, FontStyle::Normal, FONT)
                    .map_err(|_| anyhow::anyhow!("the bundled font is invalid"))?;
            }
            let mut buf = vec![255u8; (w * h * 3) as usize];
            draw(BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area(), set, a, &title)?;
            let img = image::RgbImage::from_raw(w, h, buf).context("image buffer")?;
            let mut png = std::io::Cursor::new(Vec::new());
            img.write_to(&mut png, image::ImageFormat::Png)?;
            png.into_inner()
        }
        _ => bail!("-o {}: the output must end in .png or .svg", a.output.display()),
    };
    Ok(samplab::io::write_atomic(&a.output, &bytes)?)
}

/// The plotted range of one coordinate: [0,1] for unit-cube sets, else the data's span.
fn range(v: &[f64]) -> (f64, f64) {
    let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| (l.min(x), h.max(x)));
    if lo >= 0.0 && hi <= 1.0 {
        (0.0, 1.0)
    } else {
        let pad = 0.02 * (hi - lo).max(1e-9);
        (lo - pad, hi + pad)
    }
}

fn histogram(v: &[f64], (lo, hi): (f64, f64), bins: usize) -> Vec<f64> {
    let mut h = vec![0.0; bins];
    for &x in v {
        let b = (((x - lo) / (hi - lo)) * bins as f64) as usize;
        h[b.min(bins - 1)] += 1.0;
    }
    // as a density relative to uniform: 1 means exactly uniform
    let expect = v.len() as f64 / bins as f64;
    h.iter_mut().for_each(|c| *c /= expect);
    h
}

fn draw<DB: DrawingBackend>(root: DrawingArea<DB, Shift>, set: &PointSet, a: &Args, title: &str) -> anyhow::Result<()>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| anyhow::anyhow!("drawing the plot: {e:?}");
    root.fill(&WHITE).map_err(err)?;
    let (xs, ys) = (set.column(a.axes[0]), set.column(a.axes[1]));
    let (rx, ry) = (range(&xs), range(&ys));
    let bins = ((set.len() as f64).sqrt() as usize).clamp(8, 64);
    let (hx, hy) = (histogram(&xs, rx, bins), histogram(&ys, ry, bins));
    let hmax = hx.iter().chain(&hy).fold(1.5f64, |m, &v| m.max(v)) * 1.05;

    let root = root.titled(title, ("sans-serif", 22)).map_err(err)?;
    let (w, h) = root.dim_in_pixel();
    let side = (w.min(h) as f64 * 0.2) as u32;
    let (top, bottom) = root.split_vertically(side);
    let (main, right) = bottom.split_horizontally(w - side);
    let (top_hist, _corner) = top.split_horizontally(w - side);

    let mut chart = ChartBuilder::on(&main)
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(rx.0..rx.1, ry.0..ry.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("x{}", a.axes[0]))
        .y_desc(format!("x{}", a.axes[1]))
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err)?;
    if let Some(k) = a.grid {
        let step_x = (rx.1 - rx.0) / k as f64;
        let step_y = (ry.1 - ry.0) / k as f64;
        let grey = RGBColor(200, 200, 200);
        for i in 0..=k {
            let (gx, gy) = (rx.0 + i as f64 * step_x, ry.0 + i as f64 * step_y);
            chart.draw_series(LineSeries::new([(gx, ry.0), (gx, ry.1)], grey)).map_err(err)?;
            chart.draw_series(LineSeries::new([(rx.0, gy), (rx.1, gy)], grey)).map_err(err)?;
        }
    }
    let radius = if set.len() > 20_000 {
        1
    } else if set.len() > 2000 {
        2
    } else {
        3
    };
    chart
        .draw_series(xs.iter().zip(&ys).map(|(&x, &y)| Circle::new((x, y), radius, RGBColor(31, 119, 180).filled())))
        .map_err(err)?;

    // marginal histograms, as density relative to uniform (1 = flat)
    let bar = RGBColor(120, 120, 120).filled();
    let mut top_chart = ChartBuilder::on(&top_hist)
        .margin(8)
        .y_label_area_size(50)
        .x_label_area_size(0)
        .build_cartesian_2d(rx.0..rx.1, 0.0..hmax)
        .map_err(err)?;
    top_chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("density")
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(err)?;
    let wx = (rx.1 - rx.0) / bins as f64;
    top_chart
        .draw_series(
            hx.iter()
                .enumerate()
                .map(|(i, &c)| Rectangle::new([(rx.0 + i as f64 * wx, 0.0), (rx.0 + (i + 1) as f64 * wx, c)], bar)),
        )
        .map_err(err)?;
    let mut right_chart = ChartBuilder::on(&right)
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(0)
        .build_cartesian_2d(0.0..hmax, ry.0..ry.1)
        .map_err(err)?;
    right_chart
        .configure_mesh()
        .disable_mesh()
        .disable_y_axis()
        .x_desc("density")
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(err)?;
    let wy = (ry.1 - ry.0) / bins as f64;
    right_chart
        .draw_series(
            hy.iter()
                .enumerate()
                .map(|(i, &c)| Rectangle::new([(0.0, ry.0 + i as f64 * wy), (c, ry.0 + (i + 1) as f64 * wy)], bar)),
        )
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}
