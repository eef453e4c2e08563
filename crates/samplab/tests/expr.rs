//! The expression integrand against the same formulas written in Rust, its precedence and
//! folding by hand, and its one-line errors with their columns; the image integrand's
//! exact integral against a fine midpoint rule.

use samplab::integrand::{Expr, Integrand, Lookup, Texture};

type Formula = fn(&[f64]) -> f64;

#[test]
fn formulas_agree_with_rust_at_random_points() {
    let cases: &[(&str, Formula)] = &[
        ("exp(-x0*x0 - x1*x1)", |x| (-x[0] * x[0] - x[1] * x[1]).exp()),
        ("sin(2*pi*x0) * cos(pi*x1) + 1", |x| {
            (2.0 * std::f64::consts::PI * x[0]).sin() * (std::f64::consts::PI * x[1]).cos() + 1.0
        }),
        ("x0^2 + x1**3 - x2/(1+x0)", |x| x[0].powf(2.0) + x[1].powf(3.0) - x[2] / (1.0 + x[0])),
        ("step(x0 + x1 - 1) * sqrt(abs(x2 - 0.5))", |x| {
            if x[0] + x[1] - 1.0 >= 0.0 { (x[2] - 0.5).abs().sqrt() } else { 0.0 }
        }),
        ("min(x0, x1) + max(x1, x2) + pow(x0, 0.5) + atan2(x1, x0)", |x| {
            x[0].min(x[1]) + x[1].max(x[2]) + x[0].powf(0.5) + x[1].atan2(x[0])
        }),
        ("log(1 + x0) + tanh(x1) - floor(3*x2) + ceil(x0) + e", |x| {
            (1.0 + x[0]).ln() + x[1].tanh() - (3.0 * x[2]).floor() + x[0].ceil() + std::f64::consts::E
        }),
        ("-x0^2", |x| -(x[0] * x[0])),
        ("2^3^2 + 1 - 2 - 3 + 8/4/2", |_| 512.0 - 4.0 + 1.0),
        ("1.5e-1 * x1 + .25", |x| 0.15 * x[1] + 0.25),
    ];
    // points from a fixed linear congruential walk, three coordinates each
    let mut state = 12345u64;
    let mut next = || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let points: Vec<f64> = (0..3 * 1000).map(|_| next()).collect();
    for (text, rust) in cases {
        let f = Expr::parse(text, Some(3)).unwrap();
        // 1000 points: three full blocks of 256 and a partial one
        let mut out = vec![0.0; 1000];
        f.eval_many(&points, &mut out);
        for (x, v) in points.chunks_exact(3).zip(&out) {
            let want = rust(x);
            assert!((v - want).abs() <= 1e-14 * want.abs().max(1.0), "{text} at {x:?}: {v} vs {want}");
            assert_eq!(f.eval(x).to_bits(), v.to_bits(), "{text}: one point and a block agree");
        }
    }
}

#[test]
fn dimensions_come_from_the_highest_variable_or_are_given() {
    assert_eq!(Expr::parse("x0 + x4", None).unwrap().dims(), 5);
    assert_eq!(Expr::parse("1", None).unwrap().dims(), 1);
    assert_eq!(Expr::parse("x1", Some(6)).unwrap().dims(), 6);
    let err = Expr::parse("x0 + x3", Some(2)).unwrap_err().to_string();
    assert!(err.contains("uses x3") && err.contains("2 dimensions"), "{err}");
    assert!(Expr::parse("x0", None).unwrap().exact().is_nan());
    assert_eq!(Expr::parse("x0", None).unwrap().with_exact(0.5).exact(), 0.5);
}

#[test]
fn bad_formulas_get_one_line_errors_with_their_column() {
    for (text, column, says) in [
        ("exp(-x0*x0 - )", 14, "found `)`"),
        ("exp(-x0*x0", 11, "expected `)` to close `exp(` at column 1"),
        ("x0 +* 2", 5, "found `*`"),
        ("x0 @ 1", 4, "`@` is not part of the grammar"),
        ("foo(x0)", 1, "unknown name `foo`"),
        ("sin x0", 5, "expected `(` after the function `sin`"),
        ("min(x0)", 7, "expected `,` between the two arguments of `min`"),
        ("x0 x1", 4, "unexpected `x1`"),
        ("", 1, "the expression ended"),
        ("(x0 + 1", 8, "to close the `(` at column 1"),
        ("1..2", 1, "`1..2` is not a number"),
    ] {
        let err = Expr::parse(text, None).unwrap_err().to_string();
        assert!(!err.contains('\n'), "{err}");
        assert!(err.contains(&format!("column {column}:")), "{text}: {err}");
        assert!(err.contains(says), "{text}: {err}");
    }
}

#[test]
fn nesting_is_limited_with_an_error_not_a_stack_overflow() {
    use samplab::integrand::MAX_NESTING;
    // a right-nested difference as deep as allowed: x0 - (x1 - (x0 - ... x1)), evaluated
    // against the same alternation summed in Rust
    let levels = MAX_NESTING - 1;
    let text = (0..levels).map(|k| format!("x{} - (", k % 2)).collect::<String>() + "x1" + &")".repeat(levels);
    let f = Expr::parse(&text, None).unwrap();
    let x = [0.375, 0.0625];
    let want = (0..=levels).rev().fold(0.0, |inner, k| if k == levels { x[1] } else { x[k % 2] - inner });
    assert_eq!(f.eval(&x), want);
    // one level more, and far more of each kind of nesting: a one-line error at the
    // token that would open level MAX_NESTING + 1
    let deep = 100_000;
    for (text, column) in [
        ("(".repeat(MAX_NESTING) + "x0" + &")".repeat(MAX_NESTING), MAX_NESTING + 1),
        ("(".repeat(deep) + "x0" + &")".repeat(deep), MAX_NESTING + 1),
        ("-".repeat(deep) + "x0", MAX_NESTING + 1),
        ("x0^".repeat(deep) + "x0", 3 * (MAX_NESTING + 1) - 2),
        ("exp(".repeat(deep) + "x0" + &")".repeat(deep), 4 * (MAX_NESTING + 1) - 3),
    ] {
        let err = Expr::parse(&text, None).unwrap_err().to_string();
        assert!(err.contains(&format!("column {column}: nested more than {MAX_NESTING} levels")), "{err}");
        // the expression cut to the 40 characters either side of the column
        let shown = &text[column - 41..column + 40];
        assert!(err.contains(&format!("`...{shown}...` ({} characters)", text.len())), "{err}");
    }
}

#[test]
fn a_long_flat_formula_sums_as_rust_does() {
    // 20000 terms, 80000 operations on a stack of at most three values
    let text = (0..20_000).map(|k| format!("{}*x{}", k % 7, k % 3)).collect::<Vec<_>>().join(" + ");
    let f = Expr::parse(&text, None).unwrap();
    let x = [0.5, 0.25, 0.125];
    let want = (0..20_000).fold(0.0, |sum, k| sum + (k % 7) as f64 * x[k % 3]);
    assert_eq!(f.eval(&x), want);
}

/// The midpoint rule on a grid of k x k cells.
fn midpoint(f: &dyn Integrand, k: usize) -> f64 {
    let mut sum = 0.0;
    for j in 0..k {
        for i in 0..k {
            sum += f.eval(&[(i as f64 + 0.5) / k as f64, (j as f64 + 0.5) / k as f64]);
        }
    }
    sum / (k * k) as f64
}

#[test]
fn an_image_integrates_to_its_mean_texel_with_either_lookup() {
    let (w, h) = (5, 3);
    let texels: Vec<f64> = (0..w * h).map(|i| ((i * 7 + 2) % 11) as f64 / 3.0).collect();
    let mean = texels.iter().sum::<f64>() / (w * h) as f64;
    for lookup in [Lookup::Box, Lookup::Bilinear] {
        let f = Texture::new(w, h, texels.clone(), lookup).unwrap();
        assert!((f.exact() - mean).abs() < 1e-15);
        // a 3000^2 midpoint rule: the box lookup's cell edges (multiples of 1/5 and 1/3)
        // fall on cell boundaries of the rule, the bilinear lookup is piecewise bilinear
        let quadrature = midpoint(&f, 3000);
        assert!((quadrature - mean).abs() < 1e-6, "{lookup:?}: {quadrature} vs {mean}");
    }
    // the box lookup reads the texel under the point; row 0 is at the top (x1 = 0)
    let f = Texture::new(w, h, texels.clone(), Lookup::Box).unwrap();
    assert_eq!(f.eval(&[0.99, 0.01]), texels[4]);
    assert_eq!(f.eval(&[0.0, 0.99]), texels[2 * w]);
    // bilinear: a texel centre reads the texel itself
    let f = Texture::new(w, h, texels.clone(), Lookup::Bilinear).unwrap();
    assert!((f.eval(&[2.5 / 5.0, 1.5 / 3.0]) - texels[w + 2]).abs() < 1e-14);
}

#[test]
fn a_bad_image_is_refused() {
    let err = Texture::new(2, 2, vec![0.0, 1.0, f64::NAN, 0.0], Lookup::Box).unwrap_err().to_string();
    assert!(err.contains("texel (0, 1) = NaN"), "{err}");
    assert!(Texture::new(2, 2, vec![0.0; 3], Lookup::Box).is_err());
    assert!(Lookup::parse("trilinear").unwrap_err().to_string().contains("box or bilinear"));
}
