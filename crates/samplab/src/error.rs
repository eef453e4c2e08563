//! The library's typed errors. Every message is one line that names what is wrong and where.

use thiserror::Error;

/// Everything that can go wrong in samplab's library calls.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A sampler cannot make exactly `n` points (e.g. a grid sampler asked for a non-power).
    #[error("{sampler}: cannot make {n} points in {dims}D: {reason}")]
    InvalidCount {
        /// The sampler's canonical name.
        sampler: String,
        /// The count asked for.
        n: usize,
        /// The dimension asked for.
        dims: usize,
        /// Why, and what would work instead.
        reason: String,
    },
    /// A sampler does not support the dimension asked for.
    #[error("{sampler}: {dims}D is not supported (supported: {supported})")]
    InvalidDims {
        /// The sampler's canonical name.
        sampler: String,
        /// The dimension asked for.
        dims: usize,
        /// The supported range, in words.
        supported: String,
    },
    /// A name that no registry knows.
    #[error("unknown {kind} {}{}", quoted(.name, NAME_SHOWN), suggest(.suggestions))]
    UnknownName {
        /// "sampler", "warp", "format", ...
        kind: &'static str,
        /// The name as given.
        name: String,
        /// The closest known names.
        suggestions: Vec<String>,
    },
    /// A parameter that is unknown, malformed or out of range.
    #[error("{owner}: parameter '{param}': {reason}")]
    Param {
        /// The sampler or warp the parameter belongs to.
        owner: String,
        /// The parameter's name (or its position).
        param: String,
        /// What is wrong, with the valid range.
        reason: String,
    },
    /// A construction or computation that could not finish (Poisson disks that do not fit,
    /// Voronoi cells that do not close, a value beyond double precision).
    #[error("{what}: {reason}")]
    Infeasible {
        /// The sampler's canonical name, or the computation.
        what: String,
        /// What could not be done, with numbers.
        reason: String,
    },
    /// Malformed input data (a point file); `location` is `file:line` or similar.
    #[error("{location}: {reason}")]
    Parse {
        /// Where: `path:line`, `path`, or a flag name.
        location: String,
        /// What is wrong there.
        reason: String,
    },
    /// An operating-system I/O failure.
    #[error("{path}: {reason}")]
    Io {
        /// The file involved.
        path: String,
        /// The OS error, as text.
        reason: String,
    },
    /// A setting of a computation (a study's realizations, a render's sample counts) out of
    /// its range; `name` is the library's name for it (a front end maps it to its flag).
    #[error("{name} = {value}: {reason}")]
    Setting {
        /// The setting's name, e.g. `sets`, `instances`, `spp`.
        name: &'static str,
        /// The value given.
        value: String,
        /// What it must be.
        reason: String,
    },
    /// An exact algorithm refused before any work: its estimated cost is over the limit
    /// the caller set (`discrepancy::Limits::max_work`).
    #[error("{what} takes about {work:.1e} steps, over the work limit {limit:.1e}")]
    WorkLimit {
        /// What would have been computed, with its size.
        what: String,
        /// The estimated number of steps.
        work: f64,
        /// The limit.
        limit: f64,
    },
    /// An allocation that does not fit in the memory available ([`crate::memory`]).
    #[error("{what} needs {} of memory, over the {} available", crate::memory::human(*.need), crate::memory::human(u128::from(*.available)))]
    Memory {
        /// What would have been allocated, with its size.
        what: String,
        /// The bytes it needs.
        need: u128,
        /// The bytes available.
        available: u64,
    },
    /// Work stopped on request (Ctrl-C, SIGTERM, a stop flag: [`crate::progress`]).
    #[error("interrupted")]
    Interrupted,
    /// Points, sets or integrands in a dimension the computation does not take.
    #[error("{what} takes {takes}, not {got}D")]
    Dimension {
        /// The computation, e.g. `the exact extreme discrepancy`.
        what: String,
        /// The dimensions it takes, in words (`2D points`, `1 to 6 dimensions`).
        takes: String,
        /// The dimension given.
        got: usize,
    },
    /// Inputs whose sizes or dimensions do not agree with one another.
    #[error("{what}: got {got}, expected {expected}")]
    Mismatch {
        /// Which input, e.g. `set 3`.
        what: String,
        /// What it should be (set by the other inputs).
        expected: String,
        /// What it is.
        got: String,
    },
    /// Fewer inputs than a computation needs (an empty set, one set for a variance).
    #[error("{what} needs at least {}, got {got}", counted(*.least, .of))]
    TooFew {
        /// The computation.
        what: String,
        /// The least number it takes.
        least: usize,
        /// Of what, in the singular (`point`, `set`).
        of: &'static str,
        /// The number given.
        got: usize,
    },
    /// A point coordinate outside the unit cube [0, 1]^d.
    #[error("point {point} coordinate {coordinate} is {value} (outside [0, 1])")]
    OutsideUnitCube {
        /// The point's index.
        point: usize,
        /// The coordinate's index.
        coordinate: usize,
        /// Its value.
        value: f64,
    },
    /// A number that must be finite and is NaN or infinite.
    #[error("{what} is {value}, not a finite number")]
    NotFinite {
        /// Which number, e.g. `point 3 coordinate 1`.
        what: String,
        /// Its value.
        value: f64,
    },
    /// An output folder that holds an entry samplab did not write: it is replaced only when
    /// the caller says so ([`crate::io::Replace::Force`]; each front end names its switch).
    #[error("{folder}: holds '{entry}', which samplab did not write; name a new folder, or allow replacing it")]
    ForeignEntry {
        /// The folder.
        folder: String,
        /// The first entry samplab did not write, relative to the folder.
        entry: String,
    },
    /// A failure on one set of a stack (a discrepancy of set 7 over its work limit): the
    /// failure itself, with the set's index.
    #[error("set {set}: {error}")]
    InSet {
        /// The set's index in the stack.
        set: u64,
        /// What went wrong there.
        error: Box<Error>,
    },
    /// What fits none of the typed cases (few: each is one of a kind).
    #[error("{0}")]
    Invalid(String),
}

impl Error {
    /// This failure as one on set `set` of a stack ([`Error::InSet`]); a stop stays a stop.
    pub fn in_set(self, set: usize) -> Error {
        match self {
            Error::Interrupted => self,
            error => Error::InSet { set: set as u64, error: Box::new(error) },
        }
    }

    /// The failure itself, inside any [`Error::InSet`].
    pub fn innermost(&self) -> &Error {
        match self {
            Error::InSet { error, .. } => error.innermost(),
            e => e,
        }
    }
}

/// `n` of `what`, in the plural where `n` is not 1 (`1 point`, `2 sets`, `2 axes`).
fn counted(n: usize, what: &str) -> String {
    match (n, what) {
        (1, _) => format!("1 {what}"),
        (_, "axis") => format!("{n} axes"),
        _ => format!("{n} {what}s"),
    }
}

fn suggest(s: &[String]) -> String {
    if s.is_empty() { String::new() } else { format!(" (did you mean {}?)", s.join(", ")) }
}

/// Shorthand for results with [`enum@Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// The known names closest to `name` (Levenshtein distance, at most three), best first.
pub fn closest_names<'a>(name: &str, known: impl IntoIterator<Item = &'a str>) -> Vec<String> {
    let name = name.to_ascii_lowercase();
    // a name is also compared with its family (the part before '.'): "disc" finds "disk.polar"
    let mut scored: Vec<(usize, &str)> = known
        .into_iter()
        .map(|k| {
            let k_low = k.to_ascii_lowercase();
            let family = k_low.split('.').next().unwrap_or("");
            (edit_distance(&name, &k_low).min(edit_distance(&name, family) + 1), k)
        })
        .filter(|(d, k)| *d <= 3.max(name.len() / 3) || k.starts_with(name.as_str()))
        .collect();
    scored.sort();
    scored.dedup_by(|a, b| a.1 == b.1);
    scored.into_iter().take(3).map(|(_, k)| k.to_string()).collect()
}

fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (diag + usize::from(ca != cb)).min(row[j] + 1).min(row[j + 1] + 1);
            diag = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

/// `text` quoted for an error message: at most [`EXCERPT`] characters of it (an ellipsis
/// marks a cut), control characters as `?`. A message about a file quotes the offending
/// token through this, never a whole line: the file may not be one the user meant to show
/// (a scene naming `/etc/shadow`, a point file that is `/proc/self/environ`).
pub fn excerpt(text: &str) -> String {
    quoted(text, EXCERPT)
}

/// The most characters of a file's content that [`excerpt`] quotes.
pub const EXCERPT: usize = 16;

/// The most characters of an unknown name that its error quotes (a name of 10^5 characters
/// made a line of as many).
const NAME_SHOWN: usize = 64;

/// `text` quoted: at most `most` characters of it (an ellipsis marks a cut), control
/// characters as `?`.
fn quoted(text: &str, most: usize) -> String {
    let mut out: String = text.chars().take(most).map(|c| if c.is_control() { '?' } else { c }).collect();
    if text.chars().nth(most).is_some() {
        out.push('…');
    }
    format!("'{out}'")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_by_hand() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("jitter", "jitter"), 0);
    }

    #[test]
    fn closest_names_ranks_by_distance() {
        let known = ["sobol", "halton", "hammersley", "jitter"];
        assert_eq!(closest_names("sobl", known)[0], "sobol");
        assert_eq!(closest_names("haltn", known)[0], "halton");
        assert!(closest_names("zzzzzzzzzz", known).is_empty());
    }

    #[test]
    fn excerpts_are_short_and_printable() {
        assert_eq!(excerpt("abc"), "'abc'");
        assert_eq!(excerpt("root:*:19000:0:99999:7:::"), "'root:*:19000:0:9…'");
        assert_eq!(excerpt("a\u{1b}[2Jb"), "'a?[2Jb'");
    }

    #[test]
    fn unknown_names_are_quoted_whole_up_to_64_characters() {
        let unknown = |name: String| Error::UnknownName { kind: "sampler", name, suggestions: vec![] }.to_string();
        let name = "x".repeat(NAME_SHOWN);
        assert_eq!(unknown(name.clone()), format!("unknown sampler '{name}'"));
        assert_eq!(unknown("x".repeat(100_000)), format!("unknown sampler '{name}…'"));
        assert_eq!(unknown("a\nb".into()), "unknown sampler 'a?b'");
    }
}
