//! `samplab atlas`: its numbers are the CLI's for the same arguments, and its bytes do not
//! depend on the thread count.

mod common;
use common::Temp;

use std::path::Path;
use std::process::{Command, Output};

fn samplab(args: &[&str], threads: &str) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_samplab"))
        .args(args)
        .env("RAYON_NUM_THREADS", threads)
        .output()
        .expect("running samplab");
    assert!(out.status.success(), "samplab {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    out
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

/// Every file under `dir`, by its path relative to `dir`, with its bytes.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let path = e.unwrap().path();
        if path.is_dir() {
            let sub = path.file_name().unwrap().to_string_lossy().to_string();
            out.extend(files(&path).into_iter().map(|(k, v)| (format!("{sub}/{k}"), v)));
        } else {
            out.push((path.file_name().unwrap().to_string_lossy().to_string(), std::fs::read(&path).unwrap()));
        }
    }
    out.sort();
    out
}

const SAMPLERS: [&str; 3] = ["jitter", "sobol.owen", "poisson"];

#[test]
fn the_atlas_agrees_with_the_cli_and_with_itself_on_any_thread_count() {
    let t = Temp::new("atlas", "agree");
    let only = SAMPLERS.join(",");
    let (one, two) = (t.join("one"), t.join("two"));
    samplab(&["atlas", "--only", &only, "--out", one.to_str().unwrap()], "1");
    samplab(&["atlas", "--only", &only, "--out", two.to_str().unwrap()], "2");
    let (a, b) = (files(&one), files(&two));
    assert_eq!(a.iter().map(|f| &f.0).collect::<Vec<_>>(), b.iter().map(|f| &f.0).collect::<Vec<_>>());
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(x == y, "{name} differs between 1 and 2 threads");
    }
    for s in SAMPLERS {
        assert!(one.join(format!("samplers/{s}.html")).is_file(), "no page for {s}");
        let m = json(&one.join(format!("samplers/{s}.json")));
        let seed = m["seed"].as_u64().unwrap().to_string();
        let rows = m["rows"].as_array().unwrap();
        assert!(rows.len() >= 5, "{s}: {} counts", rows.len());
        for row in rows {
            let (n, sets) = (row["n"].to_string(), row["sets"].to_string());
            let out = samplab(
                &[
                    "discrepancy",
                    "star",
                    "l2-star",
                    "--sampler",
                    s,
                    "-n",
                    &n,
                    "--sets",
                    &sets,
                    "--seed",
                    &seed,
                    "--json",
                ],
                "2",
            );
            let cli: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
            let mean = |k: usize| cli["metrics"][k]["mean"].as_f64().unwrap();
            assert_eq!(row["star"].as_f64().unwrap(), mean(0), "{s} at n = {n}: star");
            assert_eq!(row["l2_star"].as_f64().unwrap(), mean(1), "{s} at n = {n}: L2-star");
        }
        let spec = t.join(format!("spectrum-{s}"));
        let (n, sets, res) = (m["n"].to_string(), m["spectrum_sets"].to_string(), m["res"].to_string());
        samplab(
            &[
                "spectrum",
                "--sampler",
                s,
                "-n",
                &n,
                "--sets",
                &sets,
                "--seed",
                &seed,
                "--res",
                &res,
                "--stat",
                "periodogram",
                "-o",
                spec.to_str().unwrap(),
            ],
            "2",
        );
        let cli = json(&spec.join("spectrum.json"));
        assert_eq!(m["radial"], cli["statistics"]["periodogram"]["radial"], "{s}: the radial spectrum");
        // the t-value at a power of 2: the largest over the same sets
        let t = m["t_value"].as_f64().unwrap_or_else(|| panic!("{s}: no t-value at {n} points"));
        let out = samplab(
            &["discrepancy", "t-value", "--sampler", s, "-n", &n, "--sets", &sets, "--seed", &seed, "--json"],
            "2",
        );
        let cli: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(cli["metrics"][0]["max"].as_f64().unwrap(), t, "{s}: the t-value");
    }
}

#[test]
fn an_unknown_sampler_is_refused_and_nothing_is_written() {
    let t = Temp::new("atlas", "unknown");
    let out = Command::new(env!("CARGO_BIN_EXE_samplab"))
        .args(["atlas", "--only", "jitter,sobl", "--out", t.join("a").to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("sobl") && err.contains("did you mean sobol"), "{err}");
    assert!(!t.join("a").exists());
}

#[test]
fn a_sampler_named_twice_has_one_page() {
    let t = Temp::new("atlas", "twice");
    let out = t.join("a");
    samplab(&["atlas", "--only", "jitter,jittered,JITTER", "--out", out.to_str().unwrap()], "2");
    let pages: Vec<String> = files(&out.join("samplers")).into_iter().map(|f| f.0).collect();
    assert_eq!(pages, ["jitter.html", "jitter.json"]);
}
