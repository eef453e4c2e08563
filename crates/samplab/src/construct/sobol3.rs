//! Sobol's construction carried to GF(3), from a table of polynomials and initial numbers in
//! the format Ostromoukhov, Bonneel, Coeurjolly & Iehl (2024) publish their quad-optimized
//! base-3 sequences in (`initIrreducibleGF3.dat`; samplab ships no such table: give yours as
//! `net:directions=FILE,base=3`). `#` starts a comment; an optional title line `d s a m_i`;
//! then one line `i s a m_1 .. m_s` per dimension, in order: i the polynomial's number in
//! the authors' list (not read), s its degree, a its coefficients as a base-3 number (digit
//! k the coefficient of x^k; the polynomial monic, digit s = 1), m_k the initial numbers,
//! m_k below 3^k with its last base-3 digit not 0.
//!
//! Dimension j with polynomial x^s + p_{s-1} x^{s-1} + ... + p_0 continues its m_k by Sobol's
//! recurrence in base 3, digit by digit without carries (the authors' `generate_mkGF3`):
//! m_k = m_{k-s} + sum_{i=1..s} 3^i (-p_{s-i}) m_{k-i}  (mod 3 in every digit).
//! Column k of the generating matrix holds the digits of m_{k+1}: row r the digit of weight
//! 3^(k-r), so row 0 is the most significant and the diagonal the last digit (never 0).
//! The authors' code stops at 10 columns, 3^10 = 59,049 points; the recurrence goes on as
//! far as the caller asks, and what the authors claim of their table (each pair of
//! dimensions (2k, 2k + 1) a (0, m, 2)-net for m up to 10) says nothing past their 10.

/// Largest degree a line may give.
const MAX_DEGREE: u64 = 32;

/// The generating matrices of a table's dimensions, `cols` columns (and rows) each: entry
/// `[j][k][r]` is the digit in row r, column k of dimension j.
///
/// # Errors
/// `(line, reason)` (the line 1-based): a token that is not a whole number, fewer than four
/// numbers, a degree outside 1..=32, a polynomial that is not monic of that degree, the wrong
/// count of initial numbers, or an m_k not below 3^k or whose last digit is 0.
pub fn matrices(text: &str, cols: usize) -> Result<Vec<Vec<Vec<u8>>>, (usize, String)> {
    let mut dims = Vec::new();
    for line in super::joe_kuo::numbered_lines(text) {
        let (lineno, f) = line?;
        if f.len() < 4 {
            return Err((lineno, format!("expected i s a m_1 .. m_s, got {} numbers", f.len())));
        }
        let (s, a) = (f[1], f[2]);
        if !(1..=MAX_DEGREE).contains(&s) {
            return Err((lineno, format!("degree s = {s} is not in 1..={MAX_DEGREE}")));
        }
        let s = s as usize;
        // p_0 .. p_s, the polynomial's coefficients
        let p: Vec<u8> = (0..=s as u32).map(|k| (u128::from(a) / 3u128.pow(k) % 3) as u8).collect();
        if u128::from(a) >= 3u128.pow(s as u32 + 1) || p[s] != 1 {
            return Err((
                lineno,
                format!("a = {a} is not a monic polynomial of degree {s} (its base-3 digit {s} must be 1, none above)"),
            ));
        }
        if f.len() != 3 + s {
            return Err((lineno, format!("degree {s} needs {s} initial numbers m_1 .. m_{s}, got {}", f.len() - 3)));
        }
        // m_k's digits, least significant first (m[k - 1] is m_k)
        let mut m: Vec<Vec<u8>> = Vec::with_capacity(cols.max(s));
        for (k, &mk) in (1u32..).zip(&f[3..]) {
            if u128::from(mk) >= 3u128.pow(k) || mk % 3 == 0 {
                return Err((lineno, format!("m_{k} = {mk} must be below 3^{k} with its last base-3 digit not 0")));
            }
            m.push((0..k).map(|d| (u128::from(mk) / 3u128.pow(d) % 3) as u8).collect());
        }
        for k in s + 1..=cols {
            let mut next = m[k - s - 1].clone();
            next.resize(k, 0);
            for i in 1..=s {
                let c = (3 - p[s - i]) % 3;
                for (d, &digit) in m[k - i - 1].iter().enumerate() {
                    next[d + i] = (next[d + i] + c * digit) % 3;
                }
            }
            m.push(next);
        }
        // column k: row r is the digit of weight 3^(k - r)
        dims.push(
            m[..cols]
                .iter()
                .enumerate()
                .map(|(k, digits)| (0..cols).map(|r| if r <= k { digits[k - r] } else { 0 }).collect())
                .collect(),
        );
    }
    Ok(dims)
}
