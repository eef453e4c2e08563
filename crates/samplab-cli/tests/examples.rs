//! Every example a reader is shown runs as shown: each `samplab` line of the shell blocks of
//! the README and the guide (docs/), and of each command's `--help` "Examples:", pasted into
//! a shell in the order given, one folder per page or command, succeeds. The files a reader
//! would bring (a point file, a Mitsuba scene, renders to compare) are made first, by
//! samplab, where a line reads one that no earlier line wrote. A `--help` example must also
//! fit the help's width: one that clap wraps pastes as two commands. (The pages' Python
//! examples are run by crates/samplab-py/tests/test_examples.py.)

mod common;
use common::Temp;

use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A shell line, its backslash continuations joined.
fn join_continued(lines: &mut dyn Iterator<Item = String>) -> Vec<String> {
    let mut out = Vec::new();
    let mut current = String::new();
    for line in lines {
        let line = line.trim();
        match line.strip_suffix('\\') {
            Some(head) => {
                current.push_str(head.trim_end());
                current.push(' ');
            }
            None => {
                current.push_str(line);
                out.push(std::mem::take(&mut current));
            }
        }
    }
    out
}

/// The `samplab` lines of a Markdown page's `sh` and `bash` blocks.
fn page_examples(text: &str) -> Vec<String> {
    let mut blocks = Vec::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        if matches!(line.trim(), "```sh" | "```bash") {
            let body: Vec<String> = lines.by_ref().take_while(|l| l.trim() != "```").map(String::from).collect();
            blocks.extend(join_continued(&mut body.into_iter()));
        }
    }
    blocks.into_iter().filter(|l| l.starts_with("samplab ")).collect()
}

/// The lines of a `--help`'s "Examples:" section (up to its first blank line); a line that
/// is neither a command nor the continuation of one ending in a backslash is an error.
fn help_examples(help: &str) -> Result<Vec<String>, String> {
    let Some((_, after)) = help.split_once("Examples:\n") else { return Ok(Vec::new()) };
    let section: Vec<&str> = after.lines().take_while(|l| !l.trim().is_empty()).collect();
    for (k, line) in section.iter().enumerate() {
        let continued = k > 0 && section[k - 1].ends_with('\\');
        if !continued && !line.trim_start().starts_with("samplab ") {
            return Err(format!("example line {k} is not a command (wrapped?): {line:?}"));
        }
    }
    Ok(join_continued(&mut section.into_iter().map(String::from)))
}

/// The words of a line up to a comment, single quotes removed (the examples quote with
/// single quotes only).
fn words(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let (mut word, mut quoted, mut any) = (String::new(), false, false);
    for c in line.chars() {
        match c {
            '\'' => (quoted, any) = (!quoted, true),
            '#' if !quoted && !any => break,
            c if c.is_whitespace() && !quoted => {
                if any {
                    out.push(std::mem::take(&mut word));
                }
                any = false;
            }
            c => {
                word.push(c);
                any = true;
            }
        }
    }
    if any {
        out.push(word);
    }
    out
}

/// The files a line reads: its words (and what follows `image:` or `file:path=`, up to a
/// `+` stage) that end in a file extension samplab reads, but for the ones it writes (after
/// `-o`, `--output`, `--out`, `--error-image`, and a render's `--reference`, which it
/// renders when missing), also where the line reads them after writing them (`generate -o
/// j.txt && plot j.txt`).
fn inputs(line: &str) -> Vec<String> {
    let words = words(line);
    let render = words.get(1).is_some_and(|w| w == "render");
    let written: Vec<&String> = (1..words.len())
        .filter(|&k| {
            matches!(words[k - 1].as_str(), "-o" | "--output" | "--out" | "--error-image")
                || (render && words[k - 1] == "--reference")
        })
        .map(|k| &words[k])
        .collect();
    let mut out = Vec::new();
    for w in words.iter().filter(|w| !written.contains(w)) {
        let name = w.strip_prefix("image:").or_else(|| w.strip_prefix("file:path=")).unwrap_or(w);
        let name = name.split('+').next().unwrap_or(name);
        if [".exr", ".xml", ".txt", ".npy", ".json"].iter().any(|e| name.ends_with(e)) {
            out.push(name.to_string());
        }
    }
    out
}

/// How a reader's own file is made, in the folder `dir`.
fn make_input(name: &str, dir: &Path, cache: &Path) -> Result<(), String> {
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_samplab"))
            .args(args)
            .current_dir(dir)
            .env("SAMPLAB_CACHE", cache)
            .output()
            .unwrap();
        out.status
            .success()
            .then_some(())
            .ok_or_else(|| format!("making {name}: samplab {args:?}: {}", String::from_utf8_lossy(&out.stderr).trim()))
    };
    match name {
        // a Mitsuba 3 scene: the one samplab ships
        "scene.xml" => std::fs::copy(root().join("crates/samplab-render/scenes/glossy-box.xml"), dir.join(name))
            .map(|_| ())
            .map_err(|e| format!("copying the scene: {e}")),
        // one set of points, several sets, a set to read back 256 points of
        "points.txt" => run(&["generate", "jitter", "-n", "64", "-o", name]),
        "sets.txt" => run(&["generate", "jitter", "-n", "64", "--sets", "4", "-o", name]),
        "best.npy" => run(&["generate", "sobol.owen", "-n", "256", "-o", name]),
        // a study of two chunks (`samplab study`)
        "study.json" => std::fs::write(
            dir.join(name),
            r#"{"kind": "integrate", "samplers": ["random", "jitter"], "integrand": "quad", "n": [16, 64], "sets": 60, "units_per_chunk": 20}"#,
        )
        .map_err(|e| format!("writing the study: {e}")),
        // renders of one scene at one size, each of its own seed: frames, `sN.exr` at N spp,
        // a reference at 1024, an image to integrate
        n if n.ends_with(".exr") => {
            let spp = match n.strip_prefix('s').and_then(|s| s.strip_suffix(".exr")).map(str::parse::<u32>) {
                Some(Ok(spp)) => spp,
                _ if n.starts_with("ref") => 1024,
                _ => 4,
            };
            let seed = n.bytes().map(u32::from).sum::<u32>();
            run(&[
                "render",
                "spheres",
                "--res",
                "48x48",
                "--spp",
                &spp.to_string(),
                "--seed",
                &seed.to_string(),
                "-o",
                n,
            ])
        }
        _ => Err(format!("no recipe for the reader's file {name}")),
    }
}

/// The examples' cache of measured spectra (`SAMPLAB_CACHE`), shared by this run's tests
/// (the pages and the commands' help repeat lines) and emptied when the run starts, in
/// cargo's scratch folder for integration tests: the user's cache is neither read, so the
/// run's cost does not depend on what earlier runs left there, nor filled (it had grown to
/// 2.2 GB, one set of spectra per source digest).
static CACHE: std::sync::LazyLock<PathBuf> = std::sync::LazyLock::new(|| {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("examples-cache");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
});

/// Run each source's examples (a page's or a command's: its name and lines) in order in a
/// fresh folder of its own, the sources side by side, as many at a time as there are
/// cores (most lines are short single-threaded commands); the failures, in the sources'
/// order, with [`CACHE`] for their measured spectra.
fn run_all(sources: &[(String, Vec<String>)]) -> Vec<String> {
    use std::sync::Mutex;
    let cache: &Path = &CACHE;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let next = AtomicUsize::new(0);
    let results: Vec<Mutex<Vec<String>>> = sources.iter().map(|_| Mutex::default()).collect();
    let workers = std::thread::available_parallelism().map_or(2, |n| n.get());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some((source, lines)) = sources.get(k) else { break };
                    *results[k].lock().unwrap() = run_examples(source, lines, cache);
                }
            });
        }
    });
    results.into_iter().flat_map(|r| r.into_inner().unwrap()).collect()
}

/// Run a page's or a command's examples in order in a fresh folder; the failures.
fn run_examples(source: &str, lines: &[String], cache: &Path) -> Vec<String> {
    let dir = Temp::new("examples", &source.replace(['/', ' ', '.'], "-"));
    let bin = Path::new(env!("CARGO_BIN_EXE_samplab")).parent().unwrap().to_path_buf();
    let path =
        std::env::join_paths(std::iter::once(bin).chain(std::env::split_paths(&std::env::var_os("PATH").unwrap())))
            .unwrap();
    let mut failures = Vec::new();
    for line in lines {
        // the whole reproduction and atlas: the documentation site's build runs both
        // (scripts/docs), tests/atlas.rs the atlas on a few samplers
        let w = words(line);
        let command = w.get(1).map_or("", String::as_str);
        if command == "reproduce" || (command == "atlas" && !w.iter().any(|x| x == "--only")) {
            continue;
        }
        if let Some(e) =
            inputs(line).iter().filter(|f| !dir.join(f).exists()).find_map(|f| make_input(f, &dir, cache).err())
        {
            failures.push(format!("{source}: {line}\n    {e}"));
            continue;
        }
        let out = Command::new("bash")
            .args(["-c", line])
            .current_dir(&dir)
            .env("PATH", &path)
            .env("SAMPLAB_CACHE", cache)
            .output()
            .unwrap();
        if !out.status.success() {
            failures.push(format!("{source}: {line}\n    {}", String::from_utf8_lossy(&out.stderr).trim()));
        }
    }
    failures
}

#[test]
fn the_words_and_inputs_of_a_line() {
    let line = "samplab cubature --integrand 'expr:exp(-x0 * x0)' --sampler file:path=best.npy+shift -o a.npy # x.txt";
    assert_eq!(
        words(line),
        [
            "samplab",
            "cubature",
            "--integrand",
            "expr:exp(-x0 * x0)",
            "--sampler",
            "file:path=best.npy+shift",
            "-o",
            "a.npy"
        ]
    );
    assert_eq!(inputs(line), ["best.npy"]);
    assert_eq!(inputs("samplab render spheres -o a.exr --reference ref.exr"), Vec::<String>::new());
    assert_eq!(inputs("samplab image-metrics a.exr --reference ref.exr"), ["a.exr", "ref.exr"]);
    assert_eq!(inputs("samplab cubature --integrand image:sky.exr"), ["sky.exr"]);
    assert_eq!(inputs("samplab generate jitter -o j.txt && samplab plot j.txt -o j.png"), Vec::<String>::new());
    let help = "Usage\n\nExamples:\n  samplab a \\\n    --b\n  samplab c\n\nMore";
    assert_eq!(help_examples(help).unwrap(), ["samplab a --b", "samplab c"]);
    assert!(help_examples("Examples:\n  samplab a --b\n  --c 1\n").is_err(), "a wrapped example passed");
    let page = "text\n```sh\nsamplab a \\\n    b   # note\nls\n```\n```python\nsamplab.x()\n```\n";
    assert_eq!(page_examples(page), ["samplab a b   # note"]);
}

#[test]
fn every_example_of_the_readme_and_the_guide_runs() {
    let mut pages = vec![root().join("README.md"), root().join("docs/index.md")];
    let mut guide: Vec<PathBuf> =
        std::fs::read_dir(root().join("docs/guide")).unwrap().map(|e| e.unwrap().path()).collect();
    guide.sort();
    pages.extend(guide.into_iter().filter(|p| p.extension().is_some_and(|e| e == "md")));
    let sources: Vec<(String, Vec<String>)> = pages
        .iter()
        .map(|page| {
            let name = page.strip_prefix(root()).unwrap_or(page).display().to_string();
            (name, page_examples(&std::fs::read_to_string(page).unwrap()))
        })
        .collect();
    let count: usize = sources.iter().map(|s| s.1.len()).sum();
    let failures = run_all(&sources);
    assert!(count >= 40, "only {count} examples found in the README and the guide");
    assert!(failures.is_empty(), "{} of {count} examples failed:\n{}", failures.len(), failures.join("\n"));
}

#[test]
fn every_example_of_every_commands_help_runs() {
    let samplab = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_samplab")).args(args).output().unwrap();
        assert!(out.status.success(), "samplab {args:?}");
        String::from_utf8(out.stdout).unwrap()
    };
    let top = samplab(&["--help"]);
    let commands: Vec<String> = top
        .split("Commands:")
        .nth(1)
        .and_then(|s| s.split("Options:").next())
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("  ").filter(|l| !l.starts_with(' ')).and_then(|l| l.split_whitespace().next()))
        .filter(|c| *c != "help")
        .map(String::from)
        .collect();
    assert!(commands.len() >= 14, "commands: {commands:?}");
    let (mut sources, mut failures) = (Vec::new(), Vec::new());
    for c in &commands {
        match help_examples(&samplab(&[c, "--help"])) {
            Ok(lines) => sources.push((format!("samplab {c} --help"), lines)),
            Err(e) => failures.push(format!("samplab {c} --help: {e}")),
        }
    }
    let count: usize = sources.iter().map(|s| s.1.len()).sum();
    failures.extend(run_all(&sources));
    assert!(failures.is_empty(), "{} failures:\n{}", failures.len(), failures.join("\n"));
    assert!(count >= 30, "only {count} examples in the commands' help");
}
