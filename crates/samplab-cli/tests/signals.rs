//! Long commands stopped by a signal (Ctrl-C is SIGINT, `kill` sends SIGTERM): they exit
//! 130 promptly with one line, and leave no output at all, neither under the final name nor
//! as a temporary file beside it. Memory: requests larger than the memory available are
//! refused in one line before any allocation, under the address-space limit `ulimit -v`.
#![cfg(unix)]

mod common;
use common::Temp;
#[path = "common/stopped.rs"]
mod stopped;

use std::io::Read as _;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

fn temp(name: &str) -> Temp {
    Temp::new("signals", name)
}

/// Start `args` in `dir`, send `signal` after `after`, and check the stop: exit 130 after
/// at most [`stopped::STOP_CPU`] CPU seconds of work, one line on stderr, nothing left in `dir`.
fn stopped(name: &str, args: &[&str], signal: &str, after: Duration) {
    let dir = temp(name);
    let mut child = Command::new(env!("CARGO_BIN_EXE_samplab"))
        .args(args)
        .current_dir(&dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(after);
    assert!(child.try_wait().unwrap().is_none(), "{name}: finished before the signal; make it longer");
    let at_signal = stopped::cpu_seconds(child.id());
    let kill = Command::new("kill").args([signal, &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let (status, cpu, _) = stopped::reap(child.id(), Duration::from_secs(60));
    let mut stderr = String::new();
    child.stderr.take().unwrap().read_to_string(&mut stderr).unwrap();
    assert_eq!(status.code(), Some(130), "{name}: {stderr}");
    let after = cpu - at_signal;
    assert!(after < stopped::STOP_CPU, "{name}: {after:.2} CPU seconds after the signal");
    assert!(stderr.ends_with("samplab: interrupted: nothing was written\n"), "{name}: {stderr}");
    assert_eq!(listing(&dir), Vec::<String>::new(), "{name}: files were left behind");
}

fn listing(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect()
}

#[test]
fn a_long_render_stops_on_sigterm() {
    stopped("render", &["render", "spheres", "--spp", "4096", "-o", "out.exr"], "-TERM", Duration::from_secs(1));
}

#[test]
fn a_long_spectrum_stops_on_sigint() {
    let args =
        ["spectrum", "--sampler", "jitter", "-n", "4096", "--sets", "400", "--res", "256", "--direct", "-o", "spectra"];
    stopped("spectrum", &args, "-INT", Duration::from_secs(1));
}

#[test]
fn a_long_integration_study_stops_on_sigterm() {
    let args = [
        "integrate",
        "--sampler",
        "random",
        "--sampler",
        "jitter",
        "--integrand",
        "disk",
        "-n",
        "65536",
        "--sets",
        "100000",
        "--plot",
        "p.png",
    ];
    stopped("integrate", &args, "-TERM", Duration::from_secs(1));
}

#[test]
fn a_long_reproduction_stops_on_sigint() {
    stopped("reproduce", &["reproduce", "--full", "--out", "report"], "-INT", Duration::from_secs(2));
}

#[test]
fn requests_past_the_memory_available_are_refused_before_any_allocation() {
    let dir = temp("memory");
    // 2^32 jittered points in 2D need 128 GiB with their file, and jitter cannot be made in
    // pieces; under a 2 GiB address space an attempt would abort the process
    let bin = env!("CARGO_BIN_EXE_samplab");
    let out = Command::new("sh")
        .args(["-c", &format!("ulimit -v 2000000 && exec '{bin}' generate jitter -n 4294967296 -o x.npy")])
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.starts_with(
            "samplab: error: 4294967296 2D points and their npy file needs 128.0 GiB of memory, over the "
        ),
        "{stderr}"
    );
    assert!(stderr.ends_with(" available; set another limit with --max-memory\n") && stderr.lines().count() == 1);
    // every command's large request, under the same limit
    for (args, what) in [
        ("render spheres --res 16384x16384 -n 1 -o x.exr", "a 16384x16384 image needs 4.0 GiB"),
        ("spectrum --sampler jitter -n 16 --sets 2 --res 8192 -o s", "the spectra of 2 sets at 8192^2 needs 4.0 GiB"),
        ("integrate --sampler random --integrand quad -n 16 --sets 1000000000", "1000000000 realizations on "),
        (
            "generate sobol -n 4294967296 -d 8 --sets 2 -o y.npy",
            "8589934592 8D points and their npy file needs 1.0 TiB",
        ),
    ] {
        let out = Command::new("sh")
            .args(["-c", &format!("ulimit -v 2000000 && exec '{bin}' {args}")])
            .current_dir(&dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args}: {stderr}");
        assert!(
            stderr.starts_with(&format!("samplab: error: {what}")) && stderr.lines().count() == 1,
            "{args}: {stderr}"
        );
    }
    // a point file larger than memory (sparse: 64 GiB of nothing on disk)
    let big = std::fs::File::create(dir.join("big.txt")).unwrap();
    big.set_len(64 << 30).unwrap();
    drop(big);
    let out = Command::new("sh")
        .args(["-c", &format!("ulimit -v 2000000 && exec '{bin}' discrepancy star big.txt")])
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.starts_with("samplab: error: reading big.txt needs 320.0 GiB of memory"), "{stderr}");
    std::fs::remove_file(dir.join("big.txt")).unwrap();
    // --max-memory sets the limit: 4 x 65536 2D points (4 MiB) and their text (12.5 MiB)
    let out = Command::new(bin)
        .args(["generate", "jitter", "-n", "65536", "--sets", "4", "--max-memory", "1M"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "samplab: error: 262144 2D points and their text file needs 16.5 MiB of memory, over the 1.0 MiB available; set another limit with --max-memory\n"
    );
    assert_eq!(listing(&dir), Vec::<String>::new());
}

#[test]
fn a_set_larger_than_memory_is_streamed_to_the_same_bytes() {
    let dir = temp("stream");
    let bin = env!("CARGO_BIN_EXE_samplab");
    for (spec, file) in [("random", "r.npy"), ("sobol.owen", "s.txt"), ("halton.xor", "h.csv")] {
        let args = ["generate", spec, "-n", "300000", "-d", "3", "--seed", "4"];
        let whole =
            Command::new(bin).args(args).args(["-o", &format!("whole-{file}")]).current_dir(&dir).output().unwrap();
        assert!(whole.status.success());
        // 12 MiB holds the chunks' buffers (about 6 MiB for text; every block from 64 KiB
        // counts against --max-memory) but not the points (7.2 MB) with their file (7.2 MB
        // as npy, more as text): made and written in chunks
        let streamed = Command::new(bin)
            .args(args)
            .args(["-o", &format!("streamed-{file}"), "--max-memory", "12M"])
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(streamed.status.success(), "{}", String::from_utf8_lossy(&streamed.stderr));
        let read = |name: String| std::fs::read(dir.join(name)).unwrap();
        assert!(read(format!("whole-{file}")) == read(format!("streamed-{file}")), "{spec}: the streamed file differs");
    }
    // a Ctrl-C while streaming leaves nothing
    stopped(
        "streamed",
        // 2^28 points: past memory, and within a disk's room (8 GiB at 8 bytes a coordinate)
        &["generate", "halton.owen", "-n", "268435456", "-d", "4", "-o", "big.txt", "--max-memory", "1G"],
        "-INT",
        Duration::from_secs(1),
    );
}
