//! Sobol' direction numbers in Joe & Kuo's file format (Joe & Kuo 2008, the files
//! `new-joe-kuo-6.21201` and its kin; `#` starts a comment, as in samplab's other formats):
//! a line `d s a m_1 ... m_s` per dimension d from 2 on, where s is the degree of the
//! dimension's primitive polynomial, a its inner coefficients as a number (bit s-1-i is
//! a_i), and m_k the initial direction integers (odd, below 2^k).
//! Dimension 1 is van der Corput's (every m_k = 1). Bonneel et al. (2025) publish their
//! OneTwo table with that dimension written out as a first line `0 0 0` and the rest
//! numbered from 1, and Paulin et al. (2021) their Cascaded Sobol' table numbered from 1
//! with it left out; the reader takes all three. The remaining m_k follow Bratley &
//! Fox's recurrence (Joe & Kuo 2008, section 2):
//! m_k = 2 a_1 m_{k-1} ^ 4 a_2 m_{k-2} ^ ... ^ 2^{s-1} a_{s-1} m_{k-s+1} ^ 2^s m_{k-s} ^ m_{k-s}.
//!
//! One reader for the table baked in at build time (`build.rs` includes this file) and for
//! any table a user brings (`net:directions=FILE`). It imports nothing, so `build.rs` can.

/// The direction numbers of each dimension, dimension 0 (van der Corput's) first: entry
/// `[j][k]` is v_k = m_{k+1} 2^(31-k), column k of dimension j's generating matrix with row 0
/// the most significant bit. A malformed line is an error with its line number (1-based)
/// and the reason in words.
///
/// # Errors
/// `(line, reason)`: a token that is not a whole number, a dimension out of sequence (from
/// 2, or from 1, after a first line `0 0 0` or not), a
/// degree outside 1..=32 or a coefficient number of more than s - 1 bits, the wrong count
/// of initial numbers, or an m_k that is even or not below 2^k.
pub fn directions(text: &str) -> Result<Vec<[u32; 32]>, (usize, String)> {
    let mut table: Vec<[u32; 32]> = vec![std::array::from_fn(|k| 1u32 << (31 - k))];
    // the number of the first dimension after van der Corput's: 2, or 1 (after `0 0 0` or not)
    let mut first = 2u64;
    for line in numbered_lines(text) {
        let (lineno, f) = line?;
        if f == [0, 0, 0] && table.len() == 1 && first == 2 {
            // van der Corput's dimension written out (the OneTwo table's first line)
            first = 1;
            continue;
        }
        if table.len() == 1 && first == 2 && f.first() == Some(&1) {
            // numbered from 1 with van der Corput's dimension left out (Paulin et al.'s table)
            first = 1;
        }
        let want = table.len() as u64 + first - 1;
        if f.len() < 4 {
            return Err((lineno, format!("expected d s a m_1 .. m_s, got {} numbers", f.len())));
        }
        let (d, s, a) = (f[0], f[1], f[2]);
        if d != want {
            return Err((
                lineno,
                format!("dimension {d} where {want} comes next (the lines start at {first}, in order)"),
            ));
        }
        if !(1..=32).contains(&s) {
            return Err((lineno, format!("degree s = {s} is not in 1..=32")));
        }
        let s = s as usize;
        if a >> (s - 1) != 0 {
            return Err((lineno, format!("a = {a} has more than s - 1 = {} bits", s - 1)));
        }
        if f.len() != 3 + s {
            return Err((lineno, format!("degree {s} needs {s} initial numbers m_1 .. m_{s}, got {}", f.len() - 3)));
        }
        let mut m = [0u64; 32];
        for (k, &mk) in f[3..].iter().enumerate() {
            // m_{k+1} is odd and below 2^(k+1)
            if mk % 2 == 0 || mk >> (k + 1) != 0 {
                return Err((lineno, format!("m_{} = {mk} must be odd and below 2^{}", k + 1, k + 1)));
            }
        }
        m[..s].copy_from_slice(&f[3..]);
        for k in s..32 {
            let mut v = m[k - s] ^ (m[k - s] << s);
            for i in 1..s {
                if (a >> (s - 1 - i)) & 1 == 1 {
                    v ^= m[k - i] << i;
                }
            }
            m[k] = v;
        }
        table.push(std::array::from_fn(|k| (m[k] << (31 - k)) as u32));
    }
    Ok(table)
}

/// The lines of a direction table that hold numbers, as `(line number, numbers)`, 1-based:
/// `#` starts a comment, blank lines are skipped, and so is a title line of words (`d s a
/// m_i`) before the first line of numbers. The base-3 reader (`sobol3`) shares it.
///
/// # Errors
/// `(line, reason)` for a token that is not a whole number.
pub fn numbered_lines(text: &str) -> impl Iterator<Item = Result<(usize, Vec<u64>), (usize, String)>> + '_ {
    let mut title_allowed = true;
    text.lines().enumerate().filter_map(move |(i, line)| {
        let line = line.split('#').next().unwrap_or_default().trim();
        if line.is_empty() {
            return None;
        }
        let tokens: Vec<&str> = line.split_whitespace().collect();
        let allowed = std::mem::replace(&mut title_allowed, false);
        match tokens.iter().map(|t| t.parse::<u64>().map_err(|_| *t)).collect::<Result<Vec<u64>, &str>>() {
            Ok(f) => Some(Ok((i + 1, f))),
            Err(_) if allowed && tokens[0] == "d" => None,
            Err(t) => Some(Err((i + 1, format!("'{}' is not a whole number", t.chars().take(24).collect::<String>())))),
        }
    })
}
