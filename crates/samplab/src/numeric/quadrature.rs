//! Composite Gauss-Legendre quadrature, for integrals without a closed form.

use std::sync::LazyLock;

/// 16-point Gauss-Legendre nodes and weights on [-1, 1], computed by Newton's method on
/// the Legendre polynomial (to machine precision).
static NODES: LazyLock<Vec<(f64, f64)>> = LazyLock::new(|| {
    let n = 16;
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
});

/// The integral of `f` over [a, b] with `panels` equal panels of 16-point Gauss-Legendre.
pub fn gauss_legendre(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    let h = (b - a) / panels as f64;
    let mut sum = crate::numeric::Sum::default();
    for p in 0..panels {
        let mid = a + (p as f64 + 0.5) * h;
        for &(x, w) in NODES.iter() {
            sum.add(w * f(mid + 0.5 * h * x));
        }
    }
    0.5 * h * sum.value()
}

#[cfg(test)]
mod tests {
    #[test]
    fn integrates_polynomials_and_oscillations() {
        // exact for degree <= 31
        let v = super::gauss_legendre(|x| x.powi(30), 0.0, 1.0, 1);
        assert!((v - 1.0 / 31.0).abs() < 1e-15);
        // int_0^1 cos(100 x) = sin(100)/100
        let v = super::gauss_legendre(|x| (100.0 * x).cos(), 0.0, 1.0, 40);
        assert!((v - 100f64.sin() / 100.0).abs() < 1e-15);
    }
}
