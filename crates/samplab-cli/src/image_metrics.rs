//! `samplab image-metrics`: how a render's error is spread over the screen.

use std::path::PathBuf;

use anyhow::Context as _;
use samplab::screen::{self, Plane};
use samplab_render::image::Image;

/// The error of one or more renders (.exr) against a reference, on luminance: RMSE, RMSE
/// after Gaussian blurs (what a denoiser or the eye sees) beside white noise's of the same
/// RMSE, the low-frequency share of the error's power, its radial spectrum (--json), and,
/// given several images, the flicker of the error from frame to frame (frames of one
/// sequence) or, with --spp, its convergence (one render per sample count).
#[derive(clap::Args)]
#[command(after_help = "The error image is the luminance (Rec. 709) of IMAGE minus the reference's. Its measures \
                        treat it as periodic: the periodogram, and blurs that wrap around (a band of 3 sigma at the \
                        borders). White noise of the same standard deviation gives low-frequency energy 1 and the \
                        blurred RMSE printed beside each measured one. Flicker: RMS of the frame-to-frame change of \
                        the error over its RMS (independent frames: 1.41, a static pattern: 0).\n\nExamples:\n  \
                        samplab image-metrics zsobol.exr --reference ref.exr\n  \
                        samplab image-metrics f0.exr f1.exr f2.exr f3.exr --reference ref.exr --json\n  \
                        samplab image-metrics s4.exr s16.exr s64.exr --spp 4,16,64 --reference ref.exr")]
pub struct Args {
    /// Rendered images (.exr); several are frames of one sequence
    #[arg(required = true)]
    images: Vec<PathBuf>,
    /// Reference image (.exr)
    #[arg(long)]
    reference: PathBuf,
    /// Blur widths in pixels (Gaussian standard deviations; 0 is no blur)
    #[arg(long, value_delimiter = ',', default_values_t = [0.0, 1.0, 2.0, 4.0])]
    sigma: Vec<f64>,
    /// The images' sample counts, one each, increasing: the images are a convergence series,
    /// and the slopes of ln(error) against ln(spp) are printed (RMSE, blurred RMSE, per-pixel
    /// quartiles) instead of the flicker
    #[arg(long, value_delimiter = ',')]
    spp: Vec<f64>,
    /// One JSON object per image (and one for the flicker or the convergence), with the
    /// radial error spectrum
    #[arg(long)]
    json: bool,
}

fn read(path: &std::path::Path) -> anyhow::Result<Image> {
    Image::read_exr(path).with_context(|| format!("reading {}", path.display()))
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let reference = read(&a.reference)?;
    let truth = reference.luminance();
    let mut errors = Vec::with_capacity(a.images.len());
    let mut out = String::new();
    for path in &a.images {
        let image = read(path)?;
        if (image.width, image.height) != (reference.width, reference.height) {
            anyhow::bail!(
                "{}: {}x{} pixels, the reference {}x{}",
                path.display(),
                image.width,
                image.height,
                reference.width,
                reference.height
            );
        }
        let values = image.luminance().iter().zip(&truth).map(|(v, t)| v - t).collect();
        let error = Plane::new(image.width, image.height, values).with_context(|| path.display().to_string())?;
        let m = error.metrics(&a.sigma)?;
        if a.json {
            let mut line = serde_json::to_value(&m)?;
            line["image"] = path.display().to_string().into();
            out.push_str(&format!("{line}\n"));
        } else {
            out.push_str(&format!("{}: RMSE {:.6}", path.display(), m.rmse));
            for b in &m.blurred {
                out.push_str(&format!(", blurred {} px {:.6} (white {:.6})", b.sigma, b.rmse, b.white));
            }
            match m.low_frequency {
                Some(l) => out.push_str(&format!(", low-frequency energy {l:.4} of white noise's\n")),
                None => out.push_str(", low-frequency energy undefined (a constant error)\n"),
            }
        }
        errors.push(error);
    }
    if !a.spp.is_empty() {
        let c = screen::convergence(&errors, &a.spp, &a.sigma)?;
        if a.json {
            out.push_str(&format!("{}\n", serde_json::json!({ "convergence": c })));
        } else {
            let (slope, (lo, hi)) = c.rmse;
            out.push_str(&format!("convergence over spp {:?}: RMSE slope {slope:.3} [{lo:.3}, {hi:.3}]", a.spp));
            for (s, b) in &c.blurred {
                out.push_str(&format!(", blurred {s} px {b:.3}"));
            }
            let [q1, q2, q3] = c.per_pixel;
            out.push_str(&format!(
                "; per pixel (|error|) quartiles {q1:.3} {q2:.3} {q3:.3} over {} pixels\n",
                c.pixels
            ));
        }
    } else if errors.len() > 1 {
        let f = screen::flicker(&errors)?;
        if a.json {
            out.push_str(&format!("{}\n", serde_json::json!({"frames": errors.len(), "flicker": f})));
        } else {
            out.push_str(&format!("flicker over {} frames: {f:.4} (independent 1.4142, static 0)\n", errors.len()));
        }
    }
    crate::emit(None, out.as_bytes()).with_context(|| "printing the image metrics")
}
