//! `samplab mask`: a blue-noise mask by void-and-cluster, as NumPy or PNG.

use std::path::PathBuf;

use anyhow::Context as _;
use samplab::Seed;
use samplab::pixel::mask::Mask;

/// Make a tileable blue-noise mask.
#[derive(clap::Args)]
#[command(after_help = "Channel c is seeded by a hash of the seed and c, so the channels are independent masks. \
                  A .npy holds float64 values (rank + 1/2) / size^2 of shape (size, size, channels); a .png \
                  shows 1 channel in grey, 2 in red and green, 3 as RGB.\n\nExamples:\n  \
                  samplab mask --size 64 -o mask.png\n  samplab mask --size 128 --channels 2 --seed 7 -o mask.npy")]
pub struct Args {
    /// Side in pixels (4 to 256; the cost grows as size^3: 0.01 s at 64, 0.08 s at 128, 0.5 s at 256)
    #[arg(long, default_value_t = 64)]
    size: usize,
    /// Values per pixel (1 to 4)
    #[arg(long, default_value_t = 1)]
    channels: usize,
    /// Seed; the default is samplab's
    #[arg(long, default_value_t = Seed::DEFAULT.0)]
    seed: u64,
    /// Output .npy or .png, written atomically
    #[arg(short, long)]
    output: PathBuf,
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let ext = a.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("npy" | "png")) {
        anyhow::bail!("-o {}: a mask is written as .npy or .png", a.output.display());
    }
    samplab::io::check_file(&a.output)?;
    if ext.as_deref() == Some("png") && a.channels > 3 {
        anyhow::bail!("--channels {}: a .png shows at most 3 channels; write .npy", a.channels);
    }
    let mask = Mask::void_and_cluster(a.size, a.channels, Seed(a.seed))?;
    let bytes = if ext.as_deref() == Some("npy") {
        let mut bytes = samplab::io::npy_header(&[a.size, a.size, a.channels]);
        mask.values().iter().for_each(|v| bytes.extend_from_slice(&v.to_le_bytes()));
        bytes
    } else {
        let level = |v: f64| (v * 256.0) as u8;
        let rgb: Vec<u8> = mask
            .values()
            .chunks_exact(a.channels)
            .flat_map(|p| match *p {
                [g] => [level(g); 3],
                [r, g] => [level(r), level(g), 0],
                [r, g, b] => [level(r), level(g), level(b)],
                _ => unreachable!("at most 3 channels in a png (checked above)"),
            })
            .collect();
        let side = a.size as u32;
        let img = samplab_render::image::Srgb8::from_raw(side, side, rgb).context("a mask image of size^2 pixels")?;
        img.png()?
    };
    crate::emit(Some(&a.output), &bytes).with_context(|| "writing the mask")
}
