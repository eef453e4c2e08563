//! The report: every page's links and images resolve, the run is deterministic whatever
//! the thread count, and a failed run never replaces or fakes a report.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::LazyLock;
use std::sync::atomic::AtomicBool;

use samplab::Seed;
use samplab::io::Replace;
use samplab_report::{Error, Experiment, Options, Paper, Scale, paper, reproduce};
use sha2::{Digest as _, Sha256};

/// A fresh folder `name` under cargo's scratch folder for integration tests (in the target
/// folder, emptied here by the next run: a run leaves nothing in the system's temporary
/// folder).
fn temp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("report-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every value of `attr="..."` in `html`.
fn attributes<'a>(html: &'a str, attr: &str) -> Vec<&'a str> {
    let key = format!("{attr}=\"");
    html.match_indices(&key).map(|(i, _)| &html[i + key.len()..]).map(|rest| &rest[..rest.find('"').unwrap()]).collect()
}

/// The claims of a run, by paper.
type Claims = Vec<(String, samplab_report::Claim)>;

/// Run `papers` at fast scale with the default seed (`samplab reproduce`'s) on `threads`
/// threads into `out`; the claims, and
/// the run's events as text, each after its experiment's place in the run ("3 start
/// paper/experiment", "3 length n", "3 finish").
fn run(papers: &[Paper], out: &Path, threads: usize) -> (Claims, Vec<String>) {
    let refs: Vec<&Paper> = papers.iter().collect();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let events = std::sync::Mutex::new(Vec::new());
    let watch = |task: usize, e: samplab_report::Event<'_>| {
        let text = match e {
            samplab_report::Event::Started { paper, experiment } => format!("start {paper}/{experiment}"),
            samplab_report::Event::Length(n) => format!("length {n}"),
            samplab_report::Event::Advanced(_) => return,
            samplab_report::Event::Finished(_) => "finish".into(),
            other => format!("{other:?}"),
        };
        events.lock().unwrap().push(format!("{task} {text}"));
    };
    let claims = pool
        .install(|| {
            reproduce(
                &refs,
                &Options { scale: Scale::Fast, seed: Seed::DEFAULT, out: out.to_path_buf(), replace: Replace::IfOurs },
                &AtomicBool::new(false),
                &watch,
            )
        })
        .unwrap();
    (claims, events.into_inner().unwrap())
}

/// The whole fast reproduction on two threads, run once and shared by the tests: the bytes
/// of `samplab reproduce`, which CI's documentation site shows (`scripts/docs --report
/// target/tmp/report-full/report`) rather than running it a third time.
static FULL_RUN: LazyLock<(PathBuf, Claims, Vec<String>)> = LazyLock::new(|| {
    let out = temp("full").join("report");
    let (claims, events) = run(&paper::all(), &out, 2);
    (out, claims, events)
});

/// The watcher hears every experiment once: its start, then its length and progress, then
/// its end, under the experiment's place in the pages' order; the experiments that start
/// first are the longest by `data/timings.json`.
#[test]
fn the_watcher_hears_each_experiment_start_and_finish_longest_first() {
    let events = &FULL_RUN.2;
    let expected: Vec<String> =
        paper::all().iter().flat_map(|p| p.experiments.iter().map(move |e| format!("{}/{}", p.key, e.id))).collect();
    let mut open = vec![false; expected.len()];
    let mut started = Vec::new();
    for e in events {
        let (task, text) = e.split_once(' ').unwrap();
        let task: usize = task.parse().unwrap();
        match text.split(' ').next().unwrap() {
            "start" => {
                assert_eq!(text, format!("start {}", expected[task]), "the place names the experiment");
                assert!(!open[task] && !started.contains(&task), "{e}: started twice");
                open[task] = true;
                started.push(task);
            }
            "finish" => {
                assert!(open[task], "{e}: a finish without a start");
                open[task] = false;
            }
            _ => assert!(open[task], "{e} outside its experiment"),
        }
    }
    assert_eq!(started.len(), expected.len());
    assert!(open.iter().all(|o| !o));
    // two workers take the two longest first (in either order)
    let seconds = samplab_report::expected_seconds(Scale::Fast);
    let mut by_length: Vec<usize> = (0..expected.len()).collect();
    by_length.sort_by(|&a, &b| seconds[&expected[b]].total_cmp(&seconds[&expected[a]]));
    let (mut first, mut want) = (started[..2].to_vec(), by_length[..2].to_vec());
    first.sort_unstable();
    want.sort_unstable();
    assert_eq!(first, want);
}

/// Every experiment has its time in `data/timings.json` at both scales, so that each run
/// is ordered longest first.
#[test]
fn every_experiment_has_an_expected_time() {
    for scale in [Scale::Fast, Scale::Full] {
        let seconds = samplab_report::expected_seconds(scale);
        for p in paper::all() {
            for e in &p.experiments {
                let key = format!("{}/{}", p.key, e.id);
                assert!(seconds.contains_key(&key), "{key} is missing from data/timings.json ({scale:?})");
            }
        }
    }
}

#[test]
fn every_link_and_image_resolves() {
    let (out, claims, _) = &*FULL_RUN;
    assert!(!claims.is_empty());
    let pages: Vec<PathBuf> = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "html"))
        .collect();
    assert!(pages.iter().any(|p| p.ends_with("index.html")));
    for key in paper::keys() {
        assert!(out.join(format!("{key}.html")).exists(), "{key}.html missing");
    }
    let mut checked = 0;
    for page in &pages {
        let html = std::fs::read_to_string(page).unwrap();
        for target in attributes(&html, "href").into_iter().chain(attributes(&html, "src")) {
            assert!(!target.starts_with("http"), "{}: external link {target}", page.display());
            if let Some(anchor) = target.strip_prefix('#') {
                assert!(html.contains(&format!("id=\"{anchor}\"")), "{}: no anchor {target}", page.display());
                checked += 1;
                continue;
            }
            let file = out.join(target.split('#').next().unwrap());
            assert!(file.is_file(), "{}: {target} does not exist", page.display());
            if target.ends_with(".png") {
                assert_eq!(&std::fs::read(&file).unwrap()[1..4], b"PNG", "{target} is not a PNG");
            }
            checked += 1;
        }
    }
    assert!(checked > 20, "only {checked} links");
    let claims_json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("claims.json")).unwrap()).unwrap();
    assert_eq!(claims_json.as_array().unwrap().len(), claims.len());
    for c in claims_json.as_array().unwrap() {
        for key in ["paper", "id", "statement", "published", "ours", "verdict"] {
            assert!(c.get(key).is_some(), "claim without {key}: {c}");
        }
    }
    // no staging folder left behind
    assert_eq!(std::fs::read_dir(out.parent().unwrap()).unwrap().count(), 1);
}

#[test]
fn every_figure_passes_the_lint_and_every_failure_says_why() {
    // the coverage audit runs inside the report (a breach refuses the report), so the run
    // itself is its test on the real report; its failing inputs are coverage.rs's unit tests
    let (out, _, _) = &*FULL_RUN;
    let lint: Vec<String> = serde_json::from_slice(&std::fs::read(out.join("lint.json")).unwrap()).unwrap();
    assert!(lint.is_empty(), "figure lint: {lint:#?}");
    let claims: serde_json::Value = serde_json::from_slice(&std::fs::read(out.join("claims.json")).unwrap()).unwrap();
    for c in claims.as_array().unwrap() {
        if c["verdict"] != "reproduced" {
            assert!(c["explanation"].as_str().is_some_and(|e| !e.is_empty()), "no explanation field: {c}");
        }
    }
    // the index says which verdicts the recorded full-scale run gives otherwise
    let index = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(index.contains("<h2>Verdicts at full scale</h2>"));
    let full = samplab_report::published::full_scale();
    assert!(!full.verdicts.is_empty(), "data/full_scale.json records no run");
    // and a key claim (in a paper's overview, before the summary) that the full run decided
    // otherwise shows both verdicts, never the fast one alone
    let overviews = &index[..index.find("<h2>Summary</h2>").unwrap()];
    let (_, claims, _) = &*FULL_RUN;
    for (paper, c) in claims {
        let link = format!("href=\"{paper}.html#claim-{}\"", c.id);
        let Some(at) = overviews.find(&link) else { continue };
        let line = &overviews[at..at + overviews[at..].find("</li>").unwrap()];
        match full.verdicts.get(&format!("{paper}/{}", c.id)) {
            Some(v) if v != c.verdict_name() => {
                assert!(line.contains(&format!("{v}</span> at full scale")), "{paper}/{}: {line}", c.id);
            }
            _ => assert!(!line.contains("at full scale"), "{paper}/{}: {line}", c.id),
        }
    }
    // renders narrower than the minimum are enlarged on the page
    let page = std::fs::read_to_string(out.join("subr2013.html")).unwrap();
    for w in attributes(&page, "width") {
        assert!(w.parse::<u32>().unwrap() >= samplab_report::lint::MIN_PICTURE_WIDTH, "a render shown {w} px wide");
    }
}

/// Whether this run of the tests includes the slow tier (`--include-ignored` or
/// `--ignored`, as .ci/run's test command passes).
fn slow_tier() -> bool {
    std::env::args().any(|a| a == "--include-ignored" || a == "--ignored")
}

/// The papers on one thread in two groups of about the same expected time
/// (`data/timings.json`), side by side, each on a one-thread pool of its own, beside the
/// two-thread run (run as one, the one-thread reproduction outlasted the two-thread run
/// with a core idle: the test took 179 s at 161% CPU, against 151 s at 195% in two groups,
/// 2026-11-29). Returns each group's report.
fn one_thread_runs(mut papers: Vec<Paper>) -> Vec<PathBuf> {
    let seconds = samplab_report::expected_seconds(Scale::Fast);
    let cost = |p: &Paper| p.experiments.iter().map(|e| seconds[&format!("{}/{}", p.key, e.id)]).sum::<f64>();
    papers.sort_by(|a, b| cost(b).total_cmp(&cost(a)));
    // longest first, each to the group with less so far
    let mut groups: [(f64, Vec<Paper>); 2] = Default::default();
    for p in papers {
        let g = usize::from(groups[1].0 < groups[0].0);
        groups[g].0 += cost(&p);
        groups[g].1.push(p);
    }
    std::thread::scope(|scope| {
        let runs: Vec<_> = groups
            .iter()
            .enumerate()
            .map(|(g, (_, papers))| {
                scope.spawn(move || {
                    let out = temp(&format!("det{g}")).join("one-thread");
                    run(papers, &out, 1);
                    out
                })
            })
            .collect();
        runs.into_iter().map(|r| r.join().unwrap()).collect()
    })
}

/// The paper whose one-thread run is left to the slow tier when it is not recorded.
const SLOW_PAPER: &str = "subr2013";

/// What the determinism check compares: each figure and table file of a report and each
/// claim of its claims.json, by name (`figures/NAME`, `tables/NAME`, `claims/PAPER/ID`),
/// with the SHA-256 of its bytes.
type Outputs = BTreeMap<String, String>;

fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// The outputs of the reports in `dirs` (one run's groups), each name once.
fn outputs(dirs: &[PathBuf]) -> Outputs {
    let mut out = Outputs::new();
    let mut add =
        |name: String, bytes: &[u8]| assert!(out.insert(name.clone(), sha256(bytes)).is_none(), "{name} twice");
    for dir in dirs {
        for sub in ["figures", "tables"] {
            for entry in std::fs::read_dir(dir.join(sub)).unwrap() {
                let path = entry.unwrap().path();
                add(format!("{sub}/{}", path.file_name().unwrap().to_string_lossy()), &std::fs::read(&path).unwrap());
            }
        }
        let claims: Vec<serde_json::Value> =
            serde_json::from_slice(&std::fs::read(dir.join("claims.json")).unwrap()).unwrap();
        for c in claims {
            let name = format!("claims/{}/{}", c["paper"].as_str().unwrap(), c["id"].as_str().unwrap());
            add(name, &serde_json::to_vec(&c).unwrap());
        }
    }
    out
}

/// The recorded one-thread run (written by `scripts/record-one-thread`): the inputs it was
/// made from and its outputs.
const RECORD: &str = "tests/one-thread-run.json";

/// The files that compile into the reproduction or that it includes, from the repository's
/// root: the three crates it runs (their sources, data, scenes and assets), the guide pages
/// the library includes, the manifests and lock file, and this test (which sets the run's
/// options). A folder stands for every file under it.
const SOURCES: &[&str] = &[
    "Cargo.toml",
    "Cargo.lock",
    "docs/guide",
    "crates/samplab/Cargo.toml",
    "crates/samplab/build.rs",
    "crates/samplab/src",
    "crates/samplab/data",
    "crates/samplab-render/Cargo.toml",
    "crates/samplab-render/src",
    "crates/samplab-render/scenes",
    "crates/samplab-report/Cargo.toml",
    "crates/samplab-report/src",
    "crates/samplab-report/data",
    "crates/samplab-report/assets",
    "crates/samplab-report/tests/report.rs",
];

/// The SHA-256 of the files at `paths` under `root` (folders walked), each file's path
/// relative to `root` and its bytes, in the paths' sorted order.
fn sources_digest(root: &Path, paths: &[&str]) -> String {
    fn walk(path: &Path, files: &mut Vec<PathBuf>) {
        if path.is_dir() {
            for entry in std::fs::read_dir(path).unwrap() {
                walk(&entry.unwrap().path(), files);
            }
        } else {
            files.push(path.to_path_buf());
        }
    }
    let mut files = Vec::new();
    for p in paths {
        assert!(root.join(p).exists(), "{p} does not exist");
        walk(&root.join(p), &mut files);
    }
    files.sort();
    let mut all = Vec::new();
    for f in files {
        let name = f.strip_prefix(root).unwrap().to_string_lossy().into_owned();
        let bytes = std::fs::read(&f).unwrap();
        all.extend_from_slice(format!("{name}\n{}\n", bytes.len()).as_bytes());
        all.extend_from_slice(&bytes);
    }
    sha256(&all)
}

/// The first line a command prints, if it runs.
fn first_line(program: &str, arg: &str) -> Option<String> {
    let out = std::process::Command::new(program).arg(arg).output().ok()?;
    let text = String::from_utf8_lossy(&out.stdout);
    out.status.success().then(|| text.lines().next().unwrap_or_default().to_string())
}

/// Everything besides the thread count that the one-thread run's bytes depend on: the
/// sources ([`SOURCES`]), the compiler, the instruction sets the build targets and those
/// the library chooses among at run time (`samplab::simd` and the FFT), the processor's
/// vendor, and the C library (whose mathematical functions differ between versions); None
/// where one of them cannot be read.
fn inputs() -> Option<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    #[cfg(not(target_arch = "x86_64"))]
    let cpu = String::new();
    #[cfg(target_arch = "x86_64")]
    let cpu = {
        use std::arch::is_x86_feature_detected as has;
        let features = [
            ("sse4.1", has!("sse4.1")),
            ("avx", has!("avx")),
            ("avx2", has!("avx2")),
            ("fma", has!("fma")),
            ("avx512f", has!("avx512f")),
            ("avx512bw", has!("avx512bw")),
            ("avx512dq", has!("avx512dq")),
            ("avx512vl", has!("avx512vl")),
            ("gfni", has!("gfni")),
        ];
        features.iter().filter(|f| f.1).map(|f| f.0).collect::<Vec<_>>().join(" ")
    };
    let built_for = [cfg!(target_feature = "avx2"), cfg!(target_feature = "fma"), cfg!(target_feature = "avx512f")];
    let vendor = std::fs::read_to_string("/proc/cpuinfo")
        .ok()?
        .lines()
        .find_map(|l| l.strip_prefix("vendor_id").map(|v| v.trim_start_matches([' ', '\t', ':']).to_string()))?;
    Some(format!(
        "sources {}; {}; {} {}; built for avx2 fma avx512f: {built_for:?}; {} on {vendor}, {}",
        sources_digest(&root, SOURCES),
        first_line("rustc", "-V")?,
        std::env::consts::ARCH,
        std::env::consts::OS,
        cpu,
        first_line("ldd", "--version")?,
    ))
}

/// A line on the test's standard error that the harness does not capture (CI's log shows
/// which way the determinism check went).
fn say(line: &str) {
    use std::io::Write as _;
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// The one-thread side of the determinism check, shared by the tests: the recorded run
/// where it was made from exactly this run's inputs ([`inputs`]), else the papers run on
/// one thread now (all of them in the slow tier; otherwise Subr & Kautz's renders, most of
/// the fast run's time, are left out); and whether it holds every paper. With
/// `SAMPLAB_RECORD_ONE_THREAD` set (`scripts/record-one-thread`), every paper is run on
/// one thread and the record is written.
///
/// A record is as strong as a rerun: the one-thread run is a function of the inputs the
/// record names, so a rerun from the same inputs makes the same bytes; where any input
/// differs (a source edited since the record, another compiler, C library or instruction
/// set), the run is made again.
static ONE_THREAD: LazyLock<(Outputs, bool)> = LazyLock::new(|| {
    let record = Path::new(env!("CARGO_MANIFEST_DIR")).join(RECORD);
    let inputs = inputs();
    if std::env::var_os("SAMPLAB_RECORD_ONE_THREAD").is_some() {
        let outputs = outputs(&one_thread_runs(paper::all()));
        let inputs = inputs.expect("the run's inputs cannot be read: nothing to record");
        let json = serde_json::json!({
            "about": "the fast reproduction's outputs on one thread (SHA-256), and the inputs they \
                      were made from; written by scripts/record-one-thread, read by tests/report.rs",
            "inputs": inputs,
            "outputs": outputs,
        });
        std::fs::write(&record, serde_json::to_string_pretty(&json).unwrap() + "\n").unwrap();
        say(&format!("determinism: the one-thread run recorded in {RECORD}"));
        return (outputs, true);
    }
    if let (Some(inputs), Ok(text)) = (&inputs, std::fs::read_to_string(&record)) {
        let json: serde_json::Value = serde_json::from_str(&text).unwrap();
        if json["inputs"].as_str() == Some(inputs) {
            say(&format!("determinism: compared with the one-thread run recorded from these inputs ({RECORD})"));
            return (serde_json::from_value(json["outputs"].clone()).unwrap(), true);
        }
    }
    say("determinism: no one-thread run recorded from these inputs; running it");
    let mut papers = paper::all();
    if !slow_tier() {
        papers.retain(|p| p.key != SLOW_PAPER);
    }
    (outputs(&one_thread_runs(papers)), slow_tier())
});

/// Every output of the one-thread side equals the two-thread run's (each experiment's seed
/// depends only on its paper and id); returns the two-thread run's digests.
fn assert_same_as_two_threads() -> Outputs {
    let two = outputs(std::slice::from_ref(&FULL_RUN.0));
    for (name, digest) in &ONE_THREAD.0 {
        assert_eq!(two.get(name), Some(digest), "{name}: the one-thread run made other bytes (or none)");
    }
    two
}

#[test]
fn deterministic_whatever_the_thread_count() {
    assert_same_as_two_threads();
    let compared = ONE_THREAD.0.len();
    assert!(compared > 50, "only {compared} outputs compared");
}

#[test]
#[ignore = "slow tier (run by .ci/run): every paper's fast reproduction on one thread"]
fn slow_every_experiment_deterministic_whatever_the_thread_count() {
    assert!(slow_tier(), "the slow tier is chosen by --include-ignored or --ignored");
    let two = assert_same_as_two_threads();
    assert!(ONE_THREAD.1, "the one-thread side left papers out");
    // both ways round: the one-thread run made every file and claim of the two-thread run
    let missing: Vec<&String> = two.keys().filter(|k| !ONE_THREAD.0.contains_key(*k)).collect();
    assert!(missing.is_empty(), "not made on one thread: {missing:?}");
    assert!(two.keys().any(|k| k.contains(SLOW_PAPER)), "no output of {SLOW_PAPER}");
}

/// The sources' digest changes with a file's bytes, its name, and a file added.
#[test]
fn the_sources_digest_sees_every_change() {
    let dir = temp("digest");
    std::fs::create_dir_all(dir.join("src/sub")).unwrap();
    std::fs::write(dir.join("src/sub/a.rs"), "fn a() {}").unwrap();
    std::fs::write(dir.join("b.toml"), "b").unwrap();
    let digest = || sources_digest(&dir, &["src", "b.toml"]);
    let mut seen = vec![digest()];
    std::fs::write(dir.join("src/sub/a.rs"), "fn a() { }").unwrap();
    seen.push(digest());
    std::fs::rename(dir.join("src/sub/a.rs"), dir.join("src/sub/c.rs")).unwrap();
    seen.push(digest());
    std::fs::write(dir.join("src/d.rs"), "").unwrap();
    seen.push(digest());
    let unique: std::collections::BTreeSet<&String> = seen.iter().collect();
    assert_eq!(unique.len(), seen.len(), "{seen:?}");
    assert_eq!(digest(), seen[3], "the same files, the same digest");
}

fn failing(_: &samplab_report::Ctx) -> Result<samplab_report::Output, Error> {
    Err(Error::Invalid("this experiment fails on purpose".into()))
}

#[test]
fn a_failed_run_leaves_the_old_report_alone() {
    let dir = temp("fail");
    let out = dir.join("report");
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("index.html"), "old").unwrap();
    std::fs::write(out.join(samplab::io::MANIFEST), "index.html\n").unwrap();
    let bad = Paper {
        key: "shirley1991",
        title: "failing",
        experiments: vec![Experiment { id: "fails", title: "fails", source: "none", parameters: "none", run: failing }],
    };
    let options = Options { scale: Scale::Fast, seed: Seed(1), out: out.clone(), replace: Replace::IfOurs };
    let err = reproduce(&[&bad], &options, &AtomicBool::new(false), samplab_report::UNWATCHED).unwrap_err();
    assert!(err.to_string().contains("on purpose"));
    // a stopped run: the failing experiment is never started
    let err = reproduce(&[&bad], &options, &AtomicBool::new(true), samplab_report::UNWATCHED).unwrap_err();
    assert!(matches!(err, Error::Samplab(samplab::Error::Interrupted)), "{err}");
    assert_eq!(std::fs::read_to_string(out.join("index.html")).unwrap(), "old");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "a staging folder was left behind");
}
