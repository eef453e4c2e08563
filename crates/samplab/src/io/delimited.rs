//! Text and CSV point files read in parallel. The file is cut into blocks of whole lines;
//! each block's numbers are parsed on a thread of its own into a run of coordinates and
//! the few events whose meaning depends on the lines before them (a comment, a set id, a
//! change in the count of coordinates, the block's first error), each at its place in the
//! run. One pass over the blocks' events in order then does what a reader of one line
//! after another does, so the sets and the first error (its line and message) are the
//! same whatever the blocks and threads.

use std::ops::RangeInclusive;

use rayon::prelude::*;

use super::refuse;
use crate::error::{Error, Result, excerpt};
use crate::points::PointSet;

/// Bytes per block: each ends at the first newline from this many bytes on.
pub(super) const BLOCK: usize = 1 << 20;

/// What a point row means for the rows after it, met in the order of the lines.
enum Event<'a> {
    /// A comment line: the set so far ends.
    Comment,
    /// A row of set `id` (the `set` column): the block's first such row, or a change.
    Set(&'a str),
    /// A row of this many coordinates, on this line: the block's first row, or a change.
    Count(usize, usize),
    /// The block's first error: its line and what is wrong.
    Bad(usize, String),
}

/// A block's coordinates and its events, each at the count of coordinates before it.
struct Block<'a> {
    values: Vec<f64>,
    events: Vec<(usize, Event<'a>)>,
}

/// The sets of a text (`csv` false) or CSV file, every coordinate in `domain`; errors name
/// `name` and the line.
pub(super) fn decode(bytes: &[u8], csv: bool, name: &str, domain: &RangeInclusive<f64>) -> Result<Vec<PointSet>> {
    let at = |line: usize, reason: String| Error::Parse { location: format!("{name}:{line}"), reason };
    // blocks of whole lines (a newline byte is never inside a UTF-8 character), each
    // checked to be UTF-8 on its own; a bad one's error is the whole file's
    let mut cuts = vec![0];
    let mut end = 0;
    while end < bytes.len() {
        let from = (end + BLOCK).min(bytes.len());
        end = bytes[from..].iter().position(|&b| b == b'\n').map_or(bytes.len(), |p| from + p + 1);
        cuts.push(end);
    }
    let blocks: Vec<&str> = cuts
        .par_windows(2)
        .map(|w| std::str::from_utf8(&bytes[w[0]..w[1]]))
        .collect::<std::result::Result<_, _>>()
        .map_err(|in_block| {
            let e = std::str::from_utf8(bytes).err().unwrap_or(in_block);
            Error::Parse { location: name.into(), reason: format!("not UTF-8 text ({e})") }
        })?;
    let (header, set_column) =
        if csv { header(&blocks).map_err(|(line, reason)| at(line, reason))? } else { (None, false) };
    let newlines: Vec<usize> = blocks.par_iter().map(|b| b.bytes().filter(|&c| c == b'\n').count()).collect();
    let parsed: Vec<Block> = blocks
        .par_iter()
        .zip(starts(1, newlines))
        .map(|(block, first)| parse(block, first, (csv, set_column, header), domain))
        .collect();
    // the events in order, as one line after another: the sets' ranges in the blocks'
    // coordinates one after another
    let offsets = starts(0, parsed.iter().map(|b| b.values.len()));
    let mut ranges: Vec<std::ops::Range<usize>> = Vec::new();
    let (mut start, mut dims, mut current_set): (usize, usize, Option<&str>) = (0, 0, None);
    let finish = |start: &mut usize, upto: usize, ranges: &mut Vec<std::ops::Range<usize>>| {
        if upto > *start {
            ranges.push(*start..upto);
        }
        *start = upto;
    };
    for (block, &offset) in parsed.iter().zip(&offsets) {
        for (upto, event) in &block.events {
            let upto = offset + upto;
            match *event {
                Event::Comment => finish(&mut start, upto, &mut ranges),
                Event::Set(id) => {
                    if current_set != Some(id) {
                        finish(&mut start, upto, &mut ranges);
                        current_set = Some(id);
                    }
                }
                Event::Count(count, line) => {
                    if dims == 0 {
                        dims = count;
                        if dims == 0 {
                            return Err(at(line, "a row with no coordinates".into()));
                        }
                    } else if count != dims {
                        return Err(at(line, format!("{count} coordinates where earlier points have {dims}")));
                    }
                }
                Event::Bad(line, ref reason) => return Err(at(line, reason.clone())),
            }
        }
    }
    finish(&mut start, parsed.iter().map(|b| b.values.len()).sum(), &mut ranges);
    // each set's coordinates copied from the blocks in parallel (zeroed memory, its pages
    // faulted in by the copies)
    let mut sets: Vec<Vec<f64>> = ranges.iter().map(|r| vec![0.0; r.len()]).collect();
    let mut pieces = Vec::new();
    for (set, range) in sets.iter_mut().zip(&ranges) {
        let mut rest = set.as_mut_slice();
        for (block, &offset) in parsed.iter().zip(&offsets) {
            let (from, to) = (range.start.max(offset), range.end.min(offset + block.values.len()));
            if from < to {
                let (piece, tail) = rest.split_at_mut(to - from);
                pieces.push((piece, &block.values[from - offset..to - offset]));
                rest = tail;
            }
        }
    }
    pieces.into_par_iter().for_each(|(to, from)| to.copy_from_slice(from));
    Ok(sets.into_iter().map(|values| PointSet::from_raw(dims, values)).collect())
}

/// The running sums of `counts` from `first`, each taken before its count is added (a
/// block's first line, its first coordinate).
fn starts(first: usize, counts: impl IntoIterator<Item = usize>) -> Vec<usize> {
    counts.into_iter().scan(first, |sum, n| Some(std::mem::replace(sum, *sum + n))).collect()
}

/// A CSV file's header, read from its first line that is neither blank nor a comment: its
/// line when it is a row of names (none of them a number) and whether it starts with a
/// `set` column; no header when that line is a row of numbers. A row that mixes the two
/// is neither: its line and why.
fn header(blocks: &[&str]) -> std::result::Result<(Option<usize>, bool), (usize, String)> {
    let Some((i, line)) = blocks
        .iter()
        .flat_map(|b| b.lines())
        .map(str::trim)
        .enumerate()
        .find(|(_, l)| !l.is_empty() && !l.starts_with('#'))
    else {
        return Ok((None, false));
    };
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    let numbers = fields.iter().filter(|f| f.parse::<f64>().is_ok()).count();
    if numbers == 0 {
        return Ok((Some(i + 1), fields.first().is_some_and(|f| f.eq_ignore_ascii_case("set"))));
    }
    if numbers < fields.len() {
        let name = fields.iter().find(|f| f.parse::<f64>().is_err()).copied().unwrap_or_default();
        return Err((
            i + 1,
            format!("the first row mixes numbers with {}: neither a header (names only) nor a point", excerpt(name)),
        ));
    }
    Ok((None, false))
}

/// One block of lines, its first numbered `first`: its coordinates and events (up to its
/// first error). `(csv, set_column, header)`: the format, whether rows start with a set
/// id, and the header's line (skipped).
fn parse<'a>(
    block: &'a str,
    first: usize,
    (csv, set_column, header): (bool, bool, Option<usize>),
    domain: &RangeInclusive<f64>,
) -> Block<'a> {
    let (mut values, mut events) = (Vec::new(), Vec::new());
    let (mut last_set, mut last_count) = (None, None);
    let mut fields: Vec<&str> = Vec::new();
    for (line, raw) in (first..).zip(block.lines()) {
        let row = raw.trim();
        if row.is_empty() || Some(line) == header {
            continue;
        }
        if row.starts_with('#') {
            events.push((values.len(), Event::Comment));
            continue;
        }
        fields.clear();
        if csv {
            fields.extend(row.split(',').map(str::trim));
        } else {
            fields.extend(row.split_whitespace());
        }
        let (id, coords) = if set_column { (Some(fields[0]), &fields[1..]) } else { (None, &fields[..]) };
        if let Some(id) = id {
            if id.parse::<u64>().is_err() {
                let reason = format!("set id {} is not a whole number from 0 to 2^64 - 1", excerpt(id));
                events.push((values.len(), Event::Bad(line, reason)));
                break;
            }
            if last_set != Some(id) {
                events.push((values.len(), Event::Set(id)));
                last_set = Some(id);
            }
        }
        if last_count != Some(coords.len()) {
            events.push((values.len(), Event::Count(coords.len(), line)));
            last_count = Some(coords.len());
        }
        let bad = coords.iter().enumerate().find_map(|(d, f)| match f.parse::<f64>() {
            Err(_) => Some(format!("coordinate {} is not a number: {}", d + 1, excerpt(f))),
            Ok(x) => match refuse(x, domain) {
                Some(why) => Some(format!("coordinate {} {why}: {}", d + 1, excerpt(f))),
                None => {
                    values.push(x);
                    None
                }
            },
        });
        if let Some(reason) = bad {
            events.push((values.len(), Event::Bad(line, reason)));
            break;
        }
    }
    Block { values, events }
}
