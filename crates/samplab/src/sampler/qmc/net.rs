//! Digital nets and sequences in a prime base b (Niederreiter 1992, "Random Number Generation
//! and Quasi-Monte Carlo Methods", section 4.3): coordinate j of point i has the base-b
//! digits y = C_j a (mod b), where a holds the digits of i (least significant first) and row
//! r of y is the digit of weight b^-(r+1). Points come in natural order, so every prefix of
//! b^m points is the net of the first m columns.
//!
//! The generating matrices C_j:
//! - from a file (`net:matrices=FILE`), in the LDData "dnet" format (see [`Matrices::parse`]);
//!   by default the Sobol' matrices of Joe & Kuo (2008);
//! - from a table of Sobol' direction numbers (`net:directions=FILE`): in base 2 in Joe &
//!   Kuo's format ([`crate::construct::joe_kuo`]; the OneTwo table of Bonneel et al. 2025
//!   reads as it is published), in base 3 (`base=3`) in the format of the quad-optimized
//!   sequences of Ostromoukhov et al. 2024 ([`crate::construct::sobol3`]); samplab ships
//!   neither authors' table (nothing taken from another repository is committed here);
//! - Faure's (Faure 1982): base p the smallest prime >= d, C_j = P^j with P the Pascal
//!   matrix mod p, entry (r, k) = binom(k, r) j^(k-r); a (0, s)-sequence in base p;
//! - Niederreiter's (Niederreiter 1988), as Bratley, Fox & Niederreiter (1992, section 3.3)
//!   compute them: dimension j takes the j-th monic irreducible polynomial p_j over F_b
//!   (by degree, then by coefficients), and row r = Q e_j + u of C_j holds the terms
//!   u, u+1, ... of a linear recurring sequence whose characteristic polynomial is
//!   p_j^(Q+1); a (t, s)-sequence with t = sum_j (deg p_j - 1);
//! - the SZ matrices (Ahmed et al. 2025, [`crate::construct::sz`]): four binary matrices
//!   that are a (0, 4)-sequence in base 4;
//! - the xi-sequence's (Ahmed et al. 2023, [`crate::construct::xi`]): a 2D (0, 2)-sequence.
//!
//! Randomizations, each on the digits, seeded per dimension (so random access equals the
//! batch):
//! - `.xor`: a digital shift, y_r + e_r mod b with uniform digits e_r (an XOR in base 2);
//! - `.lms`: Matousek's (1998) linear matrix scrambling, C_j replaced by L_j C_j with L_j
//!   lower triangular (uniform non-zero diagonal, uniform below it), then a digital shift;
//! - `.owen`: Owen's (1995) nested scrambling: the permutation of digit r depends on digits
//!   0..r, hashed (Burley 2020 in base 2; in base b the random affine digit maps of
//!   [`crate::construct::scramble`]'s `OwenDigits`, shared with Halton);
//! - `.shift`: a Cranley-Patterson shift mod 1 (not a net any more).
//!
//! The first three keep every (t, m, s)-net property of the construction.

use std::ops::RangeInclusive;
use std::sync::Arc;

use crate::numeric::BELOW_ONE;
use crate::sampler::randomize::{randomized_families, shift};
use crate::construct::Counts;
use crate::sampler::registry::SamplerEntry;
use crate::construct::scramble::{OwenDigits, Randomization, hash2, owen_scramble_u32};
use crate::sampler::{Access, Prepared, Construction, Shape};
use crate::error::{Error, Result};
use crate::progress::Progress;
use crate::seed::{Seed, below};
use crate::spec::{Default, Kind, ParamSpec, Params};

/// Generating matrices of a digital net in a prime base: `cols` columns (input digits, so
/// b^cols points) and `rows` rows (output digits) per dimension.
#[derive(Debug, Clone, PartialEq)]
pub struct Matrices {
    base: u32,
    dims: usize,
    cols: usize,
    rows: usize,
    /// Digit (row r, column k) of dimension d at `(d * cols + k) * rows + r`.
    digits: Vec<u8>,
}

/// The largest base: digits are bytes.
const MAX_BASE: u32 = 251;

/// The output digits kept in base b: the most with b^P <= 2^63 (every b^P-th of the unit
/// interval, at least 53 bits), 64 in base 2.
fn precision(base: u32) -> usize {
    if base == 2 {
        return 64;
    }
    let mut p = 0;
    let mut power = 1u128;
    while power * u128::from(base) <= 1 << 63 {
        power *= u128::from(base);
        p += 1;
    }
    p
}

/// The columns needed for 2^32 points in base b (the most a set can have).
fn columns_for_all_sets(base: u32) -> usize {
    let mut cols = 0;
    let mut power = 1u128;
    while power < 1 << 32 {
        power *= u128::from(base);
        cols += 1;
    }
    cols
}

fn is_prime(b: u32) -> bool {
    b >= 2 && (2..b).take_while(|k| k * k <= b).all(|k| !b.is_multiple_of(k))
}

impl Matrices {
    /// Matrices from their digits (`(d * cols + k) * rows + r`).
    ///
    /// # Errors
    /// A base that is not a prime below 256, a digit not below the base, or sizes that do
    /// not match.
    pub fn new(base: u32, dims: usize, cols: usize, rows: usize, digits: Vec<u8>) -> Result<Matrices> {
        let invalid = |reason: String| Err(Error::Param { owner: "net".into(), param: "matrices".into(), reason });
        if !is_prime(base) || base > MAX_BASE {
            return invalid(format!("base {base} is not a prime up to {MAX_BASE}"));
        }
        if dims == 0 || cols == 0 || rows == 0 || digits.len() != dims * cols * rows {
            return invalid(format!("{} digits for {dims} dimensions x {cols} columns x {rows} rows", digits.len()));
        }
        if let Some(d) = digits.iter().find(|&&d| u32::from(d) >= base) {
            return invalid(format!("digit {d} is not below the base {base}"));
        }
        Ok(Matrices { base, dims, cols, rows: rows.min(precision(base)), digits: truncate_rows(digits, rows, base) })
    }

    /// The base.
    pub fn base(&self) -> u32 {
        self.base
    }

    /// How many dimensions the matrices have.
    pub fn dims(&self) -> usize {
        self.dims
    }

    /// How many columns: the net has up to base^cols points.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// How many rows (output digits) each column has.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Digit (row `r`, column `k`) of dimension `d`'s matrix.
    pub fn digit(&self, d: usize, r: usize, k: usize) -> u32 {
        u32::from(self.digits[(d * self.cols + k) * self.rows + r])
    }

    /// The Sobol' matrices of Joe & Kuo (2008), 32 x 32 bits, for `dims` dimensions.
    fn sobol(dims: usize) -> Matrices {
        Matrices::from_directions((0..dims).map(crate::construct::sobol::direction_numbers))
    }

    /// The 32 x 32-bit Sobol' matrices of the direction numbers of each dimension (column k
    /// of a dimension the k-th number, row 0 its most significant bit).
    fn from_directions(directions: impl Iterator<Item = [u32; 32]>) -> Matrices {
        let digits: Vec<u8> = directions.flatten().flat_map(|v| (0..32).map(move |r| ((v >> (31 - r)) & 1) as u8)).collect();
        Matrices { base: 2, dims: digits.len() / (32 * 32), cols: 32, rows: 32, digits }
    }

    /// The first `cols` columns of each dimension: the net of base^cols points.
    fn first_columns(self, cols: usize) -> Matrices {
        let digits = self.digits.chunks_exact(self.cols * self.rows).flat_map(|d| &d[..cols * self.rows]).copied().collect();
        Matrices { cols, digits, ..self }
    }

    /// Faure's matrices for `dims` dimensions (module docs): base p the smallest prime >= d,
    /// enough columns for 2^32 points.
    pub fn faure(dims: usize) -> Matrices {
        let base = faure_base(dims);
        let b = base as usize;
        let cols = columns_for_all_sets(base);
        // binom(k, r) mod p by Pascal's rule
        let mut binom = vec![vec![0usize; cols]; cols];
        for k in 0..cols {
            binom[k][0] = 1;
            for r in 1..=k {
                binom[k][r] = (binom[k - 1][r - 1] + if r < k { binom[k - 1][r] } else { 0 }) % b;
            }
        }
        let mut digits = vec![0u8; dims * cols * cols];
        for j in 0..dims {
            for k in 0..cols {
                let mut power = 1; // j^(k - r), from r = k down
                for r in (0..=k).rev() {
                    digits[(j * cols + k) * cols + r] = (binom[k][r] * power % b) as u8;
                    power = power * (j % b) % b;
                }
            }
        }
        Matrices { base, dims, cols, rows: cols, digits }
    }

    /// Niederreiter's matrices in base `base` for `dims` dimensions (module docs), enough
    /// columns for 2^32 points and every output digit kept.
    ///
    /// # Errors
    /// A base that is not a prime up to 251.
    pub fn niederreiter(base: u32, dims: usize) -> Result<Matrices> {
        if !is_prime(base) || base > MAX_BASE {
            return Err(Error::Param {
                owner: "net.niederreiter".into(),
                param: "base".into(),
                reason: format!("{base} is not a prime up to {MAX_BASE}"),
            });
        }
        let (cols, rows) = (columns_for_all_sets(base), precision(base));
        let b = base as u64;
        let mut digits = vec![0u8; dims * cols * rows];
        for (j, p) in irreducibles(base).take(dims).enumerate() {
            let e = p.len() - 1;
            let mut power = vec![1u64]; // p^Q, coefficients from degree 0
            let mut v = Vec::new();
            for r in 0..rows {
                let u = r % e;
                if u == 0 {
                    // the sequence for p^(Q+1): zeros below deg p^Q, then ones, then the recurrence
                    let low = power.len() - 1;
                    power = multiply(&power, &p, b);
                    let m = power.len() - 1;
                    let len = (cols + e).max(m) + 1;
                    v = vec![0u64; len];
                    for x in v.iter_mut().take(m).skip(low) {
                        *x = 1;
                    }
                    for i in m..len {
                        let s: u64 = (0..m).map(|k| power[k] * v[i - m + k]).sum::<u64>() % b;
                        v[i] = (b - s) % b;
                    }
                }
                for k in 0..cols {
                    digits[(j * cols + k) * rows + r] = v[k + u] as u8;
                }
            }
        }
        Ok(Matrices { base, dims, cols, rows, digits })
    }

    /// Parse generating matrices in the LDData "dnet" format (the Magic Point Shop's, read
    /// by QMCPy): `#` starts a comment; then four numbers, one per line (the base b, the
    /// dimensions s, the largest point count b^m, the digits per column R); then one line
    /// per dimension with its m columns, each an integer whose base-b digits, most
    /// significant first, are the column's rows 0..R-1. Rows past the precision kept
    /// (64 bits in base 2; b^P <= 2^63 otherwise) are dropped.
    ///
    /// # Errors
    /// A malformed file, with its line.
    pub fn parse(text: &str, source: &str) -> Result<Matrices> {
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(i, l)| (i + 1, l.split('#').next().unwrap_or("").trim()))
            .filter(|(_, l)| !l.is_empty());
        let bad = |line: usize, reason: String| Error::Parse { location: format!("{source}:{line}"), reason };
        let mut header = [0u64; 4];
        let names = ["the base", "the dimensions", "the largest point count", "the digits per column"];
        for (value, name) in header.iter_mut().zip(names) {
            let (line, l) = lines.next().ok_or_else(|| bad(0, format!("the file ends before {name}")))?;
            *value = l.parse().map_err(|_| bad(line, format!("{} is not {name} (a whole number)", crate::error::excerpt(l))))?;
        }
        let [base, dims, _, rows] = header;
        let base = u32::try_from(base).ok().filter(|&b| is_prime(b) && b <= MAX_BASE).ok_or_else(|| {
            bad(0, format!("the base {base} is not a prime up to {MAX_BASE}"))
        })?;
        let width = (rows as f64 * f64::from(base).log2()).ceil();
        if rows == 0 || width > 64.0 {
            return Err(bad(0, format!("{rows} digits per column do not fit in 64 bits in base {base}")));
        }
        if dims == 0 || dims > 1 << 20 {
            return Err(bad(0, format!("{dims} dimensions: expected 1 to 2^20")));
        }
        let (dims, rows) = (dims as usize, rows as usize);
        let mut columns: Vec<Vec<u64>> = Vec::with_capacity(dims);
        for (line, l) in lines {
            if columns.len() == dims {
                return Err(bad(line, format!("more than the {dims} dimensions the header announces")));
            }
            let row = l
                .split_whitespace()
                .map(|t| t.parse::<u64>().map_err(|_| bad(line, format!("{} is not a whole number", crate::error::excerpt(t)))))
                .collect::<Result<Vec<u64>>>()?;
            if let Some(first) = columns.first().filter(|c| c.len() != row.len()) {
                return Err(bad(line, format!("{} columns where the first dimension has {}", row.len(), first.len())));
            }
            let limit = u128::from(base).pow(rows as u32);
            if let Some(c) = row.iter().find(|&&c| u128::from(c) >= limit) {
                return Err(bad(line, format!("column {c} has more than {rows} digits in base {base}")));
            }
            columns.push(row);
        }
        if columns.len() < dims {
            return Err(bad(0, format!("{} dimensions where the header announces {dims}", columns.len())));
        }
        let cols = columns[0].len();
        let b = u64::from(base);
        let mut digits = Vec::with_capacity(dims * cols * rows);
        for c in columns.iter().flatten() {
            let start = digits.len();
            let mut rest = *c;
            for _ in 0..rows {
                digits.push((rest % b) as u8);
                rest /= b;
            }
            digits[start..].reverse();
        }
        Matrices::new(base, dims, cols, rows, digits).map_err(|e| bad(0, e.to_string()))
    }
}

/// Keep the first `precision(base)` rows of each column.
fn truncate_rows(digits: Vec<u8>, rows: usize, base: u32) -> Vec<u8> {
    let keep = precision(base);
    if rows <= keep {
        return digits;
    }
    digits.chunks_exact(rows).flat_map(|c| c[..keep].iter().copied()).collect()
}

/// The smallest prime >= d (2 for d = 1).
fn faure_base(dims: usize) -> u32 {
    (dims.max(2) as u32..).find(|&b| is_prime(b)).expect("primes are unbounded")
}

/// The product of two polynomials over F_b (coefficients from degree 0).
fn multiply(a: &[u64], c: &[u64], b: u64) -> Vec<u64> {
    let mut out = vec![0u64; a.len() + c.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        for (j, &y) in c.iter().enumerate() {
            out[i + j] = (out[i + j] + x * y) % b;
        }
    }
    out
}

/// The monic irreducible polynomials over F_b in order of degree, then of their
/// coefficients read as a base-b number (x, x+1, x^2+x+1, ... in base 2), coefficients from
/// degree 0. Irreducibility by trial division by every monic polynomial of lower degree.
fn irreducibles(base: u32) -> impl Iterator<Item = Vec<u64>> {
    let b = u64::from(base);
    let poly = move |mut code: u64, degree: usize| {
        let mut p: Vec<u64> = (0..degree)
            .map(|_| {
                let c = code % b;
                code /= b;
                c
            })
            .collect();
        p.push(1);
        p
    };
    let divides = move |d: &[u64], p: &[u64]| {
        let mut r = p.to_vec();
        let k = d.len() - 1;
        for top in (k..r.len()).rev() {
            let q = r[top];
            if q != 0 {
                for (i, &di) in d.iter().enumerate() {
                    r[top - k + i] = (r[top - k + i] + (b - q) * di) % b;
                }
            }
        }
        r[..k].iter().all(|&x| x == 0)
    };
    (1usize..).flat_map(move |degree| {
        (0..b.pow(degree as u32)).map(move |code| poly(code, degree)).filter(move |p| {
            (1..=(p.len() - 1) / 2).all(|dd| (0..b.pow(dd as u32)).all(|c| !divides(&poly(c, dd), p)))
        })
    })
}

/// Which matrices a net sampler uses.
#[derive(Debug, Clone, PartialEq)]
enum Source {
    /// The Joe-Kuo Sobol' matrices.
    Sobol,
    /// Read from a file.
    File(Arc<Matrices>),
    /// Faure's, for the dimension asked.
    Faure,
    /// Niederreiter's in a base.
    Niederreiter(u32),
    /// The SZ matrices (Ahmed et al. 2025), four dimensions.
    Sz,
    /// The xi-sequence's two matrices (Ahmed et al. 2023).
    Xi,
    /// Cascaded Sobol' (Paulin et al. 2021) of Joe & Kuo's generators or a file's: the
    /// matrices depend on the count.
    Cascaded(Option<Arc<Vec<[u32; 32]>>>),
}

/// A digital net or sequence with a randomization.
#[derive(Debug, Clone, PartialEq)]
pub struct Net {
    source: Source,
    randomization: Randomization,
    /// Base 2: the points in Gray-code order (point i is natural point i ^ (i >> 1), so
    /// consecutive points differ by one column: Antonov & Saleev 1979).
    gray: bool,
}

impl Net {
    /// The matrices for `dims` dimensions and `n` points: a file's, or the construction's,
    /// made here.
    fn matrices(&self, dims: usize, n: usize) -> Result<Arc<Matrices>> {
        Ok(match &self.source {
            Source::File(m) => Arc::clone(m),
            Source::Sobol => Arc::new(Matrices::sobol(dims)),
            Source::Faure => Arc::new(Matrices::faure(dims)),
            Source::Niederreiter(b) => Arc::new(Matrices::niederreiter(*b, dims)?),
            Source::Sz => Arc::new(Matrices::from_directions(crate::construct::sz::SZ.into_iter().take(dims))),
            Source::Xi => Arc::new(Matrices::from_directions(crate::construct::xi::XI.into_iter().take(dims))),
            Source::Cascaded(file) => {
                // n = 2^m (the count rule); m columns (one for a single point)
                let m = n.trailing_zeros() as usize;
                let generators: Vec<[u32; 32]> = match file {
                    Some(table) => table[..dims].to_vec(),
                    None => (0..dims).map(crate::construct::sobol::direction_numbers).collect(),
                };
                let cascade = Matrices::from_directions(crate::construct::cascaded::matrices(generators, m).into_iter());
                Arc::new(cascade.first_columns(m.max(1)))
            }
        })
    }

    fn base(&self, dims: usize) -> u32 {
        match &self.source {
            Source::Sobol | Source::Sz | Source::Xi | Source::Cascaded(_) => 2,
            Source::File(m) => m.base,
            Source::Faure => faure_base(dims),
            Source::Niederreiter(b) => *b,
        }
    }

}

/// A net planned for a count and dimension: its generating matrices, made once.
#[derive(Debug)]
struct Planned {
    net: Net,
    matrices: Arc<Matrices>,
    n: usize,
    dims: usize,
    /// Base 2: each dimension's columns as 64-bit words, row 0 the most significant bit
    /// (`words[d * cols + k]`), made once.
    words: Option<Vec<u64>>,
}

impl Planned {
    /// The engine for `seed`; `bound` caps the prefix tables of an Owen scramble in base b
    /// (the count of points to make; a cache only).
    fn engine(&self, seed: Seed, bound: u64) -> Engine {
        self.engine_of(self.dims, seed, bound)
    }

    /// The engine of the first `dims` dimensions (each dimension's randomization is drawn
    /// from its own stream, so the first ones do not depend on how many follow).
    fn engine_of(&self, dims: usize, seed: Seed, bound: u64) -> Engine {
        match &self.words {
            Some(words) => Engine::Binary(Binary::new(words, self.matrices.cols, dims, self.net.randomization, seed)),
            None => Engine::Prime(Prime::new(&self.matrices, dims, self.net.randomization, seed, bound)),
        }
    }

    /// A base-2 net's points for `seed`, `CHUNK` dimensions at a time: each dimension's
    /// (scrambled) columns' running XORs, its key and its state on the stack, so that the
    /// fill allocates nothing. Point i + 1 is point i with the running XOR of the columns
    /// up to its lowest zero bit flipped in (natural order).
    fn fill_binary(&self, words: &[u64], seed: Seed, out: &mut [f64]) {
        const CHUNK: usize = 64;
        let (dims, cols) = (self.dims, self.matrices.cols);
        // indices stay below 2^32, so no walk reaches past column 32
        let used = cols.min(MAX_WORDS);
        for d0 in (0..dims).step_by(CHUNK) {
            let count = CHUNK.min(dims - d0);
            // steps[k][j]: the running XOR of dimension d0 + j's columns up to k (by column,
            // then dimension: a point's step is one contiguous row)
            let mut steps = [[0u64; CHUNK]; MAX_WORDS];
            // natural order steps by the running XOR of the columns up to the index's lowest
            // zero bit, Gray-code order by that column alone
            let mut keys = [BinaryKey::default(); CHUNK];
            let mut columns = [0u64; MAX_WORDS];
            for (j, key) in keys.iter_mut().take(count).enumerate() {
                let d = d0 + j;
                *key = binary_dimension(&words[d * cols..][..used], self.net.randomization, seed, d, &mut columns[..used]);
                let mut running = 0;
                for (step, &column) in steps.iter_mut().zip(&columns[..used]) {
                    running ^= column;
                    step[j] = if self.net.gray { column } else { running };
                }
            }
            let mut state = [0u64; CHUNK];
            for (i, p) in out.chunks_exact_mut(dims).enumerate() {
                let c = ((i as u64).trailing_ones() as usize).min(used - 1);
                let step = &steps[c][..count];
                for ((x, s), (key, &t)) in p[d0..d0 + count].iter_mut().zip(&mut state).zip(keys.iter().zip(step)) {
                    *x = key.value(*s);
                    *s ^= t;
                }
            }
        }
    }
}

/// The most columns a base-2 fill walks (a word per column on the stack).
const MAX_WORDS: usize = 64;

impl Prepared for Planned {
    fn fill(&self, seed: Seed, out: &mut [f64], progress: &Progress) -> Result<()> {
        match &self.words {
            Some(words) => self.fill_binary(words, seed, out),
            None => Prime::new(&self.matrices, self.dims, self.net.randomization, seed, self.n as u64).fill(out),
        }
        progress.advance(1)
    }

    fn access(&self, seed: Seed) -> Option<Box<dyn Access + '_>> {
        Some(Box::new(Ordered { engine: self.engine(seed, u64::MAX), gray: self.net.gray }))
    }

    fn sample_at(&self, seed: Seed, index: u64, dim: usize) -> Option<Result<f64>> {
        // a value drawn alone (per pixel): the dimensions up to its own, Owen tables at
        // their least (a cache only: the same bits)
        Some(Ordered { engine: self.engine_of(dim + 1, seed, 1), gray: self.net.gray }.sample(index, dim))
    }

    fn generating_matrices(&self) -> Option<&Matrices> {
        // Gray-code order makes the same sets of b^m points
        Some(&self.matrices)
    }
}

/// Most dimensions of the built-in constructions (Faure's base and Niederreiter's
/// polynomial degrees grow with it).
const MAX_DIMS: usize = 1024;

impl Construction for Net {
    fn dims(&self) -> RangeInclusive<usize> {
        match &self.source {
            Source::Sobol => 1..=crate::construct::sobol::SOBOL_MAX_DIMS,
            Source::File(m) => 1..=m.dims,
            Source::Faure => 1..=MAX_BASE as usize,
            Source::Niederreiter(_) => 1..=MAX_DIMS,
            Source::Sz => 1..=crate::construct::sz::SZ.len(),
            Source::Xi => 1..=2,
            Source::Cascaded(Some(table)) => 1..=table.len(),
            Source::Cascaded(None) => 1..=crate::construct::sobol::SOBOL_MAX_DIMS,
        }
    }
    fn check_count(&self, shape: &Shape) -> Result<()> {
        let (n, dims) = (shape.n(), shape.dims());
        let cols = match &self.source {
            Source::Sobol | Source::Sz | Source::Xi | Source::Cascaded(_) => 32,
            Source::File(m) => m.cols,
            _ => columns_for_all_sets(self.base(dims)),
        };
        let most = u128::from(self.base(dims)).pow(cols as u32);
        if n as u128 > most {
            return Err(shape.invalid_count(format!("the matrices have {cols} columns: at most {} points", most)));
        }
        Ok(())
    }

    fn prepare(&self, shape: &Shape) -> Result<Box<dyn Prepared>> {
        let (n, dims) = (shape.n(), shape.dims());
        let matrices = self.matrices(dims, n)?;
        let words = (matrices.base == 2).then(|| {
            (0..dims)
                .flat_map(|d| (0..matrices.cols).map(move |k| (d, k)))
                .map(|(d, k)| (0..matrices.rows).fold(0u64, |c, r| c | (u64::from(matrices.digit(d, r, k)) << (63 - r))))
                .collect()
        });
        Ok(Box::new(Planned { net: self.clone(), matrices, n, dims, words }))
    }
}

/// A net for one seed's random access (and the prime bases' fill): the (scrambled) columns
/// and the per-dimension randomization.
#[derive(Debug)]
enum Engine {
    Binary(Binary),
    Prime(Prime),
}

impl Access for Engine {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        let (cols, base) = match self {
            Engine::Binary(e) => (e.cols, 2),
            Engine::Prime(e) => (e.cols, e.base),
        };
        if u128::from(index) >= u128::from(base).pow(cols as u32) {
            return Err(Error::Setting {
                name: "index",
                value: index.to_string(),
                reason: format!("the matrices have {cols} columns: points stop at index {base}^{cols} - 1"),
            });
        }
        Ok(match self {
            Engine::Binary(e) => e.value(e.digits(index, dim), dim),
            Engine::Prime(e) => e.value(&e.digits(index, dim), dim),
        })
    }
}

/// An engine's points in natural or Gray-code order.
#[derive(Debug)]
struct Ordered {
    engine: Engine,
    gray: bool,
}

impl Access for Ordered {
    fn sample(&self, index: u64, dim: usize) -> Result<f64> {
        // the Gray code of an index below b^cols is below it too: the same range
        self.engine.sample(if self.gray { index ^ (index >> 1) } else { index }, dim)
    }
}

/// Per-dimension randomness, drawn in one order from the dimension's own stream.
struct Draws(crate::seed::Rng);

impl Draws {
    fn new(seed: Seed, dim: usize) -> Draws {
        Draws(seed.derive(dim as u64).rng())
    }
    fn below(&mut self, bound: u32) -> u32 {
        below(&mut self.0, u64::from(bound)) as u32
    }
    fn bits(&mut self) -> u64 {
        rand_core::Rng::next_u64(&mut self.0)
    }
}

/// One base-2 dimension's randomization for a seed: a digital shift or an Owen key.
#[derive(Debug, Clone, Copy, Default)]
struct BinaryKey {
    shift: u64,
    owen: Option<u32>,
}

impl BinaryKey {
    /// The coordinate of the digits `x` (row 0 the most significant bit), randomized.
    #[inline]
    fn value(self, x: u64) -> f64 {
        let x = match self.owen {
            Some(key) => {
                // nested on 64 bits: the low half's scramble is keyed by the whole high half
                let high = (x >> 32) as u32;
                let low = owen_scramble_u32(x as u32, hash2(key, high));
                (u64::from(owen_scramble_u32(high, key)) << 32) | u64::from(low)
            }
            None => x ^ self.shift,
        };
        (x >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// Dimension `d` of a base-2 net for `seed`: its columns `words` into `columns`, linearly
/// scrambled when asked (`.lms`: C replaced by L C, L lower triangular with a unit
/// diagonal), and its key, the draws taken in one order from the dimension's own stream
/// (so a fill and a random access agree).
fn binary_dimension(words: &[u64], randomization: Randomization, seed: Seed, d: usize, columns: &mut [u64]) -> BinaryKey {
    let mut draws = Draws::new(seed, d);
    if randomization == Randomization::Lms {
        // row j of L: its diagonal bit and uniform bits for the rows above it
        let lower: [u64; 64] = std::array::from_fn(|j| (draws.bits() & (u64::MAX << (63 - j))) | (1u64 << (63 - j)));
        for (column, &c) in columns.iter_mut().zip(words) {
            *column = lower.iter().enumerate().fold(0, |acc, (j, l)| acc | (u64::from((l & c).count_ones() & 1) << (63 - j)));
        }
    } else {
        columns.copy_from_slice(words);
    }
    match randomization {
        // linear matrix scrambling is followed by a digital shift
        Randomization::Xor | Randomization::Lms => BinaryKey { shift: draws.bits(), ..BinaryKey::default() },
        Randomization::Owen => BinaryKey { owen: Some(draws.bits() as u32), ..BinaryKey::default() },
        // a net's shift is the plain net under the +shift stage's code (build_net)
        Randomization::None | Randomization::Shift => BinaryKey::default(),
    }
}

/// Base 2 for one seed: the (scrambled) columns as 64-bit words, row 0 the most significant
/// bit, and each dimension's key.
#[derive(Debug)]
struct Binary {
    cols: usize,
    columns: Vec<u64>,
    keys: Vec<BinaryKey>,
}

impl Binary {
    fn new(words: &[u64], cols: usize, dims: usize, randomization: Randomization, seed: Seed) -> Binary {
        let mut columns = vec![0u64; dims * cols];
        let keys = (0..dims)
            .map(|d| binary_dimension(&words[d * cols..][..cols], randomization, seed, d, &mut columns[d * cols..][..cols]))
            .collect();
        Binary { cols, columns, keys }
    }

    fn digits(&self, index: u64, dim: usize) -> u64 {
        let mut x = 0;
        let mut i = index;
        let mut k = 0;
        while i != 0 {
            if i & 1 == 1 {
                x ^= self.columns[dim * self.cols + k];
            }
            i >>= 1;
            k += 1;
        }
        x
    }

    #[inline]
    fn value(&self, x: u64, dim: usize) -> f64 {
        self.keys[dim].value(x)
    }
}

/// An odd prime base: columns as digit vectors of the kept precision P.
#[derive(Debug)]
struct Prime {
    base: u32,
    dims: usize,
    cols: usize,
    digits: usize,
    /// Column k of dimension d at `(d * cols + k) * digits`, and their running sums mod b.
    columns: Vec<u8>,
    prefix: Vec<u8>,
    shift: Vec<u8>,
    owen: Option<Vec<OwenDigits>>,
    /// Digits in the exact leading part of a value: the most with b^high <= 2^53.
    high: usize,
    /// b^high and b^P.
    powers: [f64; 2],
}

impl Prime {
    fn new(m: &Matrices, dims: usize, randomization: Randomization, seed: Seed, bound: u64) -> Prime {
        // linear matrix scrambling, then the digital shift
        let lms = randomization == Randomization::Lms;
        let (base, cols, p) = (m.base, m.cols, precision(m.base));
        let b = base as usize;
        let mut columns = vec![0u8; dims * cols * p];
        let (mut shift, mut owen) = (vec![0u8; dims * p], Vec::new());
        for d in 0..dims {
            let mut draws = Draws::new(seed, d);
            // L: lower triangular, row j: uniform digits below the diagonal, a non-zero one on it
            let lower: Vec<Vec<u8>> = if lms {
                (0..p)
                    .map(|j| (0..=j).map(|i| (if i == j { 1 + draws.below(base - 1) } else { draws.below(base) }) as u8).collect())
                    .collect()
            } else {
                Vec::new()
            };
            for k in 0..cols {
                let column = &mut columns[(d * cols + k) * p..][..p];
                for (r, y) in column.iter_mut().enumerate().take(m.rows) {
                    *y = m.digit(d, r, k) as u8;
                }
                if lms {
                    let c = column.to_vec();
                    for (j, row) in lower.iter().enumerate() {
                        column[j] = (row.iter().zip(&c).map(|(&l, &x)| usize::from(l) * usize::from(x)).sum::<usize>() % b) as u8;
                    }
                }
            }
            match randomization {
                Randomization::Xor | Randomization::Lms => {
                    for e in &mut shift[d * p..(d + 1) * p] {
                        *e = draws.below(base) as u8;
                    }
                }
                Randomization::Owen => owen.push(OwenDigits::new(base, draws.bits(), bound)),
                // a net's shift is the plain net under the +shift stage's code (build_net)
                Randomization::None | Randomization::Shift => {}
            }
        }
        let high = (1..).find(|&k| u128::from(base).pow(k) > 1 << 53).expect("powers grow") as usize - 1;
        let mut prefix = columns.clone();
        for dim in prefix.chunks_exact_mut(cols * p) {
            for k in 1..cols {
                let (done, rest) = dim.split_at_mut(k * p);
                add_mod(&mut rest[..p], &done[(k - 1) * p..], base as u8);
            }
        }
        Prime {
            base,
            dims,
            cols,
            digits: p,
            columns,
            prefix,
            shift,
            owen: (randomization == Randomization::Owen).then_some(owen),
            high,
            powers: [f64::from(base).powi(high as i32), f64::from(base).powi(p as i32)],
        }
    }

    fn digits(&self, mut index: u64, dim: usize) -> Vec<u8> {
        let p = self.digits;
        let mut y = vec![0u8; p];
        let mut k = 0;
        while index != 0 {
            let a = (index % u64::from(self.base)) as usize;
            for _ in 0..a {
                add_mod(&mut y, &self.columns[(dim * self.cols + k) * p..][..p], self.base as u8);
            }
            index /= u64::from(self.base);
            k += 1;
        }
        y
    }

    /// The coordinate of the digits `y` of dimension `dim`, randomized: the first `high`
    /// digits as one exact integer over b^high (<= 2^53, so the quotient is correctly
    /// rounded), plus the rest over b^P; Owen-scrambled, the digit string as the integer
    /// sum y_r b^r that [`OwenDigits`] scrambles.
    fn value(&self, y: &[u8], dim: usize) -> f64 {
        let b = u64::from(self.base);
        if let Some(owen) = &self.owen {
            return owen[dim].value(y.iter().rev().fold(0, |acc, &a| acc * b + u64::from(a)));
        }
        let mut v = [0u64; 2];
        let shift = &self.shift[dim * self.digits..][..self.digits];
        for (r, (&a, &e)) in y.iter().zip(shift).enumerate() {
            let s = u64::from(a) + u64::from(e);
            let part = &mut v[usize::from(r >= self.high)];
            *part = *part * b + if s >= b { s - b } else { s };
        }
        (v[0] as f64 / self.powers[0] + v[1] as f64 / self.powers[1]).min(BELOW_ONE)
    }

    fn fill(&self, out: &mut [f64]) {
        let (p, b) = (self.digits, u64::from(self.base));
        let mut state = vec![0u8; self.dims * p];
        let mut index_digits = vec![0u32; self.cols + 1];
        for p_out in out.chunks_exact_mut(self.dims) {
            for (d, x) in p_out.iter_mut().enumerate() {
                *x = self.value(&state[d * p..(d + 1) * p], d);
            }
            // the next index: digits b-1 roll over to 0 (adding their column once more),
            // the first other digit goes up by one
            let mut c = 0;
            while c + 1 < self.cols && u64::from(index_digits[c]) == b - 1 {
                index_digits[c] = 0;
                c += 1;
            }
            index_digits[c] += 1;
            for d in 0..self.dims {
                add_mod(&mut state[d * p..(d + 1) * p], &self.prefix[(d * self.cols + c) * p..][..p], self.base as u8);
            }
        }
    }
}

/// y += c digit by digit, mod b.
#[inline]
fn add_mod(y: &mut [u8], c: &[u8], b: u8) {
    for (y, &c) in y.iter_mut().zip(c) {
        let s = *y + c;
        *y = if s >= b { s - b } else { s };
    }
}

/// The matrices file parameter.
const MATRICES: ParamSpec = ParamSpec {
    name: "matrices",
    kind: Kind::Path,
    default: Default::Auto("the Sobol' matrices of Joe & Kuo, 1024 dimensions x 32 bits"),
    doc: "generating matrices in the LDData dnet format (docs/guide/cli.md: generating matrices)",
};

/// Niederreiter's base.
const BASE: ParamSpec = ParamSpec {
    name: "base",
    kind: Kind::Int { min: 2, max: MAX_BASE as u64 },
    default: Default::Int(2),
    doc: "a prime: the field of the polynomials and of the digits",
};

/// The order of the points.
const ORDER: ParamSpec = ParamSpec {
    name: "order",
    kind: Kind::Choice(&["natural", "gray"]),
    default: Default::Word("natural"),
    doc: "natural, or Gray-code order (base 2: point i is natural point i ^ (i >> 1), as sobol orders its points)",
};

/// The direction-number file parameter.
const DIRECTIONS: ParamSpec = ParamSpec {
    name: "directions",
    kind: Kind::Path,
    default: Default::Auto("none: the matrices"),
    doc: "Sobol' direction numbers: in base 2 in Joe & Kuo's format (new-joe-kuo-6.21201: `d s a m_1 .. m_s` per \
          line from d = 2, or the OneTwo table as its authors publish it), the net their Sobol' matrices, 32 x 32 \
          bits, with van der Corput's first; with base=3 the quad-optimized sequences' format (`i s a m_1 .. m_s`, \
          a and the m_k read in base 3), Sobol's construction over GF(3)",
};

/// The field of a direction-number file.
const DIRECTIONS_BASE: ParamSpec = ParamSpec {
    name: "base",
    kind: Kind::Int { min: 2, max: 3 },
    default: Default::Auto("2"),
    doc: "the field of the directions file: 2 (Joe & Kuo's format) or 3 (Ostromoukhov et al. 2024's)",
};

/// The cascade's 1D generators.
const GENERATORS: ParamSpec = ParamSpec {
    name: "directions",
    kind: Kind::Path,
    default: Default::Auto("none: Joe & Kuo's"),
    doc: "the 1D Sobol' generators of the cascade, one per dimension, in Joe & Kuo's format (numbered from 2; or \
          from 1, van der Corput's first dimension left out or written `0 0 0`, as the authors' table \
          cascaded_sobol_init_tab.dat numbers them)",
};

fn read_text(path: &str) -> Result<String> {
    crate::io::read_small_text(path, crate::io::SPEC_FILE_MAX)
}

/// A Joe-Kuo direction-number file's table, van der Corput's dimension first.
fn read_directions(path: &str) -> Result<Vec<[u32; 32]>> {
    crate::construct::joe_kuo::directions(&read_text(path)?)
        .map_err(|(line, reason)| Error::Parse { location: format!("{path}:{line}"), reason })
}

/// A base-3 direction file's matrices ([`crate::construct::sobol3`]), every column the
/// output digits hold.
fn read_directions3(path: &str) -> Result<Matrices> {
    let rows = precision(3);
    let bad = |line: usize, reason: String| Error::Parse { location: format!("{path}:{line}"), reason };
    let dims = crate::construct::sobol3::matrices(&read_text(path)?, rows).map_err(|(line, why)| bad(line, why))?;
    if dims.is_empty() {
        return Err(bad(1, "no dimensions: expected a line i s a m_1 .. m_s per dimension".into()));
    }
    let digits: Vec<u8> = dims.iter().flatten().flatten().copied().collect();
    Ok(Matrices { base: 3, dims: dims.len(), cols: rows, rows, digits })
}

fn net_source(p: &Params) -> Result<Source> {
    let base = p.int_or_auto("base");
    let param = |param: &str, reason: &str| Error::Param { owner: "net".into(), param: param.into(), reason: reason.into() };
    match (p.path_or_auto("matrices"), p.path_or_auto("directions")) {
        (Some(_), Some(_)) => Err(param("directions", "give matrices or directions, not both")),
        (_, None) if base == Some(3) => {
            Err(param("base", "base 3 is not realizable without a directions file (the base is that file's field)"))
        }
        (Some(path), None) => Ok(Source::File(Arc::new(Matrices::parse(&read_text(path)?, path)?))),
        (None, Some(path)) if base == Some(3) => Ok(Source::File(Arc::new(read_directions3(path)?))),
        (None, Some(path)) => Ok(Source::File(Arc::new(Matrices::from_directions(read_directions(path)?.into_iter())))),
        (None, None) => Ok(Source::Sobol),
    }
}

fn niederreiter_source(p: &Params) -> Result<Source> {
    let base = p.int("base") as u32;
    if !is_prime(base) {
        return Err(Error::Param { owner: "niederreiter".into(), param: "base".into(), reason: format!("{base} is not a prime") });
    }
    Ok(Source::Niederreiter(base))
}

/// The construction of each `net` entry.
fn build_net(p: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    let source = net_source(p)?;
    let gray = p.word("order") == "gray";
    if gray && !matches!(&source, Source::Sobol) && !matches!(&source, Source::File(m) if m.base == 2) {
        let reason = "Gray-code order is for base-2 matrices (consecutive points one column apart)".into();
        return Err(Error::Param { owner: "net".into(), param: "order".into(), reason });
    }
    Ok(shift::applied(randomization, |randomization| Box::new(Net { source, randomization, gray })))
}

/// The construction of each `faure` entry.
fn build_faure(_: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    fixed(Source::Faure, randomization)
}

/// The construction of each `niederreiter` entry.
fn build_niederreiter(p: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    fixed(niederreiter_source(p)?, randomization)
}

/// A net of given matrices in natural order with a randomization.
fn fixed(source: Source, randomization: Randomization) -> Result<Box<dyn Construction>> {
    Ok(shift::applied(randomization, |randomization| Box::new(Net { source, randomization, gray: false })))
}

/// The construction of each `sz` entry.
fn build_sz(_: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    fixed(Source::Sz, randomization)
}

/// The construction of each `xi` entry.
fn build_xi(_: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    fixed(Source::Xi, randomization)
}

/// The construction of each `cascaded` entry.
fn build_cascaded(p: &mut Params, randomization: Randomization) -> Result<Box<dyn Construction>> {
    let generators = p.path_or_auto("directions").map(read_directions).transpose()?;
    fixed(Source::Cascaded(generators.map(Arc::new)), randomization)
}

/// The samplers this file registers: each family plain and with its four randomizations.
pub(crate) static ENTRIES: &[SamplerEntry] = randomized_families!(
    {
        family: "net",
        summary: "digital net in base b from generating matrices, natural order",
        aliases: ["digitalnet", "digitalnetb2"],
        params: &[MATRICES, DIRECTIONS, DIRECTIONS_BASE, ORDER],
        counts: Counts::Rule("n <= b^m (m columns; nets at powers of b)"),
        dims: "up to the file's",
        cite: ["niederreiter1992", "joe2008", "bratley1988", "antonov1979", "bonneel2025onetwo", "ostromoukhov2024quad"],
        build: build_net,
        randomizations: [xor, lms, owen, shift],
    },
    {
        family: "faure",
        summary: "Faure (0,s)-sequence, base the smallest prime >= d",
        aliases: [],
        params: &[],
        counts: Counts::Any("nets at powers of the base"),
        dims: "1..=251",
        cite: ["faure1982"],
        build: build_faure,
        randomizations: [xor, lms, owen, shift],
    },
    {
        family: "niederreiter",
        summary: "Niederreiter (t,s)-sequence from irreducible polynomials",
        aliases: [],
        params: &[BASE],
        counts: Counts::Any("nets at powers of the base"),
        dims: "1..=1024",
        cite: ["niederreiter1988", "bratley1992"],
        build: build_niederreiter,
        randomizations: [xor, lms, owen, shift],
    },
    {
        family: "sz",
        summary: "SZ sequence (q = 2): a (0,4)-sequence in base 4 in binary, Sobol's first two dimensions",
        aliases: [],
        params: &[],
        counts: Counts::Any("nets at powers of 4 (and of 2 in dimensions 0, 1)"),
        dims: "1..=4",
        cite: ["ahmed2025sz"],
        build: build_sz,
        randomizations: [xor, lms, owen, shift],
    },
    {
        family: "cascaded",
        summary: "Cascaded Sobol': each dimension a 1D Sobol' net drawn at the previous coordinate's digits, consecutive pairs (0,m,2)-nets",
        aliases: ["cascaded-sobol"],
        params: &[GENERATORS],
        counts: Counts::Listed { rule: "n = 2^m (the matrices depend on m)", list: |_, _| Box::new((0..=32).map(|k| 1usize << k)) },
        dims: "up to the generators' (1024 of Joe & Kuo's)",
        cite: ["paulin2021cascaded", "joe2008"],
        build: build_cascaded,
        randomizations: [xor, lms, owen, shift],
    },
    {
        family: "xi",
        summary: "xi-sequence: a 2D (0,2)-sequence from one vector and xi, the authors' default",
        aliases: ["xi-sequence"],
        params: &[],
        counts: Counts::Any("nets at powers of 2"),
        dims: "1..=2",
        cite: ["ahmed2023xi"],
        build: build_xi,
        randomizations: [xor, lms, owen, shift],
    },
);
