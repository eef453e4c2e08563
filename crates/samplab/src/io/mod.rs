//! Point-set files: plain text, CSV, NumPy `.npy` and JSON, read and written.
//!
//! - **text**: one point per line, coordinates separated by white space; lines starting
//!   with `#` before the first point are comments; a `#` line after points ends a set
//!   (the format UTK and pbrt's pspec read).
//! - **csv**: a header row `x0,x1,...` (with a leading `set` column when the file holds
//!   several sets), then one point per row.
//! - **npy**: little-endian f64, C order; shape (n, d) for one set, (m, n, d) for several
//!   sets of the same size. Read also as big-endian f64 and as f32 in either byte order
//!   (widened to f64 exactly).
//! - **json**: `{"sets": [[[x, y], ...], ...], ...metadata}`; a bare array of points is
//!   read as one set.
//!
//! Coordinates are written in Rust's shortest round-trip form, so a file read back gives
//! the same bits. Every write goes to a temporary file beside the target, then is renamed:
//! a failed or interrupted write never leaves a partial file.

use std::io::Write as _;
use std::ops::RangeInclusive;
use std::path::Path;

use crate::error::{Error, Result};
use crate::points::PointSet;
use crate::progress::Progress;
use crate::registry::{About, Entry, Registry};

mod delimited;
mod output;
pub mod text;
pub(crate) use output::replace_entry;
use output::write_atomic_with;
pub use output::{
    MANIFEST, Replace, Role, Staged, abandon, check_file, check_folder, refuse_overlap, resolve, write_atomic,
    write_folder,
};

/// The most bytes a file named by a spec may hold (the largest real ones, 1024 dimensions
/// of 64 matrix columns in decimal, take a few MiB).
pub const SPEC_FILE_MAX: u64 = 16 << 20;

/// The text of a small file a spec names (a generating matrix, a lattice's vector): a
/// regular file (not a device or a FIFO, which could be endless) of at most `max` bytes,
/// read whole; anything else is refused before it is read.
///
/// # Errors
/// [`Error::Io`] naming the file: missing, not a regular file, larger than `max`, not
/// UTF-8.
pub fn read_small_text(path: &str, max: u64) -> Result<String> {
    let io = |reason: String| Error::Io { path: path.into(), reason };
    let meta = std::fs::metadata(path).map_err(|e| io(e.to_string()))?;
    if !meta.is_file() {
        return Err(io("not a regular file (a device or a FIFO is not read)".into()));
    }
    if meta.len() > max {
        return Err(io(format!(
            "{} long, over the {} such a file may be",
            crate::memory::human(meta.len().into()),
            crate::memory::human(max.into())
        )));
    }
    let mut text = String::new();
    std::io::Read::read_to_string(
        &mut std::io::Read::take(std::fs::File::open(path).map_err(|e| io(e.to_string()))?, max),
        &mut text,
    )
    .map_err(|e| io(e.to_string()))?;
    Ok(text)
}

/// One CSV line (RFC 4180): the fields joined by commas, a field holding a comma, a quote
/// or a line break quoted (its quotes doubled), and a newline.
pub fn csv_line<S: AsRef<str>>(fields: impl IntoIterator<Item = S>) -> String {
    let quoted: Vec<String> = fields
        .into_iter()
        .map(|f| {
            let f = f.as_ref();
            if f.contains([',', '"', '\n', '\r']) { format!("\"{}\"", f.replace('"', "\"\"")) } else { f.to_string() }
        })
        .collect();
    quoted.join(",") + "\n"
}

/// A point-set file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Format {
    /// White-space separated, `#` comments and set separators.
    Text,
    /// Comma separated with a header row.
    Csv,
    /// NumPy array file, f64.
    Npy,
    /// JSON object with a `sets` array.
    Json,
}

/// One registered format: its name, the file extensions that imply it (also accepted as
/// names), and the format.
#[derive(Debug)]
pub struct FormatEntry {
    /// Name, extensions as aliases, summary.
    pub about: About,
    /// The format.
    pub format: Format,
}

impl Entry for FormatEntry {
    fn about(&self) -> &About {
        &self.about
    }
}

/// Every format, for `--format` and `samplab list formats`.
pub static FORMATS: Registry<FormatEntry> = Registry::new("format", "FORMATS", &[&[FORMAT_ENTRIES]]);

static FORMAT_ENTRIES: &[FormatEntry] = &[
    FormatEntry {
        about: About::new("text", "white-space separated, one point per line, '#' line between sets")
            .aliases(&["txt", "pts", "dat"]),
        format: Format::Text,
    },
    FormatEntry { about: About::new("csv", "comma separated with a header row x0,x1,..."), format: Format::Csv },
    FormatEntry {
        about: About::new(
            "npy",
            "NumPy f64 array, (n, d) or (m, n, d), or a film's (frames, height, width, spp, d); f32, u32 (32-bit fixed point, u / 2^32) and big-endian ones read too",
        ),
        format: Format::Npy,
    },
    FormatEntry { about: About::new("json", "{\"sets\": [[[x, y], ...], ...]} with metadata"), format: Format::Json },
];

impl Format {
    /// The format called `name` (or named by its file extension, e.g. `txt`).
    ///
    /// # Errors
    /// An unknown name, with suggestions.
    pub fn from_name(name: &str) -> Result<Format> {
        Ok(FORMATS.lookup(name)?.format)
    }

    /// The format a file name implies by its extension (text when unknown).
    pub fn from_path(path: &Path) -> Format {
        path.extension()
            .and_then(|e| e.to_str())
            .and_then(|e| FORMATS.lookup(e).ok())
            .map_or(Format::Text, |entry| entry.format)
    }
}

/// Encode `sets` in `format`. `header` lines go into text comments or the JSON `meta`
/// object's `header` field; CSV and npy carry none.
///
/// # Errors
/// Sets of different dimensions; for npy, sets of different sizes.
///
/// # Panics
/// Never: JSON of numbers and strings always serializes.
pub fn encode(sets: &[PointSet], format: Format, header: &[String]) -> Result<Vec<u8>> {
    let dims = sets.first().map_or(1, PointSet::dims);
    if let Some(k) = sets.iter().position(|s| s.dims() != dims) {
        return Err(Error::Mismatch {
            what: format!("set {k} (one file takes sets of one dimension)"),
            expected: format!("{dims}D, as set 0"),
            got: format!("{}D", sets[k].dims()),
        });
    }
    let n = sets.first().map_or(0, PointSet::len);
    if format == Format::Npy
        && let Some(k) = sets.iter().position(|s| s.len() != n)
    {
        return Err(Error::Mismatch {
            what: format!("set {k} (npy takes sets of equal size; use text, csv or json)"),
            expected: format!("{n} points, as set 0"),
            got: format!("{} points", sets[k].len()),
        });
    }
    if format == Format::Json {
        let sets: Vec<Vec<&[f64]>> = sets.iter().map(|s| s.iter().collect()).collect();
        let v = serde_json::json!({ "header": header, "dims": dims, "sets": sets });
        // a JSON value of finite numbers and strings always serializes
        let mut out = serde_json::to_vec(&v).expect("JSON of numbers and strings");
        out.push(b'\n');
        return Ok(out);
    }
    let mut out = prologue(format, header, sets.len(), n, dims);
    let many = sets.len() > 1;
    for (k, set) in sets.iter().enumerate() {
        if k > 0 && format == Format::Text {
            out.extend_from_slice(b"#\n");
        }
        rows(&mut out, format, set.as_slice(), dims, (many && format == Format::Csv).then_some(k));
    }
    Ok(out)
}

/// What comes before the points: text's header comments, CSV's column names, npy's header.
fn prologue(format: Format, header: &[String], sets: usize, n: usize, dims: usize) -> Vec<u8> {
    let mut out = Vec::new();
    match format {
        Format::Text => {
            for h in header {
                writeln!(out, "# {h}").unwrap();
            }
        }
        Format::Csv => {
            let cols: Vec<String> = (0..dims).map(|d| format!("x{d}")).collect();
            writeln!(out, "{}{}", if sets > 1 { "set," } else { "" }, cols.join(",")).unwrap();
        }
        Format::Npy if sets == 1 => out = npy_header(&[n, dims]),
        Format::Npy => out = npy_header(&[sets, n, dims]),
        Format::Json => {}
    }
    out
}

/// The header of a version-1 `.npy` file of little-endian f64 in C order with this shape
/// (the values follow it, 8 bytes each).
pub fn npy_header(shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let shape = if dims.len() == 1 { format!("({},)", dims[0]) } else { format!("({})", dims.join(", ")) };
    let mut dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
    // magic(6) + version(2) + len(2) + dict + '\n' is a multiple of 64
    while (10 + dict.len() + 1) % 64 != 0 {
        dict.push(' ');
    }
    dict.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out
}

/// Points per parallel task of [`rows`]: text spends about 60 ns a coordinate on its
/// shortest round-trip digits ([`text::push_f64`]).
const ROWS_CHUNK: usize = 1 << 13;

/// Points (row-major, `dims` per point) in text, CSV (`set` first when given) or npy, onto
/// `out`: the parts of [`row_parts`] joined.
fn rows(out: &mut Vec<u8>, format: Format, points: &[f64], dims: usize, set: Option<usize>) {
    if points.len() <= ROWS_CHUNK * dims {
        return rows_of(out, format, points, dims, set);
    }
    let parts = row_parts(format, points, dims, set);
    out.reserve_exact(parts.iter().map(Vec::len).sum());
    parts.iter().for_each(|part| out.extend_from_slice(part));
}

/// The bytes of [`rows`], made in parallel chunk by chunk of [`ROWS_CHUNK`] points: the
/// chunks' bytes, in order.
fn row_parts(format: Format, points: &[f64], dims: usize, set: Option<usize>) -> Vec<Vec<u8>> {
    use rayon::prelude::*;
    points
        .par_chunks(ROWS_CHUNK * dims)
        .map(|chunk| {
            let mut part = Vec::new();
            rows_of(&mut part, format, chunk, dims, set);
            part
        })
        .collect()
}

/// The body of [`rows`] on one thread.
fn rows_of(out: &mut Vec<u8>, format: Format, points: &[f64], dims: usize, set: Option<usize>) {
    if format == Format::Npy {
        out.reserve_exact(8 * points.len());
        points.iter().for_each(|x| out.extend_from_slice(&x.to_le_bytes()));
        return;
    }
    let sep = if format == Format::Csv { b',' } else { b' ' };
    for p in points.chunks_exact(dims) {
        if let Some(k) = set {
            write!(out, "{k},").unwrap();
        }
        text::push_line(out, p, sep);
    }
}

/// The most bytes `points` coordinates take encoded in `format` (for memory estimates):
/// 8 in npy, 25 as text (24 characters of the longest f64 and a separator), 60 in JSON.
pub fn encoded_size(format: Format, points: usize, dims: usize) -> u128 {
    let per = match format {
        Format::Npy => 8,
        Format::Text | Format::Csv => 25,
        Format::Json => 60,
    };
    per * points as u128 * dims as u128
}

/// The registered name of `format` (`text`, `csv`, `npy`, `json`).
pub fn format_name(format: Format) -> &'static str {
    FORMATS.iter().find(|e| e.format == format).map_or("text", |e| e.about.name)
}

/// Points per chunk of [`write_stream`].
const STREAM_CHUNK: usize = 1 << 16;

/// Write one set of `n` points in `dims` dimensions to `path`, made chunk by chunk by
/// `fill` (each call fills the next `out.len() / dims` points): the bytes [`encode`] writes
/// for the whole set, in memory of one chunk. Atomic as [`write_atomic`]; `progress`
/// advances by one per chunk and can stop the work (the temporary file is then removed).
///
/// # Errors
/// JSON (not streamed), `fill`'s errors, a stop, or the file cannot be written.
pub fn write_stream(
    path: &Path,
    format: Format,
    header: &[String],
    (n, dims): (usize, usize),
    fill: &mut dyn FnMut(&mut [f64]) -> Result<()>,
    progress: &Progress,
) -> Result<()> {
    if format == Format::Json {
        return Err(Error::Setting {
            name: "format",
            value: "json".into(),
            reason: "JSON is written whole; stream text, csv or npy".into(),
        });
    }
    // at least 8 bytes a coordinate (npy exactly; text and CSV take about 20): refused
    // before any work when the disk cannot hold it
    output::check_disk(path, 8 * n as u128 * dims as u128)?;
    write_atomic_with(path, &mut |file| {
        let io = |e: std::io::Error| Error::Io { path: path.display().to_string(), reason: e.to_string() };
        file.write_all(&prologue(format, header, 1, n, dims)).map_err(io)?;
        let mut points = vec![0.0; STREAM_CHUNK * dims];
        let mut done = 0;
        while done < n {
            progress.check()?;
            let k = STREAM_CHUNK.min(n - done);
            fill(&mut points[..k * dims])?;
            for part in row_parts(format, &points[..k * dims], dims, None) {
                file.write_all(&part).map_err(io)?;
            }
            done += k;
            progress.advance(1)?;
        }
        Ok(())
    })
}

/// The chunks [`write_stream`] takes for `n` points.
pub fn stream_chunks(n: usize) -> usize {
    n.div_ceil(STREAM_CHUNK)
}

/// Read every set in the file at `path`, in `format` (or the one its extension implies).
///
/// # Errors
/// The file cannot be read, or is malformed: the message names the file and line (or
/// element) and what is wrong there: a non-number, a non-finite value, a ragged line,
/// mixed dimensions, an empty file.
pub fn read(path: &Path, format: Option<Format>) -> Result<Vec<PointSet>> {
    read_within(path, format, &ANY)
}

/// Any finite coordinate: the domain of [`read`].
pub const ANY: RangeInclusive<f64> = f64::MIN..=f64::MAX;

/// [`read`], refusing any coordinate outside `domain` (for example [0, 1] for a
/// discrepancy) with the file and line (or element) where it is.
///
/// # Errors
/// As [`read`], and a coordinate outside `domain`.
pub fn read_within(path: &Path, format: Option<Format>, domain: &RangeInclusive<f64>) -> Result<Vec<PointSet>> {
    let name = path.display().to_string();
    let io = |e: std::io::Error| Error::Io { path: name.clone(), reason: e.to_string() };
    let format = format.unwrap_or_else(|| Format::from_path(path));
    // the file and its points in memory: npy holds 8 bytes per value; text at least two
    // ("0\n") for 8, so at most 4 times the file
    let factor = if format == Format::Npy { 2 } else { 5 };
    let meta = std::fs::metadata(path).map_err(io)?;
    let bytes = if meta.is_file() {
        crate::memory::check(|| format!("reading {name}"), u128::from(meta.len()) * factor)?;
        read_regular(path, meta.len()).map_err(io)?
    } else {
        // a pipe or a device has no length: read while the memory allows (`/dev/zero` never
        // ends), each growth of the buffer checked before it is made
        use std::io::Read as _;
        let mut file = std::fs::File::open(path).map_err(io)?;
        let mut bytes = Vec::new();
        let mut chunk = vec![0u8; 1 << 16];
        loop {
            let got = file.read(&mut chunk).map_err(io)?;
            if got == 0 {
                break;
            }
            if bytes.len() + got > bytes.capacity() {
                let grown = (2 * bytes.capacity()).max(bytes.len() + got);
                crate::memory::check(|| format!("reading {name} (not a regular file)"), grown as u128 * factor)?;
                bytes.reserve_exact(grown - bytes.len());
            }
            bytes.extend_from_slice(&chunk[..got]);
        }
        bytes
    };
    decode_within(&bytes, format, &name, domain)
}

/// Bytes per parallel read of [`read_regular`].
const READ_PART: usize = 1 << 22;

/// The bytes of the regular file at `path`, `len` long when it was looked at: from two
/// [`READ_PART`]s on, read in parts in parallel (each thread copying, and faulting in, its
/// own part of the buffer: one thread took 30 ms of a 40 MB file while the other waited),
/// then whatever the file has grown by since.
fn read_regular(path: &Path, len: u64) -> std::io::Result<Vec<u8>> {
    #[cfg(unix)]
    if len >= 2 * READ_PART as u64 {
        use rayon::prelude::*;
        use std::io::{Read as _, Seek as _};
        use std::os::unix::fs::FileExt as _;
        let mut file = std::fs::File::open(path)?;
        let mut bytes = vec![0u8; usize::try_from(len).map_err(std::io::Error::other)?];
        bytes
            .par_chunks_mut(READ_PART)
            .enumerate()
            .try_for_each(|(k, part)| file.read_exact_at(part, (k * READ_PART) as u64))?;
        file.seek(std::io::SeekFrom::Start(len))?;
        file.read_to_end(&mut bytes)?;
        return Ok(bytes);
    }
    std::fs::read(path)
}

/// Decode point sets from `bytes`; `name` is used in error messages.
///
/// # Errors
/// As [`read`].
pub fn decode(bytes: &[u8], format: Format, name: &str) -> Result<Vec<PointSet>> {
    decode_within(bytes, format, name, &ANY)
}

/// Why coordinate `x` may not be read, if it may not: not finite, or outside `domain`.
fn refuse(x: f64, domain: &RangeInclusive<f64>) -> Option<String> {
    if !x.is_finite() {
        Some("is not finite".into())
    } else if !domain.contains(&x) {
        Some(format!("is {x}, outside [{}, {}]", domain.start(), domain.end()))
    } else {
        None
    }
}

fn decode_within(bytes: &[u8], format: Format, name: &str, domain: &RangeInclusive<f64>) -> Result<Vec<PointSet>> {
    let sets = match format {
        Format::Text | Format::Csv => delimited::decode(bytes, format == Format::Csv, name, domain)?,
        Format::Npy => decode_npy(bytes, name, domain)?,
        Format::Json => decode_json(bytes, name, domain)?,
    };
    if sets.is_empty() || sets.iter().all(PointSet::is_empty) {
        return Err(Error::Parse { location: name.into(), reason: "no points".into() });
    }
    if let Some(k) = sets.iter().position(PointSet::is_empty) {
        return Err(Error::Parse { location: name.into(), reason: format!("set {k} has no points") });
    }
    Ok(sets)
}

/// An .npy file's header: its shape, each value's width in bytes and decoder, and where the
/// data starts.
struct NpyHeader {
    shape: Vec<usize>,
    width: usize,
    value: fn(&[u8]) -> f64,
    data: usize,
}

/// The shape of the .npy file whose first bytes are `bytes` (its header: `samplab pixels`
/// writes (frames, height, width, spp, dims)); `name` is used in error messages.
///
/// # Errors
/// [`Error::Parse`]: not an .npy header, or one whose dtype or shape samplab does not read.
pub fn npy_shape(bytes: &[u8], name: &str) -> Result<Vec<usize>> {
    Ok(npy_header_of(bytes, name)?.shape)
}

fn npy_header_of(bytes: &[u8], name: &str) -> Result<NpyHeader> {
    let bad = |reason: String| Error::Parse { location: name.into(), reason };
    if bytes.len() < 10 || &bytes[..6] != b"\x93NUMPY" {
        return Err(bad("not an .npy file (bad magic)".into()));
    }
    let (header_len, start) = match bytes[6] {
        1 => (u16::from_le_bytes([bytes[8], bytes[9]]) as usize, 10),
        2 | 3 if bytes.len() >= 12 => (u32::from_le_bytes([bytes[8], bytes[9], bytes[10], bytes[11]]) as usize, 12),
        v => return Err(bad(format!("unsupported .npy version {v}"))),
    };
    let header = bytes.get(start..start + header_len).ok_or_else(|| bad("truncated header".into()))?;
    let header = std::str::from_utf8(header).map_err(|_| bad("header is not text".into()))?;
    let field = |key: &str| -> Option<&str> {
        let i = header.find(&format!("'{key}'"))? + key.len() + 2;
        Some(header[i..].trim_start().trim_start_matches(':').trim_start())
    };
    let descr = field("descr").ok_or_else(|| bad("header has no descr".into()))?;
    // float64 or float32 in either byte order, each value widened exactly to f64; uint32,
    // a renderer's 32-bit fixed point, u / 2^32 (exact)
    let (width, value): (usize, fn(&[u8]) -> f64) = match descr.get(..5) {
        Some("'<f8'") => (8, |c| f64::from_le_bytes(c.try_into().expect("8 bytes"))),
        Some("'>f8'") => (8, |c| f64::from_be_bytes(c.try_into().expect("8 bytes"))),
        Some("'<f4'") => (4, |c| f64::from(f32::from_le_bytes(c.try_into().expect("4 bytes")))),
        Some("'>f4'") => (4, |c| f64::from(f32::from_be_bytes(c.try_into().expect("4 bytes")))),
        Some("'<u4'") => (4, |c| f64::from(u32::from_le_bytes(c.try_into().expect("4 bytes"))) / 4_294_967_296.0),
        Some("'>u4'") => (4, |c| f64::from(u32::from_be_bytes(c.try_into().expect("4 bytes"))) / 4_294_967_296.0),
        _ => {
            return Err(bad(format!(
                "dtype {} is not float64, float32 or uint32 ('<f8', '>f8', '<f4', '>f4', '<u4', '>u4')",
                crate::error::excerpt(descr.split(',').next().unwrap_or("").trim().trim_matches('\''))
            )));
        }
    };
    if field("fortran_order").is_some_and(|v| v.starts_with("True")) {
        return Err(bad("Fortran-order arrays are not supported; save with C order".into()));
    }
    let shape_text = field("shape").ok_or_else(|| bad("header has no shape".into()))?;
    // one tuple of whole numbers: `((2, 2),)` is not a shape
    let inner = shape_text
        .strip_prefix('(')
        .and_then(|t| t.split(')').next())
        .filter(|t| !t.contains('('))
        .ok_or_else(|| bad(format!("bad shape {}", crate::error::excerpt(shape_text))))?;
    let shape: Vec<usize> = inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().map_err(|_| bad(format!("bad shape {}", crate::error::excerpt(inner)))))
        .collect::<Result<_>>()?;
    Ok(NpyHeader { shape, width, value, data: start + header_len })
}

fn decode_npy(bytes: &[u8], name: &str, domain: &RangeInclusive<f64>) -> Result<Vec<PointSet>> {
    let bad = |reason: String| Error::Parse { location: name.into(), reason };
    let NpyHeader { shape, width, value, data } = npy_header_of(bytes, name)?;
    let inner = shape.iter().map(usize::to_string).collect::<Vec<_>>().join(", ");
    // a film's values as `samplab pixels` writes them: a set per pixel, frame by frame, row by row
    let (m, n, d) = match shape[..] {
        [n, d] => (1, n, d),
        [m, n, d] => (m, n, d),
        [frames, h, w, spp, d] => (frames.saturating_mul(h).saturating_mul(w), spp, d),
        _ => return Err(bad(format!("shape ({inner}) is not (n, d), (m, n, d) or (frames, height, width, spp, d)"))),
    };
    // the data bytes, checked: a shape whose byte count passes 2^64 once wrapped to match
    // a short file (found by fuzzing)
    let size = m.checked_mul(n).and_then(|x| x.checked_mul(d)).and_then(|x| x.checked_mul(width));
    let size = size.ok_or_else(|| bad(format!("shape ({inner}) is too large")))?;
    let body = &bytes[data..];
    if d == 0 || body.len() != size {
        return Err(bad(format!("shape ({inner}) needs {size} data bytes, file has {}", body.len())));
    }
    // in parallel: the values, the first refused one, the sets
    use rayon::prelude::*;
    let data: Vec<f64> = body.par_chunks_exact(width).map(value).collect();
    if let Some((i, why)) = data.par_iter().enumerate().find_map_first(|(i, &x)| refuse(x, domain).map(|why| (i, why)))
    {
        return Err(bad(format!("element {i} (set {}, point {}, coordinate {}) {why}", i / (n * d), i / d % n, i % d)));
    }
    if m == 1 && n > 0 {
        return Ok(vec![PointSet::from_raw(d, data)]);
    }
    Ok(data.par_chunks_exact((n * d).max(1)).map(|c| PointSet::from_raw(d, c.to_vec())).collect())
}

fn decode_json(bytes: &[u8], name: &str, domain: &RangeInclusive<f64>) -> Result<Vec<PointSet>> {
    let bad = |reason: String| Error::Parse { location: name.into(), reason };
    let v: serde_json::Value = serde_json::from_slice(bytes)
        .map_err(|e| bad(format!("invalid JSON at line {}, column {}: {e}", e.line(), e.column())))?;
    let sets: Vec<&serde_json::Value> = match &v {
        serde_json::Value::Object(o) => match o.get("sets") {
            Some(serde_json::Value::Array(a)) => a.iter().collect(),
            _ => return Err(bad("expected a \"sets\" array".into())),
        },
        serde_json::Value::Array(_) => vec![&v],
        _ => {
            return Err(bad("expected an object with \"sets\" or an array of points".into()));
        }
    };
    let mut dims = 0;
    let mut out = Vec::new();
    for (k, set) in sets.iter().enumerate() {
        let points = set.as_array().ok_or_else(|| bad(format!("sets[{k}] is not an array")))?;
        let mut data = Vec::new();
        for (i, p) in points.iter().enumerate() {
            let coords = p.as_array().ok_or_else(|| bad(format!("sets[{k}][{i}] is not an array of numbers")))?;
            if dims == 0 {
                dims = coords.len();
            }
            if coords.len() != dims || dims == 0 {
                return Err(bad(format!(
                    "sets[{k}][{i}] has {} coordinates where earlier points have {dims}",
                    coords.len()
                )));
            }
            for (d, c) in coords.iter().enumerate() {
                let x = c.as_f64().ok_or_else(|| bad(format!("sets[{k}][{i}][{d}] is not a number: {c}")))?;
                if let Some(why) = refuse(x, domain) {
                    return Err(bad(format!("sets[{k}][{i}][{d}] {why}")));
                }
                data.push(x);
            }
        }
        out.push(PointSet::from_raw(dims.max(1), data));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seed::Seed;

    fn sets() -> Vec<PointSet> {
        let random = crate::sampler::build("random").unwrap();
        (0..3).map(|k| random.generate(5, 3, Seed(k)).unwrap()).collect()
    }

    #[test]
    fn every_format_round_trips_bit_for_bit() {
        for f in FORMATS.iter().map(|e| e.format) {
            let bytes = encode(&sets(), f, &["made by a test".into()]).unwrap();
            let back = decode(&bytes, f, "mem").unwrap();
            assert_eq!(back, sets(), "{f:?}");
            let one = encode(&sets()[..1], f, &[]).unwrap();
            assert_eq!(decode(&one, f, "mem").unwrap(), sets()[..1].to_vec(), "{f:?} single");
        }
    }

    #[test]
    fn sets_of_many_chunks_are_the_bytes_of_one_point_after_another() {
        // two sets of 2.5 chunks of `rows` in 3D: each point's line (or npy's 24 bytes)
        // made here on its own, the body after the prologue compared, on 1 and 3 threads
        let random = crate::sampler::build("random").unwrap();
        let n = 5 * ROWS_CHUNK / 2;
        let sets: Vec<PointSet> = (0..2).map(|k| random.generate(n, 3, Seed(10 + k)).unwrap()).collect();
        for format in [Format::Text, Format::Csv, Format::Npy] {
            let mut expected = prologue(format, &[], 2, n, 3);
            for (k, set) in sets.iter().enumerate() {
                if k > 0 && format == Format::Text {
                    expected.extend_from_slice(b"#\n");
                }
                for p in set.iter() {
                    let line = match format {
                        Format::Npy => {
                            expected.extend(p.iter().flat_map(|x| x.to_le_bytes()));
                            continue;
                        }
                        Format::Csv => format!("{k},{:?},{:?},{:?}\n", p[0], p[1], p[2]),
                        _ => format!("{:?} {:?} {:?}\n", p[0], p[1], p[2]),
                    };
                    expected.extend_from_slice(line.as_bytes());
                }
            }
            for threads in [1, 3] {
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                let got = pool.install(|| encode(&sets, format, &[])).unwrap();
                assert!(
                    got == expected,
                    "{format:?} on {threads} threads: {} bytes against {}",
                    got.len(),
                    expected.len()
                );
            }
        }
    }

    #[test]
    fn an_npy_shape_whose_size_overflows_is_refused() {
        // 2 x 2^61 x 1 values are 2^65 bytes: 0 once wrapped, the length of this empty body
        let mut bytes = encode(&sets()[..1], Format::Npy, &[]).unwrap();
        let header_len = usize::from(u16::from_le_bytes([bytes[8], bytes[9]]));
        bytes.truncate(10 + header_len);
        let header = String::from_utf8(bytes[10..].to_vec()).unwrap();
        let forged = header.replace("(5, 3)", "(2, 2305843009213693952, 1)");
        let forged = format!("{}{}", forged.trim_end(), " ".repeat(header.len() - forged.trim_end().len() - 1)) + "\n";
        bytes.truncate(10);
        bytes.extend_from_slice(forged.as_bytes());
        bytes[8..10].copy_from_slice(&(forged.len() as u16).to_le_bytes());
        let e = decode(&bytes, Format::Npy, "forged.npy").unwrap_err().to_string();
        assert!(e.contains("too large"), "{e}");
    }

    /// An npy file of `descr` with the given body, by hand.
    fn npy_of(descr: &str, shape: &str, body: &[u8]) -> Vec<u8> {
        let dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}\n");
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
        out.extend_from_slice(dict.as_bytes());
        out.extend_from_slice(body);
        out
    }

    #[test]
    fn npy_of_either_byte_order_and_of_f32_reads_as_the_widened_values() {
        let values = [0.1f32, 0.7, 1.0 / 3.0, 0.0, 0.999_999_94, 0.25];
        let wide: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
        let le4: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let be4: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
        let be8: Vec<u8> = wide.iter().flat_map(|v| v.to_be_bytes()).collect();
        for (descr, body) in [("<f4", le4), (">f4", be4), (">f8", be8)] {
            let sets = decode(&npy_of(descr, "(3, 2)", &body), Format::Npy, "mem").unwrap();
            assert_eq!(sets, vec![PointSet::from_raw(2, wide.clone())], "{descr}");
            // a body sized for the other width is refused
            assert!(decode(&npy_of(descr, "(3, 4)", &body), Format::Npy, "mem").is_err(), "{descr}");
        }
        for descr in ["<i8", "<f2", "|u1", "<c16", "<u8"] {
            let err = decode(&npy_of(descr, "(3, 2)", &[0; 48]), Format::Npy, "mem").unwrap_err().to_string();
            assert!(err.contains("is not float64, float32 or uint32"), "{descr}: {err}");
        }
        // uint32 in either byte order: 32-bit fixed point, u / 2^32
        let words = [0u32, 1, 1 << 31, u32::MAX, 0x5555_5555, 3 << 30];
        let fractions: Vec<f64> = words.iter().map(|&u| f64::from(u) * 2f64.powi(-32)).collect();
        for (descr, body) in [
            ("<u4", words.iter().flat_map(|u| u.to_le_bytes()).collect::<Vec<u8>>()),
            (">u4", words.iter().flat_map(|u| u.to_be_bytes()).collect()),
        ] {
            let sets = decode(&npy_of(descr, "(3, 2)", &body), Format::Npy, "mem").unwrap();
            assert_eq!(sets, vec![PointSet::from_raw(2, fractions.clone())], "{descr}");
        }
    }

    #[test]
    fn npy_of_a_film_reads_a_set_per_pixel_frame_by_frame_row_by_row() {
        // (frames 2, height 1, width 3, spp 2, dims 1): value [f, y, x, i, 0] = 8f + 2x + i
        let values: Vec<f64> = (0..12).map(|k| f64::from((k / 6) * 8 + (k % 6)) / 16.0).collect();
        let body: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let bytes = npy_of("<f8", "(2, 1, 3, 2, 1)", &body);
        assert_eq!(npy_shape(&bytes, "mem").unwrap(), [2, 1, 3, 2, 1]);
        let sets = decode(&bytes, Format::Npy, "mem").unwrap();
        let pixels: Vec<Vec<f64>> = sets.iter().map(|s| s.as_slice().to_vec()).collect();
        let expect: Vec<Vec<f64>> = values.chunks(2).map(<[f64]>::to_vec).collect();
        assert_eq!(pixels, expect);
        let err = decode(&npy_of("<f8", "(1, 1, 2, 3)", &[0; 48]), Format::Npy, "mem").unwrap_err().to_string();
        assert!(
            err.contains("shape (1, 1, 2, 3) is not (n, d), (m, n, d) or (frames, height, width, spp, d)"),
            "{err}"
        );
        assert!(npy_shape(b"not npy", "mem").is_err());
    }

    #[test]
    fn npy_header_is_aligned_and_numpy_shaped() {
        let bytes = encode(&sets(), Format::Npy, &[]).unwrap();
        let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
        assert_eq!((10 + len) % 64, 0);
        assert!(std::str::from_utf8(&bytes[10..10 + len]).unwrap().contains("'shape': (3, 5, 3)"));
    }

    #[test]
    fn malformed_text_names_file_and_line() {
        let err = |t: &str| decode(t.as_bytes(), Format::Text, "pts.txt").unwrap_err().to_string();
        assert_eq!(err("0.1 0.2\n0.3 nan\n"), "pts.txt:2: coordinate 2 is not finite: 'nan'");
        assert_eq!(err("# c\n0.1 0.2\n0.3\n"), "pts.txt:3: 1 coordinates where earlier points have 2");
        assert_eq!(err("0.1 abc\n"), "pts.txt:1: coordinate 2 is not a number: 'abc'");
        assert_eq!(err("# only comments\n"), "pts.txt: no points");
        assert!(decode(b"0.1 0.2\n#\n0.3 0.4 0.5\n", Format::Text, "m").is_err());
        let csv = decode(b"x0,x1\n0.1,0.2\n0.3,inf\n", Format::Csv, "a.csv").unwrap_err().to_string();
        assert_eq!(csv, "a.csv:3: coordinate 2 is not finite: 'inf'");
        let within = |t: &[u8], f| decode_within(t, f, "p", &(0.0..=1.0)).unwrap_err().to_string();
        assert_eq!(within(b"0.1 0.2\n\n0.3 1.5\n", Format::Text), "p:3: coordinate 2 is 1.5, outside [0, 1]: '1.5'");
        assert_eq!(within(br#"[[0.5, -0.25]]"#, Format::Json), "p: sets[0][0][1] is -0.25, outside [0, 1]");
        let npy = encode(&[PointSet::new(2, vec![0.5, 0.5, 2.0, 0.5]).unwrap()], Format::Npy, &[]).unwrap();
        assert_eq!(within(&npy, Format::Npy), "p: element 2 (set 0, point 1, coordinate 0) is 2, outside [0, 1]");
    }

    #[test]
    fn files_of_many_blocks_read_as_one_line_after_another() {
        // 4 MB of CSV with a set column (about four blocks of the parallel reader): sets of
        // 40,000, 35,000 and 25,000 rows, the first two spanning blocks, then the same file
        // with errors placed deep in it (the header is line 1)
        let rows = [40_000, 35_000, 25_000];
        let value = |k: usize, i: usize, d: usize| ((1 + 100_000 * k + 2 * i + d) as f64).sqrt() / 1e3;
        let mut text = String::from("set,x0,x1\n");
        for (k, &m) in rows.iter().enumerate() {
            for i in 0..m {
                text.push_str(&format!("{k},{:?},{:?}\n", value(k, i, 0), value(k, i, 1)));
            }
        }
        assert!(text.len() > 3 * delimited::BLOCK, "{} bytes", text.len());
        let sets = decode(text.as_bytes(), Format::Csv, "big.csv").unwrap();
        assert_eq!(sets.iter().map(PointSet::len).collect::<Vec<_>>(), rows);
        for (k, set) in sets.iter().enumerate() {
            assert!(set.iter().enumerate().all(|(i, p)| p == [value(k, i, 0), value(k, i, 1)]), "set {k}");
        }
        let lines: Vec<&str> = text.lines().collect();
        let err = |changes: &[(usize, &'static str)]| {
            let mut edited = lines.clone();
            for &(line, row) in changes {
                edited[line - 1] = row;
            }
            decode(edited.join("\n").as_bytes(), Format::Csv, "big.csv").unwrap_err().to_string()
        };
        assert_eq!(
            err(&[(70_001, "1,0.5"), (90_001, "2,0.5,x")]),
            "big.csv:70001: 1 coordinates where earlier points have 2"
        );
        assert_eq!(
            err(&[(90_001, "2,0.5,x"), (99_000, "2,inf,0.5")]),
            "big.csv:90001: coordinate 2 is not a number: 'x'"
        );
        assert_eq!(err(&[(99_000, "z,0.5,0.5")]), "big.csv:99000: set id 'z' is not a whole number from 0 to 2^64 - 1");
        // as text, the set column gone and a comment after 50,000 rows: two sets of the
        // same coordinates in the same order
        let mut plain: Vec<String> =
            lines[1..].iter().map(|l| l.split_once(',').unwrap().1.replace(',', " ")).collect();
        plain.insert(50_000, "# a comment".into());
        let cut = decode(plain.join("\n").as_bytes(), Format::Text, "big.txt").unwrap();
        assert_eq!(cut.iter().map(PointSet::len).collect::<Vec<_>>(), [50_000, 50_000]);
        let all: Vec<f64> = sets.iter().flat_map(|s| s.as_slice().iter().copied()).collect();
        assert!(cut.iter().flat_map(|s| s.as_slice().iter().copied()).eq(all));
        // a byte that is not UTF-8 in the third block: the whole file's offset
        let mut bytes = text.into_bytes();
        let bad = 2 * delimited::BLOCK + 12_345;
        bytes[bad] = 0xFF;
        let expected = format!("big.csv: not UTF-8 text ({})", std::str::from_utf8(&bytes).unwrap_err());
        assert!(expected.contains(&format!("index {bad}")), "{expected}");
        assert_eq!(decode(&bytes, Format::Csv, "big.csv").unwrap_err().to_string(), expected);
    }

    #[test]
    fn large_files_read_in_parts_are_their_bytes() {
        // 2.5 parts of the parallel read (and a file too short for it), through `read`,
        // against the bytes the standard library reads
        let dir = std::env::temp_dir().join(format!("samplab-io-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for (points, name) in [(5 * READ_PART / 32, "big.npy"), (1000, "small.npy")] {
            let set = crate::sampler::build("random").unwrap().generate(points, 2, Seed(3)).unwrap();
            let path = dir.join(name);
            std::fs::write(&path, encode(std::slice::from_ref(&set), Format::Npy, &[]).unwrap()).unwrap();
            let len = std::fs::metadata(&path).unwrap().len();
            assert_eq!(read_regular(&path, len).unwrap(), std::fs::read(&path).unwrap(), "{name}");
            assert_eq!(read(&path, None).unwrap(), [set], "{name}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn text_separates_sets_with_hash_lines() {
        let s = decode(b"# header\n0.1 0.2\n0.3 0.4\n#\n0.5 0.6\n", Format::Text, "m").unwrap();
        assert_eq!(s.len(), 2);
        assert_eq!(s[1].point(0), &[0.5, 0.6]);
    }
}
