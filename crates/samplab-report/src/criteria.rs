//! The verdict criteria: named functions from measured numbers to reproduced / not
//! reproduced / undecided. A claim picks its criterion and its parameters before the run
//! (they are constants in the experiment's code, never read off its result), and the
//! criterion's words go into the report beside the verdict, so that a reader can check it.
//!
//! Statistical criteria compare intervals of `Z` = 3 standard errors (two-sided 99.7% for a
//! normal mean): a difference that its interval cannot resolve is "undecided", never
//! counted for the claim.

use samplab::stats::Summary;
use serde::Serialize;

/// Half-width of the intervals, in standard errors (two-sided 99.7% for a normal mean).
pub const Z: f64 = 3.0;

/// The verdict on a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Default)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum Verdict {
    /// The measurement supports the claim under its criterion.
    Reproduced,
    /// The measurement contradicts the claim under its criterion.
    NotReproduced,
    /// The measurement cannot decide (its interval straddles the criterion's boundary).
    #[default]
    Undecided,
}

/// A verdict and the criterion that gave it, in words.
#[derive(Debug, Clone, PartialEq, Serialize, Default)]
pub struct Decision {
    /// The verdict.
    pub verdict: Verdict,
    /// The criterion, with its parameters and the numbers it compared.
    pub criterion: String,
}

impl Decision {
    fn new(verdict: Verdict, criterion: String) -> Decision {
        Decision { verdict, criterion }
    }
}

fn holds(ok: bool) -> Verdict {
    if ok { Verdict::Reproduced } else { Verdict::NotReproduced }
}

/// A measured value and its standard error (zero for an exact value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The value.
    pub value: f64,
    /// Its standard error.
    pub se: f64,
}

impl Estimate {
    /// The mean of a summary and its standard error.
    pub fn mean_of(s: &Summary) -> Estimate {
        Estimate { value: s.mean, se: s.standard_error() }
    }

    /// A value with the standard error of its bootstrap `draws` (their sample standard
    /// deviation, summed plainly in their order).
    pub fn bootstrapped(value: f64, draws: &[f64]) -> Estimate {
        let mean = draws.iter().sum::<f64>() / draws.len() as f64;
        let se = (draws.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (draws.len() - 1) as f64).sqrt();
        Estimate { value, se }
    }

    /// An exact value.
    pub fn exact(value: f64) -> Estimate {
        Estimate { value, se: 0.0 }
    }

    /// The ratio self / other, its standard error by the delta method (independent
    /// estimates, relative errors added in quadrature).
    pub fn ratio(self, other: Estimate) -> Estimate {
        let value = self.value / other.value;
        let rel = ((self.se / self.value).powi(2) + (other.se / other.value).powi(2)).sqrt();
        Estimate { value, se: value.abs() * rel }
    }

    /// The difference self - other of independent estimates.
    pub fn minus(self, other: Estimate) -> Estimate {
        Estimate { value: self.value - other.value, se: self.se.hypot(other.se) }
    }
}

/// A closed form with a stated tolerance: reproduced when |ours - target| <= tolerance.
pub fn within(ours: f64, target: f64, tolerance: f64) -> Decision {
    Decision::new(
        holds((ours - target).abs() <= tolerance),
        format!("|ours - {target:.6}| <= {tolerance:.3e} (ours {ours:.6})"),
    )
}

/// Agreement with a published or predicted value that has its own uncertainty (a published
/// sample mean, or half a unit of its last printed digit as `rounding`): reproduced when
/// the difference is within `Z` combined standard errors, otherwise not.
pub fn agrees(ours: Estimate, target: Estimate, rounding: f64) -> Decision {
    let se = ours.se.hypot(target.se).hypot(rounding);
    let z = (ours.value - target.value) / se;
    Decision::new(
        holds(z.is_finite() && z.abs() <= Z),
        format!("|z| <= {Z} for ours {:.5} against {:.5} (z = {z:.2})", ours.value, target.value),
    )
}

/// The claim "a < b" for two estimates: reproduced when b - a exceeds `Z` standard errors
/// of the difference, not reproduced when a - b does, undecided in between.
pub fn less(a: Estimate, b: Estimate) -> Decision {
    let d = b.minus(a);
    let z = d.value / d.se;
    let verdict = if d.se == 0.0 {
        holds(d.value > 0.0)
    } else if z > Z {
        Verdict::Reproduced
    } else if z < -Z {
        Verdict::NotReproduced
    } else {
        Verdict::Undecided
    };
    Decision::new(verdict, format!("{:.4e} < {:.4e} by more than {Z} standard errors ({z:.2})", a.value, b.value))
}

/// The claim "x lies in [lo, hi]": reproduced when the interval x +- `Z` se lies inside,
/// not reproduced when it lies wholly outside, undecided when it straddles a bound.
pub fn in_range(x: Estimate, lo: f64, hi: f64) -> Decision {
    let (a, b) = (x.value - Z * x.se, x.value + Z * x.se);
    let verdict = if a >= lo && b <= hi {
        Verdict::Reproduced
    } else if b < lo || a > hi {
        Verdict::NotReproduced
    } else {
        Verdict::Undecided
    };
    Decision::new(verdict, format!("[{a:.4}, {b:.4}] (ours +- {Z} SE) inside [{}, {}]", short(lo), short(hi)))
}

/// A value with a stated confidence interval (a fitted exponent's 95% interval, say)
/// against a target: reproduced when the interval holds the target, not reproduced when
/// it does not.
pub fn covers((lo, hi): (f64, f64), target: f64) -> Decision {
    Decision::new(holds(lo <= target && target <= hi), format!("{} in the interval [{lo:.3}, {hi:.3}]", short(target)))
}

/// `x` to 6 significant digits, in the shortest form that reads back as that rounding
/// (`0.8307` for 0.8306999999999998, `0.693147` for ln 2, `0.046` as it is).
fn short(x: f64) -> String {
    let rounded: f64 = format!("{x:.5e}").parse().expect("a float's own exponent form");
    format!("{rounded}")
}

/// The claim "a < b" for two values with confidence intervals: reproduced when a's whole
/// interval lies below b's, not reproduced when above, undecided when they overlap.
pub fn interval_below(a: (f64, f64), b: (f64, f64)) -> Decision {
    let verdict = if a.1 < b.0 {
        Verdict::Reproduced
    } else if a.0 > b.1 {
        Verdict::NotReproduced
    } else {
        Verdict::Undecided
    };
    Decision::new(verdict, format!("[{:.3}, {:.3}] below [{:.3}, {:.3}]", a.0, a.1, b.0, b.1))
}

/// A share of cases: reproduced when at least `share` of `total` cases hold.
pub fn at_least(count: usize, total: usize, share: f64) -> Decision {
    Decision::new(
        holds(total > 0 && count as f64 >= share * total as f64),
        format!("at least {:.0}% of the cases ({count} of {total})", 100.0 * share),
    )
}

/// A condition checked exactly (a count, a sign, an equality of bits).
pub fn exactly(ok: bool, what: &str) -> Decision {
    Decision::new(holds(ok), what.to_string())
}

/// All of several decisions: not reproduced if any is, undecided if any is, else reproduced.
pub fn all(parts: &[Decision]) -> Decision {
    let verdict = if parts.iter().any(|d| d.verdict == Verdict::NotReproduced) {
        Verdict::NotReproduced
    } else if parts.iter().any(|d| d.verdict == Verdict::Undecided) {
        Verdict::Undecided
    } else {
        Verdict::Reproduced
    };
    let criterion = parts.iter().map(|d| d.criterion.as_str()).collect::<Vec<_>>().join("; ");
    Decision::new(verdict, format!("all of: {criterion}"))
}

/// The claim "a beats b in most cases" from `wins` of `total` paired cases (ties counted
/// against): the exact binomial sign test at p = 1/2. Reproduced when `wins` or more would
/// happen by chance with probability below `alpha`, not reproduced when `wins` or fewer
/// would, undecided in between.
pub fn sign_test(wins: usize, total: usize, alpha: f64) -> Decision {
    let tail = |range: std::ops::RangeInclusive<usize>| -> f64 {
        // binomial(total, 1/2) probabilities by the recurrence C(n, k+1) = C(n, k) (n-k)/(k+1)
        let mut p = 0.5f64.powi(total as i32);
        let mut sum = 0.0;
        for k in 0..=total {
            if range.contains(&k) {
                sum += p;
            }
            p *= (total - k) as f64 / (k + 1) as f64;
        }
        sum
    };
    let (above, below) = (tail(wins..=total), tail(0..=wins));
    let verdict = if total > 0 && above < alpha {
        Verdict::Reproduced
    } else if total > 0 && below < alpha {
        Verdict::NotReproduced
    } else {
        Verdict::Undecided
    };
    Decision::new(
        verdict,
        format!(
            "sign test: {wins} of {total} cases, exact one-sided p = {above:.3} (for) / {below:.3} (against), alpha {alpha}"
        ),
    )
}

/// Kendall's tau between two rankings of the same items (values, lower is better).
///
/// # Panics
/// When the two rankings have different lengths.
pub fn kendall_tau(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "two rankings of the same items");
    let n = a.len();
    let mut s = 0i64;
    for i in 0..n {
        for j in i + 1..n {
            let x = (a[i] - a[j]).signum() * (b[i] - b[j]).signum();
            s += x as i64;
        }
    }
    s as f64 / (n * (n - 1) / 2) as f64
}

/// The exact one-sided p-value of Kendall's tau >= `tau` for `n` items under independence,
/// by enumerating every permutation (n <= 9).
fn kendall_p(n: usize, tau: f64) -> f64 {
    assert!(n <= 9, "exact enumeration up to 9 items");
    let base: Vec<f64> = (0..n).map(|i| i as f64).collect();
    let mut perm: Vec<usize> = (0..n).collect();
    let (mut at_least, mut total) = (0u64, 0u64);
    // Heap's algorithm, iterative
    let mut c = vec![0usize; n];
    let mut visit = |p: &[usize]| {
        let other: Vec<f64> = p.iter().map(|&i| i as f64).collect();
        total += 1;
        at_least += u64::from(kendall_tau(&base, &other) >= tau - 1e-12);
    };
    visit(&perm);
    let mut i = 0;
    while i < n {
        if c[i] < i {
            if i % 2 == 0 {
                perm.swap(0, i)
            } else {
                perm.swap(c[i], i)
            }
            visit(&perm);
            c[i] += 1;
            i = 0;
        } else {
            c[i] = 0;
            i += 1;
        }
    }
    at_least as f64 / total as f64
}

/// The claim "these two rankings agree": Kendall's tau of `ours` against `theirs` (lower is
/// better in both), reproduced when its exact permutation p-value is below `alpha`
/// (agreement beyond chance), not reproduced otherwise.
pub fn rank_agreement(ours: &[f64], theirs: &[f64], alpha: f64) -> Decision {
    let tau = kendall_tau(ours, theirs);
    let p = kendall_p(ours.len(), tau);
    Decision::new(
        holds(p < alpha),
        format!("Kendall's tau = {tau:.2} over {} items, exact one-sided p = {p:.3} < {alpha}", ours.len()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn est(value: f64, se: f64) -> Estimate {
        Estimate { value, se }
    }

    #[test]
    fn within_fails_outside_the_tolerance() {
        assert_eq!(within(0.5, 0.5, 1e-9).verdict, Verdict::Reproduced);
        assert_eq!(within(0.49, 0.5, 1e-6).verdict, Verdict::NotReproduced);
    }

    #[test]
    fn agrees_fails_beyond_three_standard_errors() {
        assert_eq!(agrees(est(0.162, 0.002), est(0.165, 0.002), 5e-4).verdict, Verdict::Reproduced);
        assert_eq!(agrees(est(0.150, 0.001), est(0.165, 0.002), 5e-4).verdict, Verdict::NotReproduced);
        assert_eq!(agrees(est(f64::NAN, 0.001), est(0.165, 0.002), 0.0).verdict, Verdict::NotReproduced);
    }

    #[test]
    fn less_decides_only_resolved_differences() {
        assert_eq!(less(est(1.0, 0.1), est(2.0, 0.1)).verdict, Verdict::Reproduced);
        assert_eq!(less(est(2.0, 0.1), est(1.0, 0.1)).verdict, Verdict::NotReproduced);
        assert_eq!(less(est(1.0, 0.5), est(1.2, 0.5)).verdict, Verdict::Undecided);
        assert_eq!(less(Estimate::exact(2.0), Estimate::exact(1.0)).verdict, Verdict::NotReproduced);
    }

    #[test]
    fn in_range_is_three_valued() {
        assert_eq!(in_range(est(2.0, 0.05), 1.5, 2.5).verdict, Verdict::Reproduced);
        assert_eq!(in_range(est(1.0, 0.05), 1.5, 2.5).verdict, Verdict::NotReproduced);
        assert_eq!(in_range(est(1.5, 0.05), 1.5, 2.5).verdict, Verdict::Undecided);
        let ln2 = std::f64::consts::LN_2;
        assert!(in_range(est(0.0, 0.05), -ln2, ln2).criterion.ends_with("inside [-0.693147, 0.693147]"));
    }

    #[test]
    fn intervals() {
        assert_eq!(covers((-1.1, -0.9), -1.0).verdict, Verdict::Reproduced);
        // the target printed to its precision, not its binary rounding
        assert!(covers((-0.134, 0.046), 0.17 - 1.0007).criterion.starts_with("-0.8307 in"));
        assert_eq!(covers((-1.6, -1.3), -1.0).verdict, Verdict::NotReproduced);
        assert_eq!(interval_below((-2.0, -1.8), (-1.5, -1.3)).verdict, Verdict::Reproduced);
        assert_eq!(interval_below((-1.5, -1.3), (-2.0, -1.8)).verdict, Verdict::NotReproduced);
        assert_eq!(interval_below((-1.6, -1.4), (-1.5, -1.3)).verdict, Verdict::Undecided);
    }

    #[test]
    fn ratio_adds_relative_errors() {
        let r = est(2.0, 0.2).ratio(est(1.0, 0.1));
        assert!((r.value - 2.0).abs() < 1e-15 && (r.se - 2.0 * 0.02f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn at_least_and_all() {
        assert_eq!(at_least(9, 10, 0.9).verdict, Verdict::Reproduced);
        assert_eq!(at_least(8, 10, 0.9).verdict, Verdict::NotReproduced);
        assert_eq!(at_least(0, 0, 0.9).verdict, Verdict::NotReproduced);
        let (r, u, n) = (exactly(true, "r"), less(est(1.0, 0.5), est(1.2, 0.5)), exactly(false, "n"));
        assert_eq!(all(&[r.clone(), r.clone()]).verdict, Verdict::Reproduced);
        assert_eq!(all(&[r.clone(), u.clone()]).verdict, Verdict::Undecided);
        assert_eq!(all(&[u, n, r]).verdict, Verdict::NotReproduced);
    }

    #[test]
    fn sign_test_by_hand() {
        // 10 of 10: p = 1/1024 for; 0 of 10: p = 1/1024 against; 5 of 10 decides nothing
        assert_eq!(sign_test(10, 10, 0.01).verdict, Verdict::Reproduced);
        assert_eq!(sign_test(0, 10, 0.01).verdict, Verdict::NotReproduced);
        assert_eq!(sign_test(5, 10, 0.01).verdict, Verdict::Undecided);
        // 9 of 10: P(X >= 9) = 11/1024 = 0.0107, not below 0.01
        assert_eq!(sign_test(9, 10, 0.01).verdict, Verdict::Undecided);
        assert_eq!(sign_test(9, 10, 0.05).verdict, Verdict::Reproduced);
    }

    #[test]
    fn kendall_by_hand() {
        assert_eq!(kendall_tau(&[1.0, 2.0, 3.0], &[10.0, 20.0, 30.0]), 1.0);
        assert_eq!(kendall_tau(&[1.0, 2.0, 3.0], &[30.0, 20.0, 10.0]), -1.0);
        assert!((kendall_tau(&[1.0, 2.0, 3.0], &[10.0, 30.0, 20.0]) - 1.0 / 3.0).abs() < 1e-15);
        // n = 4: 24 permutations; tau = 1 only for the identity
        assert!((kendall_p(4, 1.0) - 1.0 / 24.0).abs() < 1e-15);
        // tau >= -1 always
        assert_eq!(kendall_p(5, -1.0), 1.0);
    }

    #[test]
    fn rank_agreement_fails_on_unrelated_or_reversed_orders() {
        let published = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0];
        assert_eq!(rank_agreement(&published, &published, 0.05).verdict, Verdict::Reproduced);
        let reversed = [7.0, 6.0, 5.0, 4.0, 3.0, 2.0, 1.0];
        assert_eq!(rank_agreement(&reversed, &published, 0.05).verdict, Verdict::NotReproduced);
        let shuffled = [4.0, 1.0, 7.0, 2.0, 6.0, 3.0, 5.0];
        assert_eq!(rank_agreement(&shuffled, &published, 0.05).verdict, Verdict::NotReproduced);
    }
}
