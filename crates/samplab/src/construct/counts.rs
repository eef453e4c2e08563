//! Which counts a construction makes: the typed rule each registry entry declares.

/// The largest point count samplab will allocate for one set (2^32 points).
pub const MAX_POINTS: usize = 1 << 32;

/// Any count.
pub(crate) const ANY: Counts = Counts::Any("");

/// Which counts n a sampler makes, declared in its entry: a typed rule that checks a count
/// (naming the nearest valid ones), finds valid counts and prints the listing line.
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum Counts {
    /// Any n (up to [`MAX_POINTS`]); the note says where the structure is best ("nets at
    /// powers of two"), or is empty.
    Any(&'static str),
    /// n at most `most`; `why` says what limits it.
    AtMost {
        /// The largest count.
        most: u64,
        /// The limit's reason, in words.
        why: &'static str,
    },
    /// n = k^d: a grid.
    Grid,
    /// The counts `list(dims, near)` yields, increasing (from the first valid count or from
    /// some way below `near`); `rule` in words.
    Listed {
        /// The rule, in words.
        rule: &'static str,
        /// The valid counts in `dims` dimensions around `near`, increasing.
        list: fn(usize, usize) -> Box<dyn Iterator<Item = usize>>,
    },
    /// A rule that depends on the parameters, in words; the construction checks it.
    Rule(&'static str),
}

impl Counts {
    /// Whether the rule admits `n` points in `dims` dimensions.
    ///
    /// # Errors
    /// Why not, in words: the rule and the nearest valid counts (the sampler makes the
    /// error that names it).
    pub fn check(&self, n: usize, dims: usize) -> Result<(), String> {
        match *self {
            Counts::Any(_) | Counts::Rule(_) => Ok(()),
            Counts::AtMost { most, why } if n as u64 > most => Err(why.into()),
            Counts::AtMost { .. } => Ok(()),
            Counts::Grid => exact_root(n, dims).map(|_| ()).map_err(|(lo, hi)| {
                format!("a {dims}D grid needs n = k^{dims}; the nearest valid counts are {lo} and {hi}")
            }),
            Counts::Listed { rule, list } => {
                if list(dims, n).take_while(|&c| c <= n).any(|c| c == n) {
                    return Ok(());
                }
                let below = list(dims, n).take_while(|&c| c < n).last();
                let above = list(dims, n).take_while(|&c| c <= MAX_POINTS).find(|&c| c > n);
                let near = match (below, above) {
                    (Some(b), Some(a)) => format!("try {b} and {a}"),
                    (Some(c), None) | (None, Some(c)) => format!("try {c}"),
                    (None, None) => "no count fits".into(),
                };
                Err(format!("{rule}: {near}"))
            }
        }
    }

    /// The first count from `n` on that the rule admits in `dims` dimensions (`None` for a
    /// rule of the parameters, or past [`MAX_POINTS`]).
    pub fn first_from(&self, n: usize, dims: usize) -> Option<usize> {
        match *self {
            Counts::Rule(_) => None,
            Counts::Listed { list, .. } => list(dims, n).find(|&c| c >= n),
            _ => (n..=MAX_POINTS).find(|&c| self.check(c, dims).is_ok()),
        }
    }

    /// The listing line: the rule in words.
    pub fn describe(&self) -> String {
        match *self {
            Counts::Any("") => "any n".into(),
            Counts::Any(note) => format!("any n ({note})"),
            Counts::AtMost { why, .. } => format!("any n up to the limit: {why}"),
            Counts::Grid => "n = k^d".into(),
            Counts::Listed { rule, list } => {
                let first: Vec<String> = list(2, 1).take(8).map(|c| c.to_string()).collect();
                format!("{rule} (in 2D: {}, ...)", first.join(", "))
            }
            Counts::Rule(words) => words.into(),
        }
    }
}

/// The integer k with k^d == n, if there is one; otherwise the two nearest valid counts.
pub(crate) fn exact_root(n: usize, dims: usize) -> Result<usize, (usize, usize)> {
    let guess = (n as f64).powf(1.0 / dims as f64).round() as usize;
    let pow = |k: usize| k.checked_pow(dims as u32).unwrap_or(usize::MAX);
    for k in guess.saturating_sub(1)..=guess + 1 {
        if pow(k) == n {
            return Ok(k);
        }
    }
    let mut k = guess.max(1);
    while pow(k) > n && k > 1 {
        k -= 1;
    }
    while pow(k + 1) <= n {
        k += 1;
    }
    Err((pow(k), pow(k + 1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_root_names_neighbours() {
        assert_eq!(exact_root(16, 2), Ok(4));
        assert_eq!(exact_root(15, 2), Err((9, 16)));
        assert_eq!(exact_root(27, 3), Ok(3));
        assert_eq!(exact_root(28, 3), Err((27, 64)));
        assert_eq!(exact_root(7, 1), Ok(7));
        assert_eq!(exact_root(2, 2), Err((1, 4)));
    }
}
