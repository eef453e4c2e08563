//! The report: every page's links and images resolve, the run is deterministic whatever
//! the thread count, and a failed run never replaces or fakes a report.

use std::path::{Path, PathBuf};

use samplab::Seed;
use samplab_report::{Error, Experiment, Options, Paper, Scale, paper, reproduce};

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("samplab-report-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every value of `attr="..."` in `html`.
fn attributes<'a>(html: &'a str, attr: &str) -> Vec<&'a str> {
    let key = format!("{attr}=\"");
    html.match_indices(&key).map(|(i, _)| &html[i + key.len()..]).map(|rest| &rest[..rest.find('"').unwrap()]).collect()
}

fn run_all(out: &Path, threads: usize) -> Vec<(String, samplab_report::Claim)> {
    let papers = paper::all();
    let refs: Vec<&Paper> = papers.iter().collect();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    pool.install(|| reproduce(&refs, &Options { scale: Scale::Fast, seed: Seed(7), out: out.to_path_buf() })).unwrap()
}

#[test]
fn every_link_and_image_resolves() {
    let dir = temp("links");
    let out = dir.join("report");
    let claims = run_all(&out, 2);
    assert!(!claims.is_empty());
    let pages: Vec<PathBuf> = std::fs::read_dir(&out)
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
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
}

#[test]
fn deterministic_whatever_the_thread_count() {
    let dir = temp("det");
    let (a, b) = (dir.join("a"), dir.join("b"));
    run_all(&a, 1);
    run_all(&b, 2);
    for file in [
        "claims.json",
        "tables/shirley1991-table5.csv",
        "tables/shirley1991-table7.csv",
        "tables/shirley1991-projected.csv",
        "figures/shirley1991-table5.svg",
    ] {
        assert_eq!(std::fs::read(a.join(file)).unwrap(), std::fs::read(b.join(file)).unwrap(), "{file} differs");
    }
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
    let bad = Paper {
        key: "shirley1991",
        title: "failing",
        experiments: vec![Experiment { id: "fails", title: "fails", source: "none", parameters: "none", run: failing }],
    };
    let err = reproduce(&[&bad], &Options { scale: Scale::Fast, seed: Seed(1), out: out.clone() }).unwrap_err();
    assert!(err.to_string().contains("on purpose"));
    assert_eq!(std::fs::read_to_string(out.join("index.html")).unwrap(), "old");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "a staging folder was left behind");
}
