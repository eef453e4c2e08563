//! Numbers as text, fast and in parallel, with the bytes of the slow serial way.
//!
//! - [`push_f64`]: Rust's `{:?}` of an f64 (its shortest round-trip digits), from the
//!   digits of the Schubfach-family algorithm of the `zmij` crate (Giulietti 2020, "The
//!   Schubfach way to render doubles"), laid out as `{:?}` lays them out: the same bytes
//!   in about 60% of the standard library's time (58 ns against 92 ns a uniform value,
//!   `cargo bench -p samplab --bench text`, 2026-11-29).
//! - [`write_csv_rows`]: values as CSV rows, and [`write_json_array`]: values as the JSON
//!   array serde_json writes, each made part by part on every thread and written in order,
//!   in buffers reused from wave to wave.
//! - [`JsonObject`]: an object written field by field as serde_json writes a struct, so
//!   that a field too large to serialize on one thread can be one of the above.

use std::io::{self, Write};
use std::ops::Range;

use rayon::prelude::*;

/// Values formatted per parallel part (about 350 KiB of text).
const PART: usize = 1 << 14;

/// `x` as `format!("{x:?}")` writes it, onto `out`.
pub fn push_f64(out: &mut Vec<u8>, x: f64) {
    if !x.is_finite() || x == 0.0 {
        // NaN, inf, -inf, 0.0, -0.0: what `{:?}` writes (signs included)
        let _ = write!(out, "{x:?}");
        return;
    }
    let mut buffer = zmij::Buffer::new();
    let text = buffer.format_finite(x).as_bytes();
    let abs = x.abs();
    let fixed = (1e-4..1e16).contains(&abs);
    if fixed && !could_be_halfway(abs) {
        // zmij writes fixed notation for scientific exponents -5..=15, as `{:?}` does for
        // -4..=15 ("0.00123", "12.5", "1234.0")
        out.extend_from_slice(text);
        return;
    }
    let (digits, count, e) = decimal(if x < 0.0 { &text[1..] } else { text });
    let digits = &digits[..count];
    if halfway(abs, digits, e) {
        // two shortest candidates as near: zmij takes the even one, `{:?}` its own
        let _ = write!(out, "{x:?}");
    } else if fixed {
        out.extend_from_slice(text);
    } else {
        // d1[.d2...dk]e(e - 1), no '+' and no leading zeros in the exponent
        if x < 0.0 {
            out.push(b'-');
        }
        out.push(digits[0]);
        if count > 1 {
            out.push(b'.');
            out.extend_from_slice(&digits[1..]);
        }
        let _ = write!(out, "e{}", e - 1);
    }
}

/// The shortest digits d1 d2 ... dk (no leading or trailing zeros), their count k, and
/// the exponent e with value = 0.d1 d2 ... dk x 10^e, of one of zmij's layouts of a
/// positive number: "123.45", "0.00123", "1234.0", "1.5e+20", "5e-7".
fn decimal(text: &[u8]) -> ([u8; 32], usize, i32) {
    let (mantissa, exp) = match text.iter().position(|&c| c == b'e') {
        Some(i) => (&text[..i], parse_exponent(&text[i + 1..])),
        None => (text, 0),
    };
    let mut digits = [0u8; 32];
    let (mut count, mut point) = (0, None);
    for &c in mantissa {
        if c == b'.' {
            point = Some(count as i32);
        } else if count > 0 || c != b'0' {
            digits[count] = c;
            count += 1;
        } else if point.is_some() {
            // a zero after "0." moves the first digit one place to the right
            point = point.map(|p| p - 1);
        }
    }
    let before_point = point.unwrap_or(count as i32);
    while count > 1 && digits[count - 1] == b'0' {
        count -= 1;
    }
    (digits, count, before_point + exp)
}

/// M and E with `abs` = M 2^E, M odd.
fn odd_binary(abs: f64) -> (u64, i32) {
    let (biased, fraction) = ((abs.to_bits() >> 52) as i32, abs.to_bits() & ((1 << 52) - 1));
    let (m, exp2) = if biased == 0 { (fraction, -1074) } else { (fraction | 1 << 52, biased - 1075) };
    (m >> m.trailing_zeros(), exp2 + m.trailing_zeros() as i32)
}

/// False when `abs` cannot be a tie of [`halfway`]: its E is outside -27..=27.
fn could_be_halfway(abs: f64) -> bool {
    odd_binary(abs).1.abs() <= 27
}

/// Whether `abs` is exactly halfway between 0.`digits` x 10^`e` and the decimal one unit
/// of its last digit below or above: a tie between two shortest candidates. With k digits,
/// such a midpoint is (10 D +- 5) x 10^p, p = e - k - 1, an odd integer times 10^p; `abs`
/// is M 2^E with M odd, so they are equal only if E = p and M 5^-p = 10 D +- 5 (p < 0) or
/// M = (10 D +- 5) 5^p (p >= 0), which exact integers decide when |p| <= 27 (else the
/// sides' sizes differ).
fn halfway(abs: f64, digits: &[u8], e: i32) -> bool {
    let (m, exp2) = odd_binary(abs);
    let p = e - digits.len() as i32 - 1;
    if exp2 != p || p.abs() > 27 {
        return false;
    }
    let d = digits.iter().fold(0u128, |v, &c| 10 * v + u128::from(c - b'0'));
    let (five, m) = (5u128.pow(p.unsigned_abs()), u128::from(m));
    [10 * d + 5, 10 * d - 5]
        .into_iter()
        .any(|mid| if p < 0 { m.checked_mul(five) == Some(mid) } else { mid.checked_mul(five) == Some(m) })
}

/// The exponent after zmij's `e`: an optional sign and decimal digits.
fn parse_exponent(text: &[u8]) -> i32 {
    let (negative, digits) = match text.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, text),
    };
    let value = digits.iter().fold(0i32, |v, &c| 10 * v + i32::from(c - b'0'));
    if negative { -value } else { value }
}

/// Fill the text of `items` items part by part ([`PART`] items, rounded to whole groups
/// of `group`) on every thread, `fill(range, buffer)` making a part's text, and write the
/// parts in order, `between` before every part but the first; a wave of parts at a time in
/// buffers reused from wave to wave (a fresh buffer costs its page faults).
fn write_parts(
    w: &mut dyn Write,
    items: usize,
    group: usize,
    between: &[u8],
    fill: impl Fn(Range<usize>, &mut Vec<u8>) + Sync,
) -> io::Result<()> {
    let part = (PART / group.max(1)).max(1) * group.max(1);
    let parts = items.div_ceil(part);
    let wave = (4 * rayon::current_num_threads()).clamp(1, parts.max(1));
    let mut buffers = vec![Vec::new(); wave];
    for first in (0..parts).step_by(wave) {
        let here = wave.min(parts - first);
        buffers[..here].par_iter_mut().enumerate().for_each(|(i, buffer)| {
            buffer.clear();
            let start = (first + i) * part;
            fill(start..(start + part).min(items), buffer);
        });
        for (i, buffer) in buffers[..here].iter().enumerate() {
            if first + i > 0 {
                w.write_all(between)?;
            }
            w.write_all(buffer)?;
        }
    }
    Ok(())
}

/// `values` as CSV rows of `row` values each (the last may be shorter), every value as
/// [`push_f64`] writes it, each row ended by a newline.
///
/// # Errors
/// The writer's.
pub fn write_csv_rows(w: &mut dyn Write, values: &[f64], row: usize) -> io::Result<()> {
    let row = row.max(1);
    write_parts(w, values.len(), row, b"", |range, out| {
        values[range].chunks(row).for_each(|line| push_line(out, line, b','));
    })
}

/// `values` as [`push_f64`] writes them, `separator` between two, and a newline.
pub(crate) fn push_line(out: &mut Vec<u8>, values: &[f64], separator: u8) {
    for (i, &x) in values.iter().enumerate() {
        if i > 0 {
            out.push(separator);
        }
        push_f64(out, x);
    }
    out.push(b'\n');
}

/// `values` as the JSON array serde_json writes for them (`[` and `]`, no spaces,
/// non-finite values as `null`).
///
/// # Errors
/// The writer's.
pub fn write_json_array(w: &mut dyn Write, values: &[f64]) -> io::Result<()> {
    w.write_all(b"[")?;
    write_parts(w, values.len(), 1, b",", |range, out| {
        for (i, &x) in values[range].iter().enumerate() {
            if i > 0 {
                out.push(b',');
            }
            if x.is_finite() {
                out.extend_from_slice(zmij::Buffer::new().format_finite(x).as_bytes());
            } else {
                out.extend_from_slice(b"null");
            }
        }
    })?;
    w.write_all(b"]")
}

/// A JSON object written field by field, with the bytes serde_json writes for a struct
/// with these fields in this order (compact: no spaces).
pub struct JsonObject<'w> {
    w: &'w mut dyn Write,
    fields: usize,
}

impl<'w> JsonObject<'w> {
    /// Starts an object on `w`.
    ///
    /// # Errors
    /// The writer's.
    pub fn new(w: &'w mut dyn Write) -> io::Result<JsonObject<'w>> {
        w.write_all(b"{")?;
        Ok(JsonObject { w, fields: 0 })
    }

    /// The next field, whose value `write` writes (as JSON).
    ///
    /// # Errors
    /// The writer's, or `write`'s.
    pub fn field_with(&mut self, key: &str, write: impl FnOnce(&mut dyn Write) -> io::Result<()>) -> io::Result<()> {
        if self.fields > 0 {
            self.w.write_all(b",")?;
        }
        self.fields += 1;
        serde_json::to_writer(&mut *self.w, key)?;
        self.w.write_all(b":")?;
        write(self.w)
    }

    /// The next field, `value` serialized by serde_json.
    ///
    /// # Errors
    /// The writer's, or serde's.
    pub fn field(&mut self, key: &str, value: &impl serde::Serialize) -> io::Result<()> {
        self.field_with(key, |w| Ok(serde_json::to_writer(w, value)?))
    }

    /// Ends the object.
    ///
    /// # Errors
    /// The writer's.
    pub fn end(self) -> io::Result<()> {
        self.w.write_all(b"}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand_core::Rng as _;
    use rand_core::SeedableRng as _;

    /// Every kind of f64 `{:?}` lays out differently, and the neighbours of its switches.
    fn edge_cases() -> Vec<f64> {
        let mut xs = vec![
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            5e-324,
            1.0,
            0.1,
            0.5,
            123.456,
            1e15,
            1234567890123456.0,
            9007199254740993.0,
        ];
        for p in -330..=310 {
            let x = format!("1e{p}").parse::<f64>().unwrap();
            for y in
                [x, f64::from_bits(x.to_bits() + 1), f64::from_bits(x.to_bits().saturating_sub(1)), 1.5 * x, 3.0 * x]
            {
                xs.extend([y, -y]);
            }
        }
        for k in -1074..=1023 {
            xs.push(2f64.powi(k));
        }
        xs
    }

    #[test]
    fn numbers_have_the_bytes_of_debug() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(7);
        let mut xs = edge_cases();
        // any bits, uniform in [0, 1) (the points of most files), few decimals
        xs.extend((0..400_000).map(|_| f64::from_bits(rng.next_u64())));
        xs.extend((0..400_000).map(|_| (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64));
        xs.extend((0..100_000).map(|_| (rng.next_u64() % 100_000) as f64 / 1000.0));
        // short binary fractions, whose exact decimals are short: ties between two
        // shortest candidates
        xs.extend(
            (0..200_000).map(|_| (rng.next_u64() % (1 << 24)) as f64 * 2f64.powi(-((rng.next_u64() % 90) as i32))),
        );
        for x in xs {
            let mut out = Vec::new();
            push_f64(&mut out, x);
            assert_eq!(String::from_utf8(out).unwrap(), format!("{x:?}"), "bits {:#x}", x.to_bits());
        }
    }

    #[test]
    fn parts_in_parallel_are_the_lines_one_after_another() {
        let mut rng = rand_pcg::Pcg64::seed_from_u64(3);
        // more than a wave of parts, a short last row, and values of every layout
        let mut values: Vec<f64> = (0..300_001).map(|_| f64::from_bits(rng.next_u64() >> 2)).collect();
        values[17] = f64::NAN;
        values[70_000] = f64::NEG_INFINITY;
        values[200_000] = -0.0;
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (csv, json) = pool.install(|| {
                let (mut csv, mut json) = (Vec::new(), Vec::new());
                write_csv_rows(&mut csv, &values, 1000).unwrap();
                write_json_array(&mut json, &values).unwrap();
                (csv, json)
            });
            let want: String = values
                .chunks(1000)
                .map(|row| row.iter().map(|x| format!("{x:?}")).collect::<Vec<_>>().join(",") + "\n")
                .collect();
            assert!(csv == want.as_bytes(), "CSV on {threads} threads");
            assert!(json == serde_json::to_vec(&values).unwrap(), "JSON on {threads} threads");
        }
        let mut empty = Vec::new();
        write_json_array(&mut empty, &[]).unwrap();
        assert_eq!(empty, b"[]");
    }

    #[test]
    fn objects_have_the_bytes_of_serde() {
        #[derive(serde::Serialize)]
        struct Reference<'a> {
            dims: usize,
            name: &'a str,
            grid: &'a [f64],
            nested: std::collections::BTreeMap<&'a str, Vec<f64>>,
        }
        let grid = [0.25, f64::NAN, 1e300, -3.0];
        let nested: std::collections::BTreeMap<_, _> = [("a", vec![1.0]), ("b\"", vec![])].into_iter().collect();
        let mut ours = Vec::new();
        let mut object = JsonObject::new(&mut ours).unwrap();
        object.field("dims", &2).unwrap();
        object.field("name", &"x \"y\"\n").unwrap();
        object.field_with("grid", |w| write_json_array(w, &grid)).unwrap();
        object.field("nested", &nested).unwrap();
        object.end().unwrap();
        let reference = Reference { dims: 2, name: "x \"y\"\n", grid: &grid, nested };
        assert_eq!(String::from_utf8(ours).unwrap(), serde_json::to_string(&reference).unwrap());
    }
}
