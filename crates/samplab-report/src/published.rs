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
