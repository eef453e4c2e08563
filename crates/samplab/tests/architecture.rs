//! The library's layers, read from its sources (ARCHITECTURE.md draws the map): the
//! constructions import only the numeric base, the base nothing above it, and the two front
//! doors (point sets in `sampler/`, pixel samplers in `pixel/`) never each other's family
//! files (a pixel sampler may serve a point set per pixel through the point sets' own front
//! door, `sampler::build` and its `Plan`); and neither they nor the constructions keep
//! process-wide state.

use std::path::Path;

/// The numeric base: what every layer may import.
const BASE: &[&str] =
    &["bibliography", "error", "memory", "numeric", "points", "progress", "registry", "seed", "simd", "spec"];

/// Each rule: files under `from` may name (as `crate::module::item`) only what `may`
/// allows, given the module and the item after it.
struct Rule {
    from: &'static [&'static str],
    may: fn(&str, &str) -> bool,
    why: &'static str,
}

/// What the pixel samplers may name of the point sets: their front door, never a family.
const SAMPLER_FRONT: &[&str] = &["build", "Plan", "Sampler"];

const RULES: &[Rule] = &[
    Rule { from: BASE, may: |m, _| BASE.contains(&m), why: "the base imports only the base" },
    Rule {
        from: &["construct"],
        may: |m, _| BASE.contains(&m) || m == "construct",
        why: "the constructions import only the base",
    },
    Rule { from: &["sampler"], may: |m, _| m != "pixel", why: "the point sets never import the pixel samplers" },
    Rule {
        from: &["pixel"],
        may: |m, item| m != "sampler" || SAMPLER_FRONT.contains(&item),
        why: "the pixel samplers reach the point sets only through sampler::build and a Plan",
    },
    Rule {
        from: &["sampler", "pixel"],
        may: |m, _| BASE.contains(&m) || ["construct", "sampler", "pixel"].contains(&m) || UPWARD.contains(&m),
        why: "the front doors import the constructions and the base (and the edges ARCHITECTURE.md lists)",
    },
];

/// The edges from the front doors to the layers above them that are left for later rounds
/// (ARCHITECTURE.md lists each): the neighbour grids of `spatial` and the file reading of
/// `io` (point sets), screen planes and Heitz et al.'s test integrands (pixel samplers), the
/// dataflow graph of the parallel optimizers. A new one fails the test until it is listed.
const UPWARD: &[&str] = &["dataflow", "integrand", "io", "screen", "spatial"];

/// The top-level module a source path (relative to `src/`) belongs to.
fn module_of(path: &str) -> &str {
    let first = path.split('/').next().unwrap_or(path);
    first.strip_suffix(".rs").unwrap_or(first)
}

/// Every `crate::module` a source names outside its comments, with its line and the item
/// named after it (`crate::sampler::build`: `sampler` and `build`; empty for a group).
fn named_modules(text: &str) -> Vec<(usize, String, String)> {
    let mut named = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("//") {
            continue;
        }
        for (at, _) in line.match_indices("crate::") {
            let rest = &line[at + "crate::".len()..];
            let word = |s: &str| s.chars().take_while(|c| c.is_ascii_alphanumeric() || *c == '_').collect::<String>();
            let module = word(rest);
            let item = rest[module.len()..].strip_prefix("::").map(word).unwrap_or_default();
            if !module.is_empty() {
                named.push((i + 1, module, item));
            }
        }
    }
    named
}

/// The modules whose state lives in their samplers and plans, never in the process.
const STATELESS: &[&str] = &["construct", "sampler", "pixel"];

/// Whether a line declares process-wide mutable or lazily made state (a cache).
fn process_wide(line: &str) -> bool {
    let code = line.trim_start();
    let declares =
        code.starts_with("static ") || code.starts_with("pub static ") || code.starts_with("pub(crate) static ");
    declares && ["Mutex", "RwLock", "OnceLock", "LazyLock", "OnceCell", "thread_local"].iter().any(|w| code.contains(w))
}

/// The rules a set of sources (path relative to `src/`, text) breaks, one line each.
fn violations(sources: &[(String, String)]) -> Vec<String> {
    let mut found = Vec::new();
    for (path, text) in sources {
        let from = module_of(path);
        if STATELESS.contains(&from) {
            for (i, line) in text.lines().enumerate().filter(|(_, l)| process_wide(l)) {
                found.push(format!("src/{path}:{} keeps process-wide state: {}", i + 1, line.trim()));
            }
        }
        for rule in RULES.iter().filter(|r| r.from.contains(&from)) {
            for (line, module, item) in named_modules(text) {
                if module != from && !(rule.may)(&module, &item) {
                    found.push(format!("src/{path}:{line} names crate::{module}: {}", rule.why));
                }
            }
        }
    }
    found
}

fn sources(dir: &Path, root: &Path, out: &mut Vec<(String, String)>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let relative = path.strip_prefix(root).unwrap().to_string_lossy().replace('\\', "/");
            out.push((relative, std::fs::read_to_string(&path).unwrap()));
        }
    }
}

#[test]
fn layers_import_only_downward() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    sources(&root, &root, &mut all);
    assert!(all.iter().any(|(p, _)| p.starts_with("construct/")) && all.len() > 90, "{} sources", all.len());
    let found = violations(&all);
    assert!(found.is_empty(), "{}", found.join("\n"));
}

/// The check finds what it is for: a pixel sampler reaching into a point-set family, a
/// construction importing a front door, the base importing a measure, a sampler's cache in a
/// static (and comments, and the state of I/O, pass).
#[test]
fn the_layer_check_sees_a_wrong_import() {
    let file = |path: &str, text: &str| (path.to_string(), text.to_string());
    let found = violations(&[
        file("pixel/sobol.rs", "use crate::construct::sobol::byte_tables;\nuse crate::sampler::qmc::sobol::Sobol;\n"),
        file("pixel/sequence.rs", "use crate::sampler::{Plan, build};\nlet s = crate::sampler::build(spec);"),
        file("sampler/qmc/net.rs", "// see crate::pixel::sobol\nfn f() { crate::pixel::prepare(); }\n"),
        file("construct/pbrt.rs", "use crate::spec::ParamSpec;\nuse crate::sampler::Counts;\n"),
        file("numeric/mod.rs", "let s = crate::discrepancy::l2::Sum::default();"),
        file("spectrum/mod.rs", "use crate::sampler::Plan;"),
        file("sampler/stratified/grid.rs", "use crate::spectrum::theory::VarianceTheory;"),
        file("sampler/qmc/lattice.rs", "static CONSTRUCTED: Mutex<Vec<u64>> = Mutex::new(Vec::new());"),
        file("io/mod.rs", "static STAGED: Mutex<Vec<u64>> = Mutex::new(Vec::new());"),
    ]);
    assert_eq!(
        found,
        [
            "src/pixel/sobol.rs:2 names crate::sampler: the pixel samplers reach the point sets only through \
             sampler::build and a Plan",
            "src/pixel/sequence.rs:1 names crate::sampler: the pixel samplers reach the point sets only through \
             sampler::build and a Plan",
            "src/sampler/qmc/net.rs:2 names crate::pixel: the point sets never import the pixel samplers",
            "src/construct/pbrt.rs:2 names crate::sampler: the constructions import only the base",
            "src/numeric/mod.rs:1 names crate::discrepancy: the base imports only the base",
            "src/sampler/stratified/grid.rs:1 names crate::spectrum: the front doors import the constructions and \
             the base (and the edges ARCHITECTURE.md lists)",
            "src/sampler/qmc/lattice.rs:1 keeps process-wide state: static CONSTRUCTED: Mutex<Vec<u64>> = \
             Mutex::new(Vec::new());",
        ]
    );
}
