//! The papers' published numbers, from `data/published.json` (the one hand-typed data
//! file, each entry with its source table or figure).

use std::sync::LazyLock;

static PUBLISHED: LazyLock<serde_json::Value> = LazyLock::new(|| {
    serde_json::from_str(include_str!("../data/published.json")).expect("data/published.json is valid JSON")
});

/// The whole data file (published numbers and the coverage lists).
pub fn data() -> &'static serde_json::Value {
    &PUBLISHED
}

/// A published table: its source line and rows of numbers by row name.
#[derive(Debug, Clone)]
pub struct PublishedTable {
    /// Where the numbers come from.
    pub source: String,
    /// Row name -> values, in the file's order.
    pub rows: Vec<(String, Vec<f64>)>,
}

/// The table `table` of paper `paper` (keys of the data file).
///
/// # Panics
/// The entry is missing: a programming error, caught by the reproduction tests.
pub fn table(paper: &str, table: &str) -> PublishedTable {
    let t = &PUBLISHED[paper][table];
    let rows = t["rows"]
        .as_object()
        .unwrap_or_else(|| panic!("published.json has no {paper}.{table}.rows"))
        .iter()
        .map(|(k, v)| {
            (
                k.clone(),
                v.as_array().expect("a row is an array").iter().map(|x| x.as_f64().expect("a number")).collect(),
            )
        })
        .collect();
    PublishedTable { source: t["source"].as_str().unwrap_or_default().to_string(), rows }
}

impl PublishedTable {
    /// The values of row `name`.
    pub fn row(&self, name: &str) -> Option<&[f64]> {
        self.rows.iter().find(|(k, _)| k == name).map(|(_, v)| v.as_slice())
    }
}

/// The verdicts of the last full-scale run (`samplab reproduce --full`), recorded by
/// `scripts/record_full_scale.py` into `data/full_scale.json`, so that the fast report can
/// say which of its verdicts change at the papers' own scales.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FullScale {
    /// When the full run was made (YYYY-MM-DD).
    pub date: String,
    /// Its seed.
    pub seed: u64,
    /// Its wall-clock time in seconds, on the machine named in `machine`.
    pub seconds: f64,
    /// The machine.
    pub machine: String,
    /// "paper/claim id" -> the verdict as the report names it.
    pub verdicts: std::collections::BTreeMap<String, String>,
}

/// The recorded full-scale verdicts.
///
/// # Panics
/// The data file is malformed: a programming error, caught by the report tests.
pub fn full_scale() -> FullScale {
    serde_json::from_str(include_str!("../data/full_scale.json")).expect("data/full_scale.json is well formed")
}
