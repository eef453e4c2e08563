//! `samplab pixels`: every value a pixel sampler gives a film, as a NumPy array.

use std::path::PathBuf;

use anyhow::Context as _;
use samplab::Seed;
use samplab::pixel::{self, Film};

fn after_help() -> String {
    format!(
        "The array has shape (frames, height, width, spp, dims): value [f, y, x, i, d] is dimension d \
         of sample i of pixel (x, y) in frame f, the same bytes as samplab.pixels() in Python and \
         samplab_pixel_sample() in C.\n\nExamples:\n  samplab pixels zsobol --res 64x64 --spp 16 --dims 8 -o z.npy\n  \
         samplab pixels sobol.padded:randomize=owen --res 32x32 --spp 4 --dims 4 --frames 16 -o p.npy\n\n\
         Pixel samplers: {}.\n`samplab list pixels` lists each with its sample counts, mapping and references.",
        pixel::PIXEL_SAMPLERS.names()
    )
}

/// Draw every value of a film from a pixel sampler.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// Pixel sampler spec, e.g. zsobol, sobol, pmj02.bn:mask=128, openqmc.sobolbn
    spec: String,
    /// Film resolution, WIDTHxHEIGHT
    #[arg(long, value_parser = parse_res)]
    res: (u32, u32),
    /// Samples per pixel
    #[arg(long)]
    spp: u32,
    /// Dimensions per sample
    #[arg(long, default_value_t = 2)]
    dims: u32,
    /// Frames (the sampler's values for frames 0 .. F-1)
    #[arg(long, default_value_t = 1)]
    frames: u32,
    /// Seed; the default is samplab's
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Output .npy file (float64, C order), written atomically
    #[arg(short, long, required_unless_present = "mask_spectrum")]
    output: Option<PathBuf>,
    /// Measure each dimension's mask (sample 0 of frame 0 over the film): its low-frequency
    /// energy (|f| < 1/16 cycle per pixel, 1/8 of Nyquist) against white noise's, and its
    /// RMS after Gaussian blurs of 1 and 2 pixels against white noise's; printed per dimension
    #[arg(long)]
    mask_spectrum: bool,
    /// With --mask-spectrum: one JSON object per dimension, with the radial power spectrum
    #[arg(long, requires = "mask_spectrum")]
    json: bool,
}

/// `WIDTHxHEIGHT` as two whole numbers.
fn parse_res(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}': expected WIDTHxHEIGHT, e.g. 64x48");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?))
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    if let Some(o) = a.output.as_ref().filter(|o| o.extension().is_none_or(|e| !e.eq_ignore_ascii_case("npy"))) {
        anyhow::bail!("-o {}: pixel values are written as .npy", o.display());
    }
    if a.frames == 0 {
        anyhow::bail!("--frames 0: at least one frame");
    }
    let film = Film { width: a.res.0, height: a.res.1, spp: a.spp, dims: a.dims };
    let p = pixel::prepare(&a.spec, film, Seed(a.seed))?;
    if a.mask_spectrum {
        masks(&p, a.json)?;
    }
    let Some(output) = &a.output else { return Ok(()) };
    let values = p.fill(a.frames)?;
    let shape = [a.frames, a.res.1, a.res.0, a.spp, a.dims].map(|k| k as usize);
    let mut bytes = samplab::io::npy_header(&shape);
    bytes.reserve(8 * values.len());
    values.iter().for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
    crate::emit(Some(output), &bytes).with_context(|| "writing the values")
}

/// Print the measures of every dimension's mask.
fn masks(p: &pixel::Pixels, json: bool) -> anyhow::Result<()> {
    // values uniform in [0, 1): white noise of variance 1/12
    let white = |sigma| samplab::screen::white_blurred_rms((1.0f64 / 12.0).sqrt(), sigma);
    let mut out = String::new();
    if !json {
        out.push_str(&format!(
            "{}: masks of sample 0, frame 0, {}x{} pixels; white noise = 1\n{:>5} {:>14} {:>14} {:>14}\n",
            p.spec(),
            p.film().width,
            p.film().height,
            "dim",
            "low-frequency",
            "blurred 1 px",
            "blurred 2 px"
        ));
    }
    for d in 0..p.film().dims {
        let mask = p.mask(0, 0, d)?;
        let centred =
            samplab::screen::Plane::new(mask.width(), mask.height(), mask.values().iter().map(|v| v - 0.5).collect())?;
        let low = mask.low_frequency(samplab::screen::LOW_FREQUENCY_CUTOFF)?;
        let [b1, b2] = [1.0, 2.0].map(|s| centred.blurred_rms(s) / white(s));
        if json {
            let line = serde_json::json!({
                "spec": p.spec(), "dim": d, "low_frequency": low, "cutoff": samplab::screen::LOW_FREQUENCY_CUTOFF,
                "blurred_rms_over_white": {"1": b1, "2": b2}, "radial": mask.radial(),
            });
            out.push_str(&format!("{line}\n"));
        } else {
            out.push_str(&format!("{d:>5} {low:>14.4} {b1:>14.4} {b2:>14.4}\n"));
        }
    }
    crate::emit(None, out.as_bytes()).with_context(|| "printing the mask measures")
}
