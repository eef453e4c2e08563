//! Property tests of every parser samplab has (point files in text, CSV, npy and JSON; the
//! sampler, metric, integrand, warp and scene-light spec grammar; Mitsuba 3 XML; OBJ): inputs
//! mutated from valid seeds (bit flips, replaced, inserted and deleted bytes, truncation,
//! repeated slices, and tokens parsers get wrong: NaN, huge numbers, quotes, brackets) must
//! give a value or a clean error, never a panic, and within a bounded amount of work (CPU
//! seconds of the parsing thread, which a loaded machine does not stretch as it does wall time).

use proptest::prelude::*;
use samplab::io::{self, Format};
use samplab::{PointSet, sampler};
use std::path::Path;

/// Tokens spliced into inputs: values and delimiters that stress number and structure parsing.
const TOKENS: [&str; 16] =
    ["nan", "-inf", "1e309", "-1", "18446744073709551616", "0x10", "\"", "<", "/>", ">", ",", ":", "=", "\n", "{", "]"];

/// One edit of an input.
#[derive(Debug, Clone)]
enum Edit {
    Flip(usize, u8),
    Replace(usize, u8),
    Insert(usize, u8),
    Delete(usize),
    Truncate(usize),
    Repeat(usize, usize),
    Token(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(p, b)| Edit::Flip(p, b)),
        (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Edit::Replace(p, b)),
        (any::<usize>(), any::<u8>()).prop_map(|(p, b)| Edit::Insert(p, b)),
        any::<usize>().prop_map(Edit::Delete),
        any::<usize>().prop_map(Edit::Truncate),
        (any::<usize>(), 1usize..64).prop_map(|(p, l)| Edit::Repeat(p, l)),
        (any::<usize>(), 0..TOKENS.len()).prop_map(|(p, t)| Edit::Token(p, t)),
    ]
}

fn apply(seed: &[u8], edits: &[Edit]) -> Vec<u8> {
    let mut v = seed.to_vec();
    for e in edits {
        let at = |p: usize, len: usize| if len == 0 { 0 } else { p % len };
        match *e {
            Edit::Flip(p, b) if !v.is_empty() => {
                let i = at(p, v.len());
                v[i] ^= 1 << b;
            }
            Edit::Replace(p, b) if !v.is_empty() => {
                let i = at(p, v.len());
                v[i] = b;
            }
            Edit::Insert(p, b) => v.insert(at(p, v.len() + 1), b),
            Edit::Delete(p) if !v.is_empty() => {
                v.remove(at(p, v.len()));
            }
            Edit::Truncate(p) => v.truncate(at(p, v.len() + 1)),
            Edit::Repeat(p, l) if !v.is_empty() => {
                let i = at(p, v.len());
                let piece: Vec<u8> = v[i..(i + l).min(v.len())].to_vec();
                v.splice(i..i, piece);
            }
            Edit::Token(p, t) => {
                let i = at(p, v.len() + 1);
                v.splice(i..i, TOKENS[t].bytes());
            }
            _ => {}
        }
    }
    v
}

/// CPU seconds the calling thread has used.
fn thread_cpu() -> f64 {
    let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
    // SAFETY: the clock of the calling thread, written to a local.
    assert_eq!(unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &raw mut t) }, 0);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

thread_local! {
    /// A pool of one thread, this one, so that the parsers' parallel loops run here and the
    /// thread's clock counts all their work.
    static HERE: rayon::ThreadPool =
        rayon::ThreadPoolBuilder::new().num_threads(1).use_current_thread().build().unwrap();
}

/// Parse `input` with `parse` (all of it on this thread) and fail the case on a parse that
/// works more than 2 CPU seconds (a panic fails it anyway).
fn bounded(what: &str, input: &[u8], parse: impl FnOnce(&[u8]) + Send) -> Result<(), TestCaseError> {
    let start = thread_cpu();
    HERE.with(|pool| pool.install(|| parse(input)));
    let took = thread_cpu() - start;
    prop_assert!(took < 2.0, "{what}: {took:.2} CPU s on {:?}", String::from_utf8_lossy(input));
    Ok(())
}

fn point_file_seeds() -> Vec<(Format, Vec<u8>)> {
    let sets: Vec<PointSet> =
        (0..2).map(|k| sampler::build("jitter").unwrap().generate(4, 2, samplab::Seed(k)).unwrap()).collect();
    let header = vec!["samplab test".to_string()];
    [Format::Text, Format::Csv, Format::Npy, Format::Json]
        .into_iter()
        .map(|f| (f, io::encode(&sets, f, &header).unwrap()))
        .collect()
}

const SPECS: [&str; 8] = [
    "jitter.gaussian:sigma=0.25",
    "poisson:radius=0.05,edge=plain",
    "force-matrix:0.5,2",
    "star-bound:seed=9",
    "disk:r=0.25",
    "steps:k=5",
    "disk.concentric",
    "GJittered:0.25",
];

/// 1500 cases per parser in the test suite; PROPTEST_CASES=N runs a longer campaign.
fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(1500);
    ProptestConfig { cases, failure_persistence: None, ..ProptestConfig::default() }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn point_files_parse_or_refuse(which in 0usize..4, edits in prop::collection::vec(edit(), 1..6)) {
        let (format, seed) = &point_file_seeds()[which];
        let input = apply(seed, &edits);
        bounded("point file", &input, |b| {
            if let Ok(sets) = io::decode(b, *format, "fuzz") {
                // what parses is finite and well formed
                assert!(sets.iter().all(|s| s.as_slice().iter().all(|x| x.is_finite())));
            }
        })?;
    }

    #[test]
    fn specs_parse_or_refuse(which in 0usize..SPECS.len(), edits in prop::collection::vec(edit(), 1..5)) {
        let input = apply(SPECS[which].as_bytes(), &edits);
        bounded("spec", &input, |b| {
            let text = String::from_utf8_lossy(b);
            if let Ok(s) = sampler::build(&text) {
                // a sampler that parses plans (or refuses) a small count without panicking
                let _ = s.plan(16, 2).and_then(|p| p.generate(samplab::Seed(1)));
            }
            let _ = samplab::discrepancy::Metric::parse(&text);
            let _ = samplab::integrand::Family::parse(&text);
            let _ = samplab::warp::lookup(&text);
            let _ = samplab_render::scenes::LightKind::parse(&text);
        })?;
    }

    #[test]
    fn mitsuba_xml_parses_or_refuses(edits in prop::collection::vec(edit(), 1..6)) {
        let seed = std::fs::read("tests/scenes/sphere-box.xml").unwrap();
        let input = apply(&seed, &edits);
        bounded("Mitsuba XML", &input, |b| {
            let _ = samplab_render::mitsuba::parse(
                &String::from_utf8_lossy(b),
                "fuzz.xml",
                Path::new("tests/scenes"),
                samplab_render::mitsuba::Paths::InsideScene,
            );
        })?;
    }

    #[test]
    fn obj_parses_or_refuses(edits in prop::collection::vec(edit(), 1..6)) {
        let seed = std::fs::read("tests/scenes/cube.obj").unwrap();
        let input = apply(&seed, &edits);
        bounded("OBJ", &input, |b| {
            if let Ok(triangles) = samplab_render::obj::parse(&String::from_utf8_lossy(b), "fuzz.obj", samplab_render::obj::Normals::Vertex) {
                assert!(triangles.iter().flat_map(|t| t.corners).all(|v| v.is_finite()));
            }
        })?;
    }
}
