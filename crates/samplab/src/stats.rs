//! Summary statistics over realizations.

/// Mean, sample standard deviation and extremes of a list of values.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Summary {
    /// How many values.
    pub count: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation (divides by count - 1; zero for one value).
    pub sd: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Summary {
    /// Summarize `values` (compensated sums).
    ///
    /// # Panics
    /// `values` is empty.
    pub fn of(values: &[f64]) -> Summary {
        assert!(!values.is_empty(), "a summary of no values");
        let n = values.len() as f64;
        let mut sum = crate::numeric::Sum::default();
        values.iter().for_each(|&v| sum.add(v));
        let mean = sum.value() / n;
        let mut sq = crate::numeric::Sum::default();
        values.iter().for_each(|&v| sq.add((v - mean) * (v - mean)));
        let sd = if values.len() > 1 { (sq.value() / (n - 1.0)).sqrt() } else { 0.0 };
        let (min, max) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        Summary { count: values.len(), mean, sd, min, max }
    }

    /// The standard error of the mean, sd / sqrt(count).
    pub fn standard_error(&self) -> f64 {
        self.sd / (self.count as f64).sqrt()
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn by_hand() {
        let s = super::Summary::of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!((s.mean, s.min, s.max, s.count), (2.5, 1.0, 4.0, 4));
        assert!((s.sd - (5.0f64 / 3.0).sqrt()).abs() < 1e-15);
        assert!((s.standard_error() - s.sd / 2.0).abs() < 1e-15);
    }
}
