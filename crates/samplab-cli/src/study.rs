//! `samplab study`: a study's chunks as separate jobs, for a job array (a Slurm array needs
//! nothing else): `plan` checks a study and cuts it into chunks, `run` computes one chunk
//! into a folder, `merge` merges the folder's chunks into what `integrate`, `spectrum`,
//! `discrepancy` or `render` prints. The library calls are Python's `Study`'s (the plan,
//! the chunk, the merge, the checked chunk files), so the bytes are the same.

use std::path::{Path, PathBuf};

use anyhow::{Context as _, bail};
use samplab::progress::Progress;
use samplab::study::{Checkpoint, fingerprint};
use samplab_render::study::{Study, read};
use serde_json::{Value, json};

/// A study's chunks as separate jobs: plan, run each chunk (anywhere), merge.
#[derive(clap::Args)]
#[command(after_help = "A study file is JSON: {\"kind\": \"integrate\" | \"spectrum\" | \"discrepancy\" | \
                  \"render\", and the arguments of Python's Study constructor of that kind, with its \
                  *_per_chunk, a render study's settings (\"n\", \"res\", ...) among them as the \
                  constructor's keywords; a key no kind declares is refused}, e.g. {\"kind\": \"integrate\", \"samplers\": [\"random\", \"jitter\"], \
                  \"integrand\": \"quad\", \"n\": [16, 64], \"sets\": 60, \"units_per_chunk\": 20} (the \
                  Python guide lists every kind's arguments). The plan names the study's fingerprint; \
                  each chunk file is checked against it when read.\n\n\
                  Examples:\n  \
                  samplab study plan study.json -o plan.json\n  \
                  samplab study run plan.json --chunk 0 --dir chunks   # one job of the array each\n  \
                  samplab study run plan.json --chunk 1 --dir chunks\n  \
                  samplab study merge plan.json --dir chunks --csv rows.csv")]
pub struct Args {
    #[command(subcommand)]
    action: Action,
}

#[derive(clap::Subcommand)]
enum Action {
    /// Check a study and cut it into chunks: write the plan (and print how many chunks)
    Plan {
        /// The study (JSON)
        study: PathBuf,
        /// The plan file to write
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Compute one chunk of a plan into a folder (chunk 0 first where it feeds the others)
    Run {
        /// The plan
        plan: PathBuf,
        /// Which chunk (0-based)
        #[arg(long)]
        chunk: usize,
        /// The folder of chunk files
        #[arg(long)]
        dir: PathBuf,
    },
    /// Merge every chunk of a folder: the study's JSON on stdout (or -o), its CSV with --csv
    Merge {
        /// The plan
        plan: PathBuf,
        /// The folder of chunk files
        #[arg(long)]
        dir: PathBuf,
        /// Write the JSON here instead of stdout
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Also write the CSV (integration rows, per-metric summaries, radial spectra, errors)
        #[arg(long)]
        csv: Option<PathBuf>,
    },
}

/// The plan file's format.
const FORMAT: u64 = 1;

/// A plan read back: the study, its chunks, its fingerprint.
struct Plan {
    study: Study,
    chunks: Vec<Vec<u64>>,
    fingerprint: String,
}

impl Plan {
    fn read(path: &Path) -> anyhow::Result<Plan> {
        let text = samplab::io::read_small_text(&path.display().to_string(), samplab::io::SPEC_FILE_MAX)?;
        let bad = || format!("{}: not a plan that `samplab study plan` wrote", path.display());
        let value: Value = serde_json::from_str(&text).with_context(bad)?;
        if value["format"] != json!(FORMAT) {
            bail!("{}: plan format {} (this samplab reads {FORMAT})", path.display(), value["format"]);
        }
        let study = Study::from_json(&value["study"].to_string())?;
        let chunks: Vec<Vec<u64>> = serde_json::from_value(value["chunks"].clone()).with_context(bad)?;
        let fingerprint = value["fingerprint"].as_str().with_context(bad)?.to_string();
        if fingerprint != self::fingerprint(&json!([value["study"], value["chunks"]]).to_string()) {
            bail!(
                "{}: the plan was changed after `samplab study plan` wrote it (its fingerprint differs)",
                path.display()
            );
        }
        Ok(Plan { study, chunks, fingerprint })
    }

    fn checkpoint(&self, dir: &Path) -> anyhow::Result<Checkpoint> {
        let manifest = json!({"fingerprint": self.fingerprint, "chunks": self.chunks.len()}).to_string();
        Ok(Checkpoint::open(dir, &self.fingerprint, &manifest)?)
    }
}

pub fn run(a: &Args) -> anyhow::Result<()> {
    let stop = Progress::until(&crate::bar::STOP);
    match &a.action {
        Action::Plan { study, output } => {
            samplab::io::check_file(output)?;
            let text = samplab::io::read_small_text(&study.display().to_string(), samplab::io::SPEC_FILE_MAX)?;
            let (study, chunks) = read(&text).and_then(|(s, per_chunk)| s.plan(per_chunk))?;
            let described: Value = serde_json::from_str(&study.to_json())?;
            let fingerprint = fingerprint(&json!([described, chunks]).to_string());
            let plan = json!({"format": FORMAT, "fingerprint": fingerprint, "study": described, "chunks": chunks});
            samplab::io::write_atomic(output, format!("{plan:#}\n").as_bytes())?;
            crate::emit(None, format!("{} chunks, fingerprint {fingerprint}\n", chunks.len()).as_bytes())
        }
        Action::Run { plan, chunk, dir } => {
            let plan = Plan::read(plan)?;
            let Some(range) = plan.chunks.get(*chunk) else {
                bail!("--chunk {chunk}: the plan has {} chunks (0 to {})", plan.chunks.len(), plan.chunks.len() - 1);
            };
            let checkpoint = plan.checkpoint(dir)?;
            let first = if plan.study.first_feeds_the_rest() && *chunk != 0 {
                let kept = checkpoint.load(1)?;
                let Some((_, first)) = kept.into_iter().next() else {
                    bail!("--chunk {chunk}: chunk 0's result feeds the others; run chunk 0 first");
                };
                Some(first)
            } else {
                None
            };
            let data = plan.study.compute(range, first.as_deref(), None, &stop)?;
            Ok(checkpoint.save(*chunk, &data)?)
        }
        Action::Merge { plan, dir, output, csv } => {
            let plan = Plan::read(plan)?;
            for path in output.iter().chain(csv) {
                samplab::io::check_file(path)?;
            }
            let kept = plan.checkpoint(dir)?.load(plan.chunks.len())?;
            if kept.len() < plan.chunks.len() {
                let missing = (0..plan.chunks.len()).find(|i| kept.iter().all(|(k, _)| k != i)).unwrap_or(0);
                bail!(
                    "{}: {} of {} chunks are missing, the first {missing}",
                    dir.display(),
                    plan.chunks.len() - kept.len(),
                    plan.chunks.len()
                );
            }
            let parts: Vec<Vec<u8>> = kept.into_iter().map(|(_, data)| data).collect();
            let merged = plan.study.merge(&parts)?;
            if let Some(path) = csv {
                samplab::io::write_atomic(path, merged.csv.as_bytes())?;
            }
            crate::emit(output.as_deref(), merged.json.as_bytes())
        }
    }
}
