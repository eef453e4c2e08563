//! Bakes the Joe–Kuo (2008) Sobol' direction numbers into Rust tables at build time.
//!
//! Input: `data/new-joe-kuo-6.1024.txt` (`d s a m_1..m_s` per line, dimensions 2..=1024).
//! Output: `$OUT_DIR/sobol_directions.rs` holding `SOBOL_DIRECTIONS: [[u32; 32]; 1024]`,
//! where entry [j][k] is the direction number v_k = m_k * 2^(31-k) of dimension j
//! (dimension 0 is van der Corput: m_k = 1), and the same numbers bit-reversed as
//! `SOBOL_REVERSED` (Owen scrambling works on reversed digits), read by
//! `src/construct/joe_kuo.rs`, the reader `net:directions=FILE` uses too.

use std::fmt::Write as _;

#[path = "src/construct/joe_kuo.rs"]
mod joe_kuo;

/// A digest (FNV-1a, 64 bits) of every file under `src/` and `data/`, paths and contents in
/// sorted order: what a measured value depends on, for keys of values kept between runs.
fn source_digest() -> String {
    let mut files = Vec::new();
    let mut stack = vec![std::path::PathBuf::from("src"), std::path::PathBuf::from("data")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("reading the sources").map(|e| e.expect("a source entry")) {
            let path = entry.path();
            if path.is_dir() { stack.push(path) } else { files.push(path) }
        }
    }
    files.sort();
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for path in &files {
        let bytes = std::fs::read(path).expect("reading a source file");
        for b in path.to_string_lossy().bytes().chain([0]).chain(bytes) {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
    }
    format!("{h:016x}")
}

/// The direction table of `src` as Rust: `{prefix}_DIRECTIONS` and its bit-reversed twin
/// `{prefix}_REVERSED`.
fn baked(src: &str, prefix: &str, what: &str) -> String {
    println!("cargo::rerun-if-changed={src}");
    let text = std::fs::read_to_string(src).expect("reading a direction-number file");
    let table = joe_kuo::directions(&text).unwrap_or_else(|(line, why)| panic!("{src}:{line}: {why}"));
    let mut out = String::new();
    let flipped: Vec<[u32; 32]> = table.iter().map(|row| row.map(u32::reverse_bits)).collect();
    let tables = [
        (format!("{prefix}_DIRECTIONS"), format!("{what} direction numbers"), &table),
        (
            format!("{prefix}_REVERSED"),
            format!("{what} direction numbers bit-reversed (for Owen scrambling)"),
            &flipped,
        ),
    ];
    for (name, doc, rows) in tables {
        writeln!(out, "/// {doc}, {} dimensions x 32 bits.", rows.len()).unwrap();
        writeln!(out, "pub(crate) static {name}: [[u32; 32]; {}] = [", rows.len()).unwrap();
        for row in rows.iter() {
            out.push('[');
            for v in row {
                write!(out, "{v:#x},").unwrap();
            }
            out.push_str("],\n");
        }
        out.push_str("];\n");
    }
    out
}

fn main() {
    println!("cargo::rerun-if-changed=src");
    println!("cargo::rerun-if-changed=data");
    println!("cargo::rustc-env=SAMPLAB_SOURCE_DIGEST={}", source_digest());
    let out = baked("data/new-joe-kuo-6.1024.txt", "SOBOL", "Joe–Kuo");
    let dest = std::path::Path::new(&std::env::var("OUT_DIR").unwrap()).join("sobol_directions.rs");
    std::fs::write(dest, out).expect("writing the direction table");
}
