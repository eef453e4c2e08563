//! `samplab conform`: the checks of [`samplab::conform`] on samples someone's own
//! implementation wrote, one line each; exit 1 when one fails.

use std::path::PathBuf;

use anyhow::{Context as _, bail};

use samplab::Seed;
use samplab::conform::{Check, Claim, Layout, Precision, conform};
use samplab::io::{self, Format};

/// Check samples dumped from your own sampler against samplab's entry of the same name.
#[derive(clap::Args)]
#[command(after_help = "The file holds sets of points (text, CSV, JSON or .npy of shape (n, d) or (sets, n, d)): \
                  realizations of a point set, set k made with sub-seed k of --seed as `samplab generate \
                  --sets` makes them; or with --res, the pixels of a film in row-major order, each set a \
                  pixel's samples (n = spp) at --frame; or an .npy of `samplab pixels`' shape (frames, \
                  height, width, spp, dims), its film. Checks: range (every value in [0, 1)), reference \
                  (with --seed: every value equals samplab's, bit for bit or within --ulps; in single \
                  precision for a float32 .npy or with --single, in 32-bit fixed point where every value \
                  is a multiple of 2^-32), uniform (each dimension, Kolmogorov-Smirnov, p >= 0.001 / d), \
                  independent (consecutive dimensions' correlation, |r| sqrt N <= 5), unbiased (30 sets or \
                  more: the means of x_j and x_j x_(j+1) within 5 standard errors), nets (each pair (j, j \
                  + 1) of every prefix of b^m points no worse a net than samplab's matrices make, or \
                  without matrices a (0, m, 2)-net where 64 of samplab's own sets all are) and distinct (sets or pixels that differ where samplab's differ); a statistical \
                  check runs where samplab's own sets pass it. One line per check; exit 1 when one \
                  fails.\n\nExamples:\n  \
                  samplab generate net.owen -n 256 -d 4 --sets 4 --seed 7 -o mine.txt\n  \
                  samplab conform mine.txt --as net.owen --seed 7\n  \
                  samplab conform mine.txt --as net.owen --json   # without the seed: the properties\n  \
                  samplab pixels zsobol --res 8x8 --spp 16 --dims 4 --seed 3 -o film.npy\n  \
                  samplab conform film.npy --as zsobol --seed 3")]
pub struct Args {
    /// The samples: a point-set file (text, CSV, JSON, .npy)
    file: PathBuf,
    /// What they should be: a samplab sampler spec (point sets, or with --res a pixel family)
    #[arg(long = "as", value_name = "SPEC")]
    spec: String,
    /// The seed they were made with: adds the bit-for-bit reference check
    #[arg(long)]
    seed: Option<u64>,
    /// The sets are the pixels of a WIDTHxHEIGHT film, row by row
    #[arg(long, value_parser = crate::pixels::parse_res)]
    res: Option<(u32, u32)>,
    /// The frame the pixels were drawn at (with --res)
    #[arg(long, default_value_t = 0, requires = "res")]
    frame: u32,
    /// How many units in the last place a value may differ from samplab's (reference)
    #[arg(long, default_value_t = 0)]
    ulps: u64,
    /// Compare in single precision (a text file of floats; a float32 .npy is found alone)
    #[arg(long)]
    single: bool,
    /// The file's format, when its extension does not say
    #[arg(long)]
    format: Option<String>,
    /// Print JSON instead of lines
    #[arg(long)]
    json: bool,
}

/// A check failed: the lines say which; the exit code is 1.
#[derive(Debug)]
pub(crate) struct Failed;

impl std::fmt::Display for Failed {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("a conformance check failed")
    }
}

impl std::error::Error for Failed {}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let format = a.format.as_deref().map(Format::from_name).transpose()?;
    // an .npy of `samplab pixels`' shape (frames, height, width, spp, dims) names its film
    let film =
        if format.unwrap_or_else(|| Format::from_path(&a.file)) == Format::Npy { film_of(&a.file)? } else { None };
    // every finite value: a value outside the unit cube is the range check's to report
    let sets = io::read_within(&a.file, format, &(f64::MIN..=f64::MAX))?;
    let layout = match (film, a.res) {
        (Some(_), Some(_)) => bail!("--res: the file's shape (frames, height, width, spp, dims) gives its film"),
        (Some((frames, w, h)), None) => Layout::frames(w, h, 0..frames),
        (None, Some((w, h))) => Layout::film(w, h, a.frame),
        (None, None) => Layout::Sets,
    };
    let precision = if a.single { Precision::Single } else { Precision::Found };
    let claim = Claim { spec: &a.spec, layout, seed: a.seed.map(Seed), precision, ulps: a.ulps };
    let checks = conform(&sets, &claim, &samplab::progress::Progress::until(&crate::bar::STOP))?;
    let out = if a.json { format!("{:#}\n", serde_json::json!(checks)) } else { lines(&checks) };
    crate::emit(None, out.as_bytes())?;
    if checks.iter().all(|c| c.passed) { Ok(()) } else { Err(Failed.into()) }
}

/// The film (frames, width, height) of an .npy of `samplab pixels`' shape, read from its
/// header; none for another shape.
fn film_of(path: &std::path::Path) -> anyhow::Result<Option<(u32, u32, u32)>> {
    use std::io::Read as _;
    let mut head = Vec::new();
    let name = path.display().to_string();
    std::fs::File::open(path).and_then(|f| f.take(1 << 16).read_to_end(&mut head)).with_context(|| name.clone())?;
    let shape = io::npy_shape(&head, &name)?;
    let word = |v: usize| u32::try_from(v).with_context(|| format!("{name}: shape {shape:?} too large"));
    Ok(match shape[..] {
        [frames, h, w, _, _] => Some((word(frames)?, word(w)?, word(h)?)),
        _ => None,
    })
}

fn lines(checks: &[Check]) -> String {
    checks
        .iter()
        .map(|c| format!("{}  {:<11} {}\n", if c.passed { "PASS" } else { "FAIL" }, c.name, c.detail))
        .collect()
}
