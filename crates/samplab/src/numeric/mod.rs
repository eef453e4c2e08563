//! Numerics shared across samplab: the last double below one, a compensated sum, the
//! normal distribution function and its inverse, Student's t quantiles, and Gauss–Legendre
//! quadrature ([`quadrature`]).

pub mod quadrature;

/// The largest f64 below one: where a rounding could land a coordinate on 1.0, it is
/// clamped here, so that every coordinate stays in [0, 1).
pub const BELOW_ONE: f64 = 1.0 - f64::EPSILON / 2.0;

/// Neumaier's compensated sum.
#[derive(Debug, Clone, Copy, Default)]
pub struct Sum {
    sum: f64,
    err: f64,
}

impl Sum {
    /// Add `x`.
    #[inline]
    pub fn add(&mut self, x: f64) {
        let t = self.sum + x;
        if self.sum.abs() >= x.abs() {
            self.err += (self.sum - t) + x;
        } else {
            self.err += (x - t) + self.sum;
        }
        self.sum = t;
    }
    /// Add another compensated sum.
    pub fn merge(&mut self, other: Sum) {
        self.add(other.sum);
        self.add(other.err);
    }
    /// The sum.
    pub fn value(&self) -> f64 {
        self.sum + self.err
    }
    /// The sum and its compensation each multiplied by `factor`.
    #[must_use]
    pub fn scaled(self, factor: f64) -> Sum {
        Sum { sum: self.sum * factor, err: self.err * factor }
    }
}

/// A double's place in `f64::total_cmp`'s order, as an integer: integers compare (and
/// sort) faster than `total_cmp` does.
#[inline(always)]
pub fn order_key(v: f64) -> i64 {
    let bits = v.to_bits() as i64;
    bits ^ (((bits >> 63) as u64) >> 1) as i64
}

/// The standard normal distribution function Phi(x) = erfc(-x / sqrt 2) / 2.
pub fn normal_cdf(x: f64) -> f64 {
    0.5 * libm::erfc(-x / std::f64::consts::SQRT_2)
}

/// The standard normal quantile Phi^-1(p) for p in (0, 1), by Wichura's algorithm AS 241
/// (PPND16; Applied Statistics 37(3), 1988, 477-484): a ratio of two degree-7 polynomials in
/// each of three regions: |p - 1/2| <= 0.425 (polynomials in 0.425^2 - (p - 1/2)^2), then
/// r = sqrt(-ln min(p, 1 - p)) up to 5, and beyond. Within 5 ulp of mpmath's quantile at the
/// 1706 points of tests/fixtures/normal_quantile.json, p down to the least normal double; no
/// call of `erfc`, so it costs about a logarithm and a square root. 0 and 1 give -inf and inf.
pub fn normal_quantile(p: f64) -> f64 {
    if p <= 0.0 || p >= 1.0 {
        return if p <= 0.0 { f64::NEG_INFINITY } else { f64::INFINITY };
    }
    let q = p - 0.5;
    if q.abs() <= 0.425 {
        let r = 0.180_625 - q * q;
        return q * horner(&AS241_CENTRAL.0, r) / horner(&AS241_CENTRAL.1, r);
    }
    let r = (-p.min(1.0 - p).ln()).sqrt();
    let ((num, den), s) = if r <= 5.0 { (&AS241_INTERMEDIATE, r - 1.6) } else { (&AS241_TAIL, r - 5.0) };
    let x = horner(num, s) / horner(den, s);
    if q < 0.0 { -x } else { x }
}

/// sum_k c[k] x^k by Horner's rule.
fn horner(c: &[f64; 8], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |s, &k| s * x + k)
}

/// AS 241's numerator and denominator coefficients (constant term first) for |p - 1/2| <= 0.425.
#[expect(clippy::excessive_precision, reason = "the paper's constants, digit for digit")]
const AS241_CENTRAL: ([f64; 8], [f64; 8]) = (
    [
        3.387_132_872_796_366_608,
        1.331_416_678_917_843_774_5e2,
        1.971_590_950_306_551_442_7e3,
        1.373_169_376_550_946_112_5e4,
        4.592_195_393_154_987_145_7e4,
        6.726_577_092_700_870_085_3e4,
        3.343_057_558_358_812_810_5e4,
        2.509_080_928_730_122_672_7e3,
    ],
    [
        1.0,
        4.231_333_070_160_091_125_2e1,
        6.871_870_074_920_579_083e2,
        5.394_196_021_424_751_107_7e3,
        2.121_379_430_158_659_586_7e4,
        3.930_789_580_009_271_061e4,
        2.872_908_573_572_194_267_4e4,
        5.226_495_278_852_854_561e3,
    ],
);

/// AS 241's coefficients for r = sqrt(-ln min(p, 1 - p)) in (1.6, 5], in r - 1.6.
#[expect(clippy::excessive_precision, reason = "the paper's constants, digit for digit")]
const AS241_INTERMEDIATE: ([f64; 8], [f64; 8]) = (
    [
        1.423_437_110_749_683_577_34,
        4.630_337_846_156_545_295_9,
        5.769_497_221_460_691_405_5,
        3.647_848_324_763_204_605_04,
        1.270_458_252_452_368_382_58,
        2.417_807_251_774_506_117_7e-1,
        2.272_384_498_926_918_458_33e-2,
        7.745_450_142_783_414_076_4e-4,
    ],
    [
        1.0,
        2.053_191_626_637_758_821_87,
        1.676_384_830_183_803_849_4,
        6.897_673_349_851_000_045_5e-1,
        1.481_039_764_274_800_745_9e-1,
        1.519_866_656_361_645_719_66e-2,
        5.475_938_084_995_344_946e-4,
        1.050_750_071_644_416_843_24e-9,
    ],
);

/// AS 241's coefficients for r > 5, in r - 5.
#[expect(clippy::excessive_precision, reason = "the paper's constants, digit for digit")]
const AS241_TAIL: ([f64; 8], [f64; 8]) = (
    [
        6.657_904_643_501_103_777_2,
        5.463_784_911_164_114_369_9,
        1.784_826_539_917_291_335_8,
        2.965_605_718_285_048_912_3e-1,
        2.653_218_952_657_612_309_3e-2,
        1.242_660_947_388_078_438_6e-3,
        2.711_555_568_743_487_578_15e-5,
        2.010_334_399_292_288_132_65e-7,
    ],
    [
        1.0,
        5.998_322_065_558_879_376_9e-1,
        1.369_298_809_227_358_053_1e-1,
        1.487_536_129_085_061_485_25e-2,
        7.868_691_311_456_132_591e-4,
        1.846_318_317_510_054_681_8e-5,
        1.421_511_758_316_445_888_7e-7,
        2.044_263_103_389_939_785_64e-15,
    ],
);

/// The regularized incomplete beta function I_x(a, b), by the continued fraction of
/// Numerical Recipes' section 6.4 evaluated with the modified Lentz method (the symmetry
/// I_x(a, b) = 1 - I_(1-x)(b, a) where the fraction converges slowly).
fn incomplete_beta(x: f64, a: f64, b: f64) -> f64 {
    if x <= 0.0 || x >= 1.0 {
        return x.clamp(0.0, 1.0);
    }
    if x > (a + 1.0) / (a + b + 2.0) {
        return 1.0 - incomplete_beta(1.0 - x, b, a);
    }
    let front = (libm::lgamma(a + b) - libm::lgamma(a) - libm::lgamma(b) + a * x.ln() + b * (1.0 - x).ln()).exp() / a;
    let tiny = 1e-300;
    let (mut c, mut d) = (1.0, 1.0 - (a + b) * x / (a + 1.0));
    d = 1.0 / if d.abs() < tiny { tiny } else { d };
    let mut h = d;
    for m in 1..500 {
        let m = f64::from(m);
        // the even and the odd step of the fraction
        for numerator in [
            m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m)),
            -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0)),
        ] {
            d = 1.0 + numerator * d;
            d = 1.0 / if d.abs() < tiny { tiny } else { d };
            c = 1.0 + numerator / c;
            c = if c.abs() < tiny { tiny } else { c };
            h *= d * c;
        }
        if (d * c - 1.0).abs() < 1e-16 {
            break;
        }
    }
    front * h
}

/// Student's t distribution function with `df` degrees of freedom.
pub fn student_t_cdf(t: f64, df: f64) -> f64 {
    let tail = 0.5 * incomplete_beta(df / (df + t * t), df / 2.0, 0.5);
    if t > 0.0 { 1.0 - tail } else { tail }
}

/// Student's t quantile: the t with [`student_t_cdf`]`(t, df) = p`, p in (0, 1), by
/// bisection to the last bit.
pub fn student_t_quantile(p: f64, df: f64) -> f64 {
    if p == 0.5 {
        return 0.0;
    }
    let (mut lo, mut hi) = (-1.0f64, 1.0f64);
    while student_t_cdf(lo, df) > p {
        lo *= 2.0;
    }
    while student_t_cdf(hi, df) < p {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if student_t_cdf(mid, df) < p { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}
