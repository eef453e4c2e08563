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
         samplab pixels sobol.padded.xor --res 32x32 --spp 4 --dims 4 --frames 16 -o p.npy\n  \
         samplab pixels sobol.owen --res 16x16 --spp 64 --dims 6 -o s.npy   # the point set in every pixel\n\n\
         Pixel samplers: {}.\n`samplab list pixels` lists each with its sample counts, mapping and references.\n\n\
         Any point-set sequence (sobol.owen, halton.owen, net.lms, lattice.shift, kronecker, SPEC+shift) is a pixel \
         sampler too: sample i of pixel p in frame f is point i of `samplab generate SPEC --seed S`, S the pixel's \
         seed (samplab.pixel_seed in Python), so a randomization word names one scramble in both commands. After a \
         pixel sampler's own name, .none, .xor and .owen set its randomize (pbrt's none, xor and fastowen: \
         fastowen is the point sets' Owen hash); randomize=WORD stays.",
        pixel::PIXEL_SAMPLERS.names()
    )
}

/// Draw every value of a film from a pixel sampler.
#[derive(clap::Args)]
#[command(after_help = after_help())]
pub struct Args {
    /// Pixel sampler spec, e.g. zsobol, zsobol.xor, sobol, pmj02.bn:mask=128, openqmc.sobolbn, or a
    /// point-set sequence per pixel: sobol.owen, halton.owen, lattice.shift
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
    /// Measure each dimension's mask (sample 0 over the film): frame 0's low-frequency
    /// energy (|f| < 1/16 cycle per pixel, 1/8 of Nyquist) and RMS after Gaussian blurs of 1
    /// and 2 pixels, against white noise's; the flicker over --frames and, with 16 frames or
    /// more, the x-t slice's low-frequency energy; printed per dimension
    #[arg(long)]
    mask_spectrum: bool,
    /// With --mask-spectrum: one JSON object per dimension, with the radial power spectrum
    #[arg(long, requires = "mask_spectrum")]
    json: bool,
}

/// `WIDTHxHEIGHT` as two whole numbers.
pub(crate) fn parse_res(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("'{text}': expected WIDTHxHEIGHT, e.g. 64x48");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    Ok((w.trim().parse().map_err(|_| bad())?, h.trim().parse().map_err(|_| bad())?))
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    if let Some(o) = a.output.as_ref().filter(|o| o.extension().is_none_or(|e| !e.eq_ignore_ascii_case("npy"))) {
        anyhow::bail!("-o {}: pixel values are written as .npy", o.display());
    }
    if let Some(o) = &a.output {
        samplab::io::check_file(o)?;
    }
    if a.frames == 0 {
        anyhow::bail!("--frames 0: at least one frame");
    }
    let film = Film { width: a.res.0, height: a.res.1, spp: a.spp, dims: a.dims };
    let stop = samplab::progress::Progress::until(&crate::bar::STOP);
    let p = pixel::prepare_with(&a.spec, film, Seed(a.seed), &stop)?;
    if a.mask_spectrum {
        masks(&p, a.frames, a.json)?;
    }
    let Some(output) = &a.output else { return Ok(()) };
    let values = p.fill_with(a.frames, &stop)?;
    let shape = [a.frames, a.res.1, a.res.0, a.spp, a.dims].map(|k| k as usize);
    let mut bytes = samplab::io::npy_header(&shape);
    bytes.reserve(8 * values.len());
    values.iter().for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
    crate::emit(Some(output), &bytes).with_context(|| "writing the values")
}

/// Print the measures of every dimension's masks.
fn masks(p: &pixel::Pixels, frames: u32, json: bool) -> anyhow::Result<()> {
    let mut out = String::new();
    if !json {
        let f = p.film();
        out.push_str(&format!(
            "{}: masks of sample 0, {}x{} pixels, {frames} frame(s); white noise = 1 (flicker: independent \
             frames 1.41, static 0; x-t: row 0 over 16 frames or more; pair: steps in dimensions d, \
             d+1)\n{:>5} {:>14} {:>14} {:>14} {:>9} {:>9} {:>9}\n",
            p.spec(),
            f.width,
            f.height,
            "dim",
            "low-frequency",
            "blurred 1 px",
            "blurred 2 px",
            "flicker",
            "x-t",
            "pair"
        ));
    }
    for d in 0..p.film().dims {
        let m = samplab::screen::mask_measures(p, d, frames)?;
        if json {
            let mut line = serde_json::to_value(&m)?;
            line["spec"] = p.spec().into();
            out.push_str(&format!("{line}\n"));
        } else {
            let or_dash = |v: Option<f64>| v.map_or("-".to_string(), |f| format!("{f:.4}"));
            let [flicker, xt, pair] = [m.flicker, m.xt_low_frequency, m.pair_low_frequency].map(or_dash);
            let [(_, b1), (_, b2)] = m.blurred_over_white;
            out.push_str(&format!(
                "{d:>5} {:>14.4} {b1:>14.4} {b2:>14.4} {flicker:>9} {xt:>9} {pair:>9}\n",
                m.low_frequency
            ));
        }
    }
    crate::emit(None, out.as_bytes()).with_context(|| "printing the mask measures")
}
