//! Every function of the report crate fits in 80 lines (issue 39): an experiment is a
//! measurement, its figures and its claims, each a function of its own.

use std::path::Path;

const MOST: usize = 80;

/// Each function's name, first line and length in lines: from a line that opens `fn`
/// (rustfmt's layout) to the first line after it that is its closing brace alone at the
/// same indentation.
fn functions(text: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut found = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let code = line.trim_start();
        let indent = &line[..line.len() - code.len()];
        let code = ["pub(crate) ", "pub(super) ", "pub "].iter().fold(code, |c, p| c.strip_prefix(p).unwrap_or(c));
        let Some(rest) = code.strip_prefix("fn ") else { continue };
        if line.trim_end().ends_with(';') {
            continue;
        }
        let name: String = rest.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
        let close = format!("{indent}}}");
        if let Some(end) = lines[i + 1..].iter().position(|l| *l == close) {
            found.push((name, i + 1, end + 2));
        }
    }
    found
}

fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn no_function_is_over_80_lines() {
    let mut files = Vec::new();
    sources(&Path::new(env!("CARGO_MANIFEST_DIR")).join("src"), &mut files);
    let mut long = Vec::new();
    for file in &files {
        for (name, line, length) in functions(&std::fs::read_to_string(file).unwrap()) {
            if length > MOST {
                long.push(format!("{}:{line} {name}: {length} lines", file.display()));
            }
        }
    }
    assert!(files.len() > 10, "the sources were not found");
    assert!(long.is_empty(), "functions over {MOST} lines:\n{}", long.join("\n"));
}

/// The counter sees a function's whole body (the test can fail).
#[test]
fn the_counter_measures_a_long_function() {
    let body: String = (0..90).map(|i| format!("    let x{i} = {i};\n")).collect();
    let text = format!("pub(super) fn long() {{\n{body}}}\n\nfn short() {{}}\n");
    assert_eq!(functions(&text), vec![("long".to_string(), 1, 92)]);
}
