//! Plots for the CLI and the reports: PNG (with the bundled DejaVu Sans, so no system
//! fonts are needed) and SVG from one drawing routine. The same strategy has the same
//! colour in every figure.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use samplab::PointSet;

use crate::Error;

const FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// Something that can draw itself on any plotters backend.
pub trait Drawable {
    /// Draw on `root`.
    ///
    /// # Errors
    /// A backend failure, as text.
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String>;

    /// Draw on a bitmap: the pixels of [`Drawable::draw`], where a bitmap lets some of the
    /// drawing be left out (an SVG keeps every element, even one that covers nothing).
    ///
    /// # Errors
    /// As [`Drawable::draw`].
    fn draw_bitmap(&self, root: DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String> {
        self.draw(root)
    }

    /// What the figure lint finds wrong in the chart as specified (two series drawn alike,
    /// an axis too wide to read); what can only be seen in the drawing is checked on its
    /// SVG by [`crate::lint`].
    fn lint(&self) -> Vec<String> {
        Vec::new()
    }
}

fn register_fonts() -> Result<(), Error> {
    for family in ["sans-serif", "serif", "monospace"] {
        plotters::style::register_font(family, FontStyle::Normal, FONT)
            .map_err(|_| Error::Plot("the bundled font is invalid".into()))?;
    }
    Ok(())
}

/// The drawing as SVG text.
///
/// # Errors
/// A drawing failure.
pub fn svg(d: &impl Drawable, (w, h): (u32, u32)) -> Result<String, Error> {
    register_fonts()?;
    let mut out = String::new();
    d.draw(SVGBackend::with_string(&mut out, (w, h)).into_drawing_area()).map_err(Error::Plot)?;
    Ok(out)
}

/// The drawing as PNG bytes.
///
/// # Errors
/// A drawing or encoding failure.
pub fn png(d: &impl Drawable, (w, h): (u32, u32)) -> Result<Vec<u8>, Error> {
    register_fonts()?;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    d.draw_bitmap(BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area()).map_err(Error::Plot)?;
    let img =
        samplab_render::image::Srgb8::from_raw(w, h, buf).ok_or_else(|| Error::Plot("image buffer size".into()))?;
    img.png().map_err(|e| Error::Plot(e.to_string()))
}

/// The colour of a strategy, the same in every figure: a fixed table (tab20 colours)
/// keyed by sampler family (the spec up to ':', variants of the low-discrepancy families
/// sharing their family's colour), then a stable hash for anything else.
///
/// # Panics
/// Never: the table of shades it picks from is not empty.
pub fn colour(strategy: &str) -> RGBColor {
    const TABLE: [(&str, RGBColor); 17] = [
        ("random", RGBColor(31, 119, 180)),
        ("regular", RGBColor(255, 127, 14)),
        ("jitter", RGBColor(44, 160, 44)),
        ("jitter.half", RGBColor(214, 39, 40)),
        ("nrooks", RGBColor(148, 103, 189)),
        ("poisson", RGBColor(0, 0, 128)),
        ("jitter.uniform", RGBColor(227, 119, 194)),
        ("jitter.gaussian", RGBColor(127, 127, 127)),
        ("halton", RGBColor(188, 189, 34)),
        ("sobol", RGBColor(23, 190, 207)),
        ("pmj02", RGBColor(0, 0, 0)),
        ("hammersley", RGBColor(174, 199, 232)),
        ("cmj", RGBColor(255, 152, 150)),
        ("jitter.box", RGBColor(152, 223, 138)),
        ("force-matrix", RGBColor(197, 176, 213)),
        ("regular.rotated", RGBColor(255, 187, 120)),
        // noise floors and other reference levels
        ("floor", RGBColor(96, 96, 96)),
    ];
    let spec = strategy.split(':').next().unwrap_or(strategy);
    // Gaussian jitter: the paper's browns, one clearly distinct shade per sigma it uses
    if spec == "jitter.gaussian" {
        let sigma = strategy
            .split("sigma=")
            .nth(1)
            .and_then(|v| v.split(',').next())
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.25);
        const SHADES: [(f64, RGBColor); 4] = [
            (0.1, RGBColor(84, 39, 4)),
            (0.25, RGBColor(166, 86, 40)),
            (0.5, RGBColor(221, 150, 60)),
            (1.0, RGBColor(240, 200, 120)),
        ];
        return SHADES.iter().min_by(|a, b| (a.0 - sigma).abs().total_cmp(&(b.0 - sigma).abs())).expect("shades").1;
    }
    let family = ["halton", "sobol", "hammersley", "poisson"].into_iter().find(|f| spec.starts_with(f)).unwrap_or(spec);
    TABLE.iter().find(|(k, _)| *k == family).map(|(_, c)| *c).unwrap_or_else(|| {
        let h = strategy.bytes().fold(2_166_136_261u32, |h, b| (h ^ u32::from(b)).wrapping_mul(16_777_619));
        TABLE[(h % TABLE.len() as u32) as usize].1
    })
}

fn err<E: std::fmt::Debug>(e: E) -> String {
    format!("{e:?}")
}

/// A scatter plot of two coordinates of a set with its two 1D marginal histograms.
pub struct Scatter<'a> {
    /// The points.
    pub set: &'a PointSet,
    /// Which coordinates go on the x and y axes.
    pub axes: [usize; 2],
    /// Strata lines: k x k.
    pub grid: Option<usize>,
    /// The title.
    pub title: String,
}

/// The plotted range of one coordinate: [0,1] for unit-cube sets, else the data's span.
fn range(v: &[f64]) -> (f64, f64) {
    let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| (l.min(x), h.max(x)));
    if lo >= 0.0 && hi <= 1.0 {
        (0.0, 1.0)
    } else {
        let (lo, hi) = span(lo, hi);
        let pad = 0.02 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

/// The most an axis reaches: past it a span of two values can overflow, and plotters'
/// search for ticks does not end on an infinite or empty range.
const AXIS_LIMIT: f64 = 1e300;

/// A linear axis over [lo, hi]: clamped to +-[`AXIS_LIMIT`], widened when empty ([0, 1]
/// when there is no finite value).
fn span(lo: f64, hi: f64) -> (f64, f64) {
    if lo.is_nan() || hi.is_nan() || lo > hi || !lo.is_finite() && !hi.is_finite() {
        return (0.0, 1.0);
    }
    let (lo, hi) = (lo.clamp(-AXIS_LIMIT, AXIS_LIMIT), hi.clamp(-AXIS_LIMIT, AXIS_LIMIT));
    if hi > lo && (hi - lo) > 1e-9 * lo.abs().max(hi.abs()) {
        return (lo, hi);
    }
    let w = (1e-3 * lo.abs()).max(1e-3);
    (lo - w, hi + w)
}

/// A logarithmic axis over [lo, hi]: within [1 / [`AXIS_LIMIT`], [`AXIS_LIMIT`]]; the decade
/// below `hi` when it is empty or no value is positive.
fn log_span(lo: f64, hi: f64) -> (f64, f64) {
    let hi = if hi > 0.0 { hi.clamp(1.0 / AXIS_LIMIT, AXIS_LIMIT) } else { 1.0 };
    let lo = if lo > 0.0 { lo.clamp(1.0 / AXIS_LIMIT, hi) } else { hi / 10.0 };
    if hi > lo * (1.0 + 1e-9) { (lo, hi) } else { (hi / 10.0, hi) }
}

/// Counts per bin as a density relative to uniform (1 = exactly uniform).
fn histogram(v: &[f64], (lo, hi): (f64, f64), bins: usize) -> Vec<f64> {
    let mut h = vec![0.0; bins];
    for &x in v {
        let b = (((x - lo) / (hi - lo)) * bins as f64) as usize;
        h[b.min(bins - 1)] += 1.0;
    }
    let expect = v.len() as f64 / bins as f64;
    h.iter_mut().for_each(|c| *c /= expect);
    h
}

/// A marginal histogram's density label, left out at zero (where it would meet the
/// scatter's own axis labels).
fn nonzero(v: &f64) -> String {
    if *v == 0.0 { String::new() } else { tick(*v, false) }
}

/// A marginal histogram: bars along the data axis (`range`), heights up to `hmax`;
/// `sideways` draws it on the right of the scatter, bars growing to the right.
fn marginal<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    counts: &[f64],
    range: (f64, f64),
    hmax: f64,
    sideways: bool,
) -> Result<(), String> {
    let bar = RGBColor(120, 120, 120).filled();
    let w = (range.1 - range.0) / counts.len() as f64;
    let bars = counts.iter().enumerate().map(|(i, &c)| (range.0 + i as f64 * w, range.0 + (i + 1) as f64 * w, c));
    let mut builder = ChartBuilder::on(area);
    builder.margin(8);
    if sideways {
        let mut chart = builder
            .x_label_area_size(40)
            .y_label_area_size(0)
            .build_cartesian_2d(0.0..hmax, range.0..range.1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_y_axis()
            .x_desc("density")
            .x_labels(3)
            .x_label_formatter(&nonzero)
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        chart.draw_series(bars.map(|(a, b, c)| Rectangle::new([(0.0, a), (c, b)], bar))).map_err(err)?;
    } else {
        let mut chart = builder
            .y_label_area_size(50)
            .x_label_area_size(0)
            .build_cartesian_2d(range.0..range.1, 0.0..hmax)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc("density")
            .y_labels(3)
            .y_label_formatter(&nonzero)
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        chart.draw_series(bars.map(|(a, b, c)| Rectangle::new([(a, 0.0), (b, c)], bar))).map_err(err)?;
    }
    Ok(())
}

impl Drawable for Scatter<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let (xs, ys) = (self.set.column(self.axes[0]), self.set.column(self.axes[1]));
        let (rx, ry) = (range(&xs), range(&ys));
        let bins = ((self.set.len() as f64).sqrt() as usize).clamp(8, 64);
        let (hx, hy) = (histogram(&xs, rx, bins), histogram(&ys, ry, bins));
        let hmax = hx.iter().chain(&hy).fold(1.5f64, |m, &v| m.max(v)) * 1.05;
        let root = root.titled(&self.title, ("sans-serif", 22)).map_err(err)?;
        let (w, h) = root.dim_in_pixel();
        let side = (w.min(h) as f64 * 0.2) as u32;
        let (top, bottom) = root.split_vertically(side);
        let (main, right) = bottom.split_horizontally(w - side);
        let (top_hist, _) = top.split_horizontally(w - side);
        let mut chart = ChartBuilder::on(&main)
            .margin(8)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(rx.0..rx.1, ry.0..ry.1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(format!("x{}", self.axes[0]))
            .y_desc(format!("x{}", self.axes[1]))
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(err)?;
        if let Some(k) = self.grid {
            let grey = RGBColor(200, 200, 200);
            for i in 0..=k {
                let (gx, gy) = (rx.0 + i as f64 * (rx.1 - rx.0) / k as f64, ry.0 + i as f64 * (ry.1 - ry.0) / k as f64);
                chart.draw_series(LineSeries::new([(gx, ry.0), (gx, ry.1)], grey)).map_err(err)?;
                chart.draw_series(LineSeries::new([(rx.0, gy), (rx.1, gy)], grey)).map_err(err)?;
            }
        }
        let radius = if self.set.len() > 20_000 {
            1
        } else if self.set.len() > 2000 {
            2
        } else {
            3
        };
        // a value past the axis (clamped to +-1e300) is drawn at its edge
        let at = |v: f64, (lo, hi): (f64, f64)| v.clamp(lo, hi);
        chart
            .draw_series(
                xs.iter()
                    .zip(&ys)
                    .map(|(&x, &y)| Circle::new((at(x, rx), at(y, ry)), radius, RGBColor(31, 119, 180).filled())),
            )
            .map_err(err)?;
        marginal(&top_hist, &hx, rx, hmax, false)?;
        marginal(&right, &hy, ry, hmax, true)?;
        root.present().map_err(err)
    }
}

/// A 2D set drawn through a warp with the k x k strata of the square it came from, their
/// boundaries warped too (Shirley 1991, Figures 7 and 8).
pub struct Strata<'a> {
    /// The points in the unit square.
    pub set: &'a PointSet,
    /// The warp (2D to 2D).
    pub warp: &'a dyn samplab::warp::Warp,
    /// Strata per axis.
    pub cells: usize,
    /// The title.
    pub title: String,
}

impl Drawable for Strata<'_> {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let map = |u: f64, v: f64| {
            let mut o = [0.0; 2];
            // a boundary at exactly 1 lies outside [0,1): pull it in by an ulp-sized step
            let w = self.warp.forward(&[u.min(1.0 - 1e-12), v.min(1.0 - 1e-12)], &mut o);
            w.then_some((o[0], o[1]))
        };
        // boundaries: lines u = i/k and v = i/k, each through 200 points
        let steps = 200;
        let mut lines: Vec<Vec<(f64, f64)>> = Vec::new();
        for i in 0..=self.cells {
            let c = i as f64 / self.cells as f64;
            let t = |j: usize| j as f64 / steps as f64;
            lines.push((0..=steps).filter_map(|j| map(c, t(j))).collect());
            lines.push((0..=steps).filter_map(|j| map(t(j), c)).collect());
        }
        let points: Vec<(f64, f64)> = self.set.iter().filter_map(|p| map(p[0], p[1])).collect();
        let (lo, hi) = lines
            .iter()
            .flatten()
            .chain(&points)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| (l.min(p.0).min(p.1), h.max(p.0).max(p.1)));
        let pad = 0.03 * (hi - lo);
        let mut chart = ChartBuilder::on(&root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(44)
            .build_cartesian_2d(lo - pad..hi + pad, lo - pad..hi + pad)
            .map_err(err)?;
        chart.configure_mesh().disable_mesh().label_style(("sans-serif", 13)).draw().map_err(err)?;
        let grey = RGBColor(150, 150, 150);
        for l in lines {
            chart.draw_series(LineSeries::new(l, grey)).map_err(err)?;
        }
        chart.draw_series(points.iter().map(|&p| Circle::new(p, 4, RGBColor(31, 119, 180).filled()))).map_err(err)?;
        root.present().map_err(err)
    }
}

/// A tick label as a paper prints it: 10, 20, 50 or 0.01 (scientific notation only for
/// log-axis values below 1e-4 or from 1e5 up), at most six significant digits (no
/// floating-point noise such as 0.30000000000000004).
fn tick(v: f64, log: bool) -> String {
    if log && !(1e-4..1e5).contains(&v.abs()) {
        format!("{v:.0e}")
    } else if v == 0.0 {
        "0".into()
    } else {
        let digits = (5 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
        let s = format!("{v:.digits$}");
        if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
    }
}

/// The labelled values of a log axis over [lo, hi]: 1, 2 and 5 times each power of ten,
/// every mantissa 1 to 9 when that leaves fewer than two, and only the powers of ten when
/// the axis spans more than six decades.
fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let pick = |mantissas: &[f64]| -> Vec<f64> {
        (lo.log10().floor() as i32..=hi.log10().ceil() as i32)
            .flat_map(|k| mantissas.iter().map(move |m| m * 10f64.powi(k)))
            .filter(|v| (lo..=hi).contains(v))
            .collect()
    };
    let decades = (hi / lo).log10();
    let ticks = pick(if decades > 6.0 { &[1.0] } else { &[1.0, 2.0, 5.0] });
    if ticks.len() >= 2 { ticks } else { pick(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0]) }
}

/// One named curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend label; also picks the colour (see [`colour`]) unless `colour_key` is set.
    pub name: String,
    /// The key for [`colour`] (defaults to the name).
    pub colour_key: Option<String>,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Mark each point (on a thin joining line).
    pub markers: bool,
    /// Dashed (for theory or published curves).
    pub dashed: bool,
    /// Per point, the (low, high) ends of its interval, drawn as a vertical bar; empty for
    /// none.
    pub intervals: Vec<(f64, f64)>,
}

impl Series {
    /// A solid line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series { name: name.into(), colour_key: None, points, markers: false, dashed: false, intervals: Vec::new() }
    }
}

/// A line chart with a legend, optional log axes.
pub struct LineChart {
    /// Title.
    pub title: String,
    /// X axis label, with unit.
    pub x_label: String,
    /// Y axis label, with unit.
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Draw in polar form: x is an angle in degrees, y a radius.
    pub polar: bool,
}

/// How a series looks, in the plot and in its legend swatch.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Look {
    /// A solid line.
    Line,
    /// A dashed line.
    Dashed,
    /// Markers on a thin line (filled or open).
    Marker(bool),
}

/// Font size of legend labels and tick labels.
const LABEL_FONT: u32 = 13;

/// A legend in its own strip right of the plot, so that it can never cover data: a
/// translucent white box with a black border, one swatch per entry in the entry's own
/// style (a dashed series has a dashed swatch), and its label.
fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, RGBColor, Look)],
) -> Result<(), String> {
    if entries.is_empty() {
        return Ok(());
    }
    let (w, _) = area.dim_in_pixel();
    let (x0, y0, row) = (6i32, 40i32, 18i32);
    let (x1, y1) = (w as i32 - 4, y0 + 8 + row * entries.len() as i32);
    area.draw(&Rectangle::new([(x0, y0), (x1, y1)], WHITE.mix(0.85).filled())).map_err(err)?;
    area.draw(&Rectangle::new([(x0, y0), (x1, y1)], BLACK)).map_err(err)?;
    for (i, (label, c, look)) in entries.iter().enumerate() {
        let y = y0 + 4 + row * i as i32 + row / 2;
        let (a, b) = (x0 + 8, x0 + 32);
        match look {
            Look::Line => area.draw(&PathElement::new([(a, y), (b, y)], c.stroke_width(2))).map_err(err)?,
            Look::Dashed => {
                for (p, q) in [(a, a + 7), (a + 11, a + 18), (a + 22, b)] {
                    area.draw(&PathElement::new([(p, y), (q, y)], c.stroke_width(2))).map_err(err)?;
                }
            }
            Look::Marker(filled) => {
                area.draw(&PathElement::new([(a, y), (b, y)], c.stroke_width(1))).map_err(err)?;
                let style = if *filled { c.filled() } else { c.stroke_width(2) };
                area.draw(&Circle::new(((a + b) / 2, y), 4, style)).map_err(err)?;
            }
        }
        area.draw(&Text::new(label.clone(), (b + 6, y - 7), ("sans-serif", LABEL_FONT).into_font())).map_err(err)?;
    }
    Ok(())
}

/// The width of a legend strip for these labels (0 without labels).
fn legend_width(labels: impl Iterator<Item = usize>) -> u32 {
    labels.max().map_or(0, |chars| (chars as f64 * LABEL_FONT as f64 * 0.806 * 0.64) as u32 + 56)
}

/// Decades an axis spans: log10(hi / lo) for a log axis; for a linear one, how far its end
/// lies above the median magnitude of the non-zero values on it (a single value at 1e275
/// beside values near 1 spans 275 decades, however the ticks read).
fn decades((lo, hi): (f64, f64), log: bool, values: &[f64]) -> f64 {
    if log {
        return (hi / lo).log10();
    }
    let mut mags: Vec<f64> = values.iter().map(|v| v.abs()).filter(|&v| v > 0.0 && v.is_finite()).collect();
    if mags.is_empty() {
        return 0.0;
    }
    mags.sort_by(f64::total_cmp);
    (lo.abs().max(hi.abs()) / mags[mags.len() / 2]).log10()
}

/// The most decades an axis may span before its figure fails the lint.
pub const MAX_DECADES: f64 = 12.0;

impl LineChart {
    fn look(s: &Series) -> Look {
        if s.markers {
            Look::Marker(true)
        } else if s.dashed {
            Look::Dashed
        } else {
            Look::Line
        }
    }

    /// The plotted x and y ranges.
    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let ends = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().zip(&s.intervals).flat_map(|(p, i)| [(p.0, i.0), (p.0, i.1)]));
        let all =
            self.series.iter().flat_map(|s| s.points.iter().copied()).chain(ends.filter(|p| !self.log_y || p.1 > 0.0));
        let (x0, x1, y0, y1) = all
            .fold((f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY), |(a, b, c, d), (x, y)| {
                (a.min(x), b.max(x), c.min(y), d.max(y))
            });
        let ((x0, x1), (y0, y1)) = (span(x0, x1), span(y0, y1));
        let ylo = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .filter(|&y| y > 0.0)
            .fold(f64::INFINITY, f64::min);
        let pad = 0.05 * (y1 - y0);
        let x = if self.log_x { log_span(x0 * 0.8, x1 * 1.25) } else { (x0, x1) };
        let y = if self.log_y { log_span(ylo * 0.8, y1 * 1.25) } else { ((y0 - pad).min(0.0), y1 + pad) };
        (x, y)
    }

    /// The labels of the log axes, drawn at [`log_ticks`] beside them (`at` maps a point
    /// to its pixel in `main`; plotters' own log labels are blank).
    fn log_labels<DB: DrawingBackend>(
        &self,
        main: &DrawingArea<DB, Shift>,
        ((x0, x1), (y0, y1)): ((f64, f64), (f64, f64)),
        at: impl Fn(f64, f64) -> (i32, i32),
    ) -> Result<(), String> {
        let font = TextStyle::from(("sans-serif", LABEL_FONT).into_font());
        if self.log_y {
            for v in log_ticks(y0, y1) {
                let (px, py) = at(x0, v);
                main.draw(&PathElement::new([(px - 5, py), (px, py)], BLACK)).map_err(err)?;
                let style = font.clone().pos(Pos::new(HPos::Right, VPos::Center));
                main.draw(&Text::new(tick(v, true), (px - 8, py), style)).map_err(err)?;
            }
        }
        if self.log_x {
            for v in log_ticks(x0, x1) {
                let (px, py) = at(v, y0);
                main.draw(&PathElement::new([(px, py), (px, py + 5)], BLACK)).map_err(err)?;
                let style = font.clone().pos(Pos::new(HPos::Center, VPos::Top));
                main.draw(&Text::new(tick(v, true), (px, py + 8), style)).map_err(err)?;
            }
        }
        Ok(())
    }

    fn draw_polar<DB: DrawingBackend>(&self, main: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let (_, (_, y1)) = self.ranges();
        let r = y1.max(1e-12) * 1.05;
        let mut chart = ChartBuilder::on(main)
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(56)
            .build_cartesian_2d(-r..r, -r..r)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.y_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        let grey = RGBColor(215, 215, 215);
        for k in 1..=4 {
            let rr = r * k as f64 / 4.0;
            let circle = (0..=180).map(|t| (t as f64 * 2.0).to_radians()).map(|t| (rr * t.cos(), rr * t.sin()));
            chart.draw_series(LineSeries::new(circle, grey)).map_err(err)?;
        }
        for s in &self.series {
            let c = colour(s.colour_key.as_deref().unwrap_or(&s.name));
            // the projection at angle + 180 degrees is the same: draw both halves
            let half = |turn: f64| s.points.iter().map(move |&(a, v)| ((a + turn).to_radians(), v));
            let pts: Vec<(f64, f64)> = half(0.0).chain(half(180.0)).map(|(a, v)| (v * a.cos(), v * a.sin())).collect();
            chart.draw_series(LineSeries::new(pts, c.stroke_width(2))).map_err(err)?;
        }
        Ok(())
    }
}

impl Drawable for LineChart {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let root = root.titled(&self.title, ("sans-serif", 20)).map_err(err)?;
        let (w, _) = root.dim_in_pixel();
        let (main, strip) =
            root.split_horizontally(w - legend_width(self.series.iter().map(|s| s.name.chars().count())));
        let entries: Vec<(String, RGBColor, Look)> = self
            .series
            .iter()
            .map(|s| (s.name.clone(), colour(s.colour_key.as_deref().unwrap_or(&s.name)), LineChart::look(s)))
            .collect();
        if self.polar {
            self.draw_polar(&main)?;
            legend(&strip, &entries)?;
            return root.present().map_err(err);
        }
        let ((x0, x1), (y0, y1)) = self.ranges();
        macro_rules! finish {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(self.x_label.as_str())
                    .y_desc(self.y_label.as_str())
                    // a log axis's labels are drawn below at log_ticks; a linear one has a
                    // label per 80 px
                    .x_labels((main.dim_in_pixel().0 as usize / 80).max(3))
                    .x_label_formatter(&|v| if self.log_x { String::new() } else { tick(*v, false) })
                    .y_label_formatter(&|v| if self.log_y { String::new() } else { tick(*v, false) })
                    .label_style(("sans-serif", LABEL_FONT))
                    .light_line_style(RGBColor(235, 235, 235))
                    .draw()
                    .map_err(err)?;
                for (s, (_, c, look)) in self.series.iter().zip(&entries) {
                    let c = *c;
                    let style = c.stroke_width(2);
                    for (&(x, _), &(lo, hi)) in s.points.iter().zip(&s.intervals) {
                        let lo = if self.log_y && lo <= 0.0 { y0 } else { lo };
                        chart.draw_series(LineSeries::new([(x, lo), (x, hi)], c.stroke_width(1))).map_err(err)?;
                    }
                    let points = s.points.iter().copied();
                    match look {
                        Look::Marker(_) => {
                            chart.draw_series(LineSeries::new(points, c.stroke_width(1))).map_err(err)?;
                            chart.draw_series(s.points.iter().map(|&p| Circle::new(p, 4, c.filled()))).map_err(err)?;
                        }
                        Look::Dashed => {
                            chart.draw_series(DashedLineSeries::new(points, 6, 4, style)).map_err(err)?;
                        }
                        Look::Line => {
                            chart.draw_series(LineSeries::new(points, style)).map_err(err)?;
                        }
                    }
                }
                let base = main.get_base_pixel();
                let at = |x: f64, y: f64| {
                    let (px, py) = chart.backend_coord(&(x, y));
                    (px - base.0, py - base.1)
                };
                self.log_labels(&main, ((x0, x1), (y0, y1)), at)?;
            }};
        }
        let mut builder = ChartBuilder::on(&main);
        builder.margin(12).x_label_area_size(40).y_label_area_size(64);
        match (self.log_x, self.log_y) {
            (true, true) => {
                finish!(builder.build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale()).map_err(err)?)
            }
            (false, true) => finish!(builder.build_cartesian_2d(x0..x1, (y0..y1).log_scale()).map_err(err)?),
            (true, false) => finish!(builder.build_cartesian_2d((x0..x1).log_scale(), y0..y1).map_err(err)?),
            (false, false) => finish!(builder.build_cartesian_2d(x0..x1, y0..y1).map_err(err)?),
        }
        legend(&strip, &entries)?;
        root.present().map_err(err)
    }

    fn lint(&self) -> Vec<String> {
        let mut found = Vec::new();
        for (i, a) in self.series.iter().enumerate() {
            let key = |s: &Series| (colour(s.colour_key.as_deref().unwrap_or(&s.name)), LineChart::look(s));
            if let Some(b) = self.series[..i].iter().find(|b| key(b) == key(a)) {
                found.push(format!("series '{}' and '{}' are drawn in the same colour and style", b.name, a.name));
            }
        }
        let ((x0, x1), (y0, y1)) = self.ranges();
        let xs: Vec<f64> = self.series.iter().flat_map(|s| s.points.iter().map(|p| p.0)).collect();
        let ys: Vec<f64> = self.series.iter().flat_map(|s| s.points.iter().map(|p| p.1)).collect();
        for (axis, range, log, values) in [("x", (x0, x1), self.log_x, &xs), ("y", (y0, y1), self.log_y, &ys)] {
            let d = decades(range, log, values);
            if d > MAX_DECADES {
                found.push(format!("the {axis} axis spans {d:.0} decades ([{:.3e}, {:.3e}])", range.0, range.1));
            }
        }
        found
    }
}

/// One marker series of a [`DotChart`]: name, colour key, and per category a value with
/// the half-width of its error bar (None: no value).
pub type DotSeries = (String, String, Vec<Option<(f64, f64)>>);

/// Values with error bars per category, one marker series per source (ours, published).
pub struct DotChart {
    /// Title.
    pub title: String,
    /// Y axis label.
    pub y_label: String,
    /// Category names along x.
    pub categories: Vec<String>,
    /// (series name, colour key, values with half-widths of the error bars, per category).
    pub series: Vec<DotSeries>,
}

impl Drawable for DotChart {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let vals = self.series.iter().flat_map(|s| s.2.iter().flatten());
        let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &(v, e)| (l.min(v - e), h.max(v + e)));
        let (lo, hi) = if lo.is_finite() { span(0f64.min(lo), hi * 1.1) } else { (0.0, 1.0) };
        let k = self.categories.len();
        let root = root.titled(&self.title, ("sans-serif", 20)).map_err(err)?;
        let (w, _) = root.dim_in_pixel();
        let (main, strip) = root.split_horizontally(w - legend_width(self.series.iter().map(|s| s.0.chars().count())));
        let mut chart = ChartBuilder::on(&main)
            .margin(12)
            .x_label_area_size(60)
            .y_label_area_size(64)
            .build_cartesian_2d(-0.5..(k as f64 - 0.5), lo..hi)
            .map_err(err)?;
        let cats = self.categories.clone();
        chart
            .configure_mesh()
            .x_labels(k)
            .x_label_formatter(&|x| {
                let i = x.round();
                if (x - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < cats.len() {
                    cats[i as usize].clone()
                } else {
                    String::new()
                }
            })
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 13))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
            .map_err(err)?;
        let m = self.series.len() as f64;
        let mut entries = Vec::new();
        for (si, (name, key, values)) in self.series.iter().enumerate() {
            let c = colour(key);
            let dx = (si as f64 - (m - 1.0) / 2.0) * 0.18;
            let pts: Vec<(f64, f64, f64)> =
                values.iter().enumerate().filter_map(|(i, v)| v.map(|(y, e)| (i as f64 + dx, y, e))).collect();
            chart
                .draw_series(pts.iter().map(|&(x, y, e)| PathElement::new([(x, y - e), (x, y + e)], c.stroke_width(2))))
                .map_err(err)?;
            let filled = si == 0;
            chart
                .draw_series(
                    pts.iter()
                        .map(|&(x, y, _)| Circle::new((x, y), 5, if filled { c.filled() } else { c.stroke_width(2) })),
                )
                .map_err(err)?;
            entries.push((name.clone(), c, Look::Marker(filled)));
        }
        legend(&strip, &entries)?;
        root.present().map_err(err)
    }
}

/// Viridis (perceptually uniform), sampled at nine points and interpolated linearly.
fn viridis(t: f64) -> RGBColor {
    const STOPS: [(f64, f64, f64); 9] = [
        (68.0, 1.0, 84.0),
        (71.0, 44.0, 122.0),
        (59.0, 81.0, 139.0),
        (44.0, 113.0, 142.0),
        (33.0, 144.0, 141.0),
        (39.0, 173.0, 129.0),
        (92.0, 200.0, 99.0),
        (170.0, 220.0, 50.0),
        (253.0, 231.0, 37.0),
    ];
    let x = t.clamp(0.0, 1.0) * 8.0;
    let i = (x.floor() as usize).min(7);
    let f = x - i as f64;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let mix = |p: f64, q: f64| (p + (q - p) * f).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// A grid of values drawn as coloured cells, log10 or linear colour scale (viridis), with
/// a colour bar.
pub struct HeatMap {
    /// Title.
    pub title: String,
    /// What the colours show.
    pub label: String,
    /// Row-major values, `rows` x `cols`; row 0 is drawn at the bottom.
    pub values: Vec<f64>,
    /// Number of rows (along y).
    pub rows: usize,
    /// Number of columns (along x).
    pub cols: usize,
    /// The x range the columns span.
    pub x_range: (f64, f64),
    /// The y range the rows span.
    pub y_range: (f64, f64),
    /// Axis labels.
    pub x_label: String,
    /// Axis labels.
    pub y_label: String,
    /// Colour by log10 of the values.
    pub log: bool,
}

impl HeatMap {
    /// A `res` x `res` grid of centred integer frequencies (index res/2 is 0 on both axes).
    pub fn centred(title: String, label: String, values: Vec<f64>, res: usize) -> HeatMap {
        let half = (res / 2) as f64;
        HeatMap {
            title,
            label,
            values,
            rows: res,
            cols: res,
            x_range: (-half - 0.5, half - 0.5),
            y_range: (-half - 0.5, half - 0.5),
            x_label: "frequency (cycles per unit), axis 1".into(),
            y_label: "frequency, axis 0".into(),
            log: true,
        }
    }

    /// The values on the colour scale (log10 when `log`, NaN where a value has none) and
    /// the scale's range.
    fn scaled(&self) -> (Vec<f64>, (f64, f64)) {
        let scaled: Vec<f64> = self
            .values
            .iter()
            .map(|&v| {
                if !self.log {
                    v
                } else if v > 0.0 {
                    v.log10()
                } else {
                    f64::NAN
                }
            })
            .collect();
        let (lo, hi) = scaled
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        let (lo, hi) = if !lo.is_finite() {
            (0.0, 1.0)
        } else if self.log {
            (lo.max(hi - 12.0), hi.max(lo + 1e-9))
        } else {
            (lo, hi.max(lo + 1e-12))
        };
        (scaled, (lo, hi))
    }

    /// [`Drawable::draw`], leaving out the cells whose edges meet on one pixel column or
    /// row when `bitmap`.
    fn draw_cells<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>, bitmap: bool) -> Result<(), String> {
        root.fill(&WHITE).map_err(err)?;
        let (scaled, (lo, hi)) = self.scaled();
        let (w, _) = root.dim_in_pixel();
        let (map, bar) = root.split_horizontally(w - 110);
        let (x0, x1) = self.x_range;
        let (y0, y1) = self.y_range;
        let mut chart = ChartBuilder::on(&map)
            .caption(&self.title, ("sans-serif", 18))
            .margin(10)
            .x_label_area_size(36)
            .y_label_area_size(52)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(err)?;
        let (dx, dy) = ((x1 - x0) / self.cols as f64, (y1 - y0) / self.rows as f64);
        // the cells' edges in pixels (the x of a point depends on its x only): the rows and
        // columns of cells wider than no pixel
        let (x_at, y_at) = (|j: usize| x0 + j as f64 * dx, |i: usize| y0 + i as f64 * dy);
        let wide = |edges: Vec<i32>| -> Vec<usize> {
            (0..edges.len() - 1).filter(|&k| !bitmap || edges[k] != edges[k + 1]).collect()
        };
        let cols = wide((0..=self.cols).map(|j| chart.backend_coord(&(x_at(j), y0)).0).collect());
        let rows = wide((0..=self.rows).map(|i| chart.backend_coord(&(x0, y_at(i))).1).collect());
        chart
            .draw_series(rows.iter().flat_map(|&i| cols.iter().map(move |&j| (i, j))).map(|(i, j)| {
                let v = scaled[i * self.cols + j];
                let c = if v.is_finite() { viridis((v - lo) / (hi - lo)) } else { viridis(0.0) };
                Rectangle::new([(x_at(j), y_at(i)), (x_at(j + 1), y_at(i + 1))], c.filled())
            }))
            .map_err(err)?;
        let mut scale = ChartBuilder::on(&bar)
            .margin_top(40)
            .margin_bottom(46)
            .margin_right(8)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..1.0, lo..hi)
            .map_err(err)?;
        scale
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(if self.log { format!("log10 {}", self.label) } else { self.label.clone() })
            .label_style(("sans-serif", 11))
            .draw()
            .map_err(err)?;
        let steps = 100;
        scale
            .draw_series((0..steps).map(|k| {
                let (a, b) = (lo + (hi - lo) * k as f64 / steps as f64, lo + (hi - lo) * (k + 1) as f64 / steps as f64);
                Rectangle::new([(0.0, a), (1.0, b)], viridis(k as f64 / (steps - 1) as f64).filled())
            }))
            .map_err(err)?;
        root.present().map_err(err)
    }
}

impl Drawable for HeatMap {
    fn draw<DB: DrawingBackend>(&self, root: DrawingArea<DB, Shift>) -> Result<(), String> {
        self.draw_cells(root, false)
    }

    /// A bitmap fills a rectangle's pixel columns from its left edge's up to, not
    /// including, its right edge's, and its rows likewise, so a cell whose edges fall on
    /// the same pixel column or row fills nothing and is left out: at 1024^2 cells in
    /// 820 x 700 pixels, 6 in 10 of them.
    fn draw_bitmap(&self, root: DrawingArea<BitMapBackend<'_>, Shift>) -> Result<(), String> {
        self.draw_cells(root, true)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_heat_map_bitmap_is_every_cell_drawn() {
        // the cells left out on a bitmap change no pixel: against all of them drawn, with
        // more cells than pixels, about as many, and fewer, square and not
        let pixels = |map: &HeatMap, size: (u32, u32), all: bool| {
            register_fonts().unwrap();
            let mut buf = vec![255u8; (size.0 * size.1 * 3) as usize];
            let root = BitMapBackend::with_buffer(&mut buf, size).into_drawing_area();
            if all { map.draw(root) } else { map.draw_bitmap(root) }.unwrap();
            buf
        };
        for (rows, cols, size) in
            [(1024, 1024, (820, 700)), (300, 700, (480, 420)), (37, 5, (400, 300)), (640, 600, (760, 700))]
        {
            let values = (0..rows * cols).map(|k| 1.0 + ((k * 7919) % 1000) as f64).collect();
            let map = HeatMap {
                rows,
                cols,
                x_range: (-3.0, 2.0),
                y_range: (0.5, 0.5 + rows as f64),
                ..HeatMap::centred("t".into(), "v".into(), values, 0)
            };
            assert!(pixels(&map, size, true) == pixels(&map, size, false), "{rows} x {cols} cells in {size:?}");
        }
    }

    #[test]
    fn ticks_read_like_a_paper() {
        assert_eq!(tick(10.0, true), "10");
        assert_eq!(tick(20.000000000000004, true), "20");
        assert_eq!(tick(0.01, true), "0.01");
        assert_eq!(tick(1e-7, true), "1e-7");
        assert_eq!(tick(0.30000000000000004, false), "0.3");
        assert_eq!(log_ticks(4.0, 64.0), [5.0, 10.0, 20.0, 50.0]);
        let fine = log_ticks(0.03, 0.045);
        assert_eq!(fine.len(), 2, "{fine:?}");
        assert_eq!(log_ticks(1e-9, 1.0).len(), 10, "powers of ten only over nine decades");
    }

    #[test]
    fn the_lint_refuses_an_axis_to_1e275_and_two_series_drawn_alike() {
        let chart = |points: Vec<(f64, f64)>, log_y: bool| LineChart {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series::line("a", points)],
            log_y,
            log_x: false,
            polar: false,
        };
        let broken = vec![(1.0, 0.5), (2.0, 1.0), (3.0, 2.0), (4.0, 1e275)];
        for log in [false, true] {
            let found = chart(broken.clone(), log).lint();
            assert!(found.iter().any(|f| f.contains("the y axis spans")), "log {log}: {found:?}");
        }
        assert!(chart(vec![(1.0, 1e-6), (2.0, 1e5)], true).lint().is_empty(), "11 decades are allowed");
        let mut twins = chart(vec![(1.0, 1.0), (2.0, 2.0)], false);
        twins.series.push(Series { colour_key: Some("a".into()), ..Series::line("b", vec![(1.0, 2.0)]) });
        assert!(twins.lint()[0].contains("same colour and style"));
        twins.series[1].dashed = true;
        assert!(twins.lint().is_empty(), "a dashed twin is told apart by its style");
    }

    #[test]
    fn gaussian_jitter_sigmas_have_distinct_colours() {
        let (a, b) = (colour("jitter.gaussian:sigma=0.1"), colour("jitter.gaussian:sigma=0.25"));
        let distance = (i32::from(a.0) - i32::from(b.0)).abs() + (i32::from(a.1) - i32::from(b.1)).abs();
        assert!(distance > 80, "{a:?} and {b:?} are too close");
    }

    #[test]
    fn intervals_are_drawn_and_widen_the_axis() {
        let chart = |intervals: Vec<(f64, f64)>| LineChart {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![Series { intervals, ..Series::line("a", vec![(1.0, 1.0), (2.0, 2.0)]) }],
            log_y: false,
            log_x: false,
            polar: false,
        };
        let bare = svg(&chart(Vec::new()), (400, 300)).expect("svg");
        let barred = svg(&chart(vec![(0.5, 1.5), (1.0, 7.0)]), (400, 300)).expect("svg");
        let c = colour("a");
        let stroke = format!("stroke=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        let count = |s: &str| s.lines().filter(|l| l.contains("<polyline") && l.contains(&stroke)).count();
        assert_eq!(count(&barred), count(&bare) + 2, "one bar per point");
        // the upper end 7 is inside the axis: the largest tick label grows from about 2 to 6 or 7
        let top = |s: &str| s.lines().filter_map(|l| l.trim().parse::<f64>().ok()).fold(f64::NEG_INFINITY, f64::max);
        assert!(top(&bare) < 3.0 && top(&barred) >= 6.0, "{} {}", top(&bare), top(&barred));
    }
}
