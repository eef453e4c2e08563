//! The one bibliography of samplab. Doc comments and registry entries cite these keys.

/// A published work that a method implements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reference {
    /// Stable key, e.g. `shirley1991`.
    pub key: &'static str,
    /// Authors, title, venue, year.
    pub citation: &'static str,
}

macro_rules! bib {
    ($($key:ident => $cite:expr),* $(,)?) => {
        /// Every reference, in key order.
        pub const ALL: &[Reference] = &[$(Reference { key: stringify!($key), citation: $cite }),*];
    };
}

bib! {
    ahmed2020 => "A. G. M. Ahmed, P. Wonka. Screen-space blue-noise diffusion of Monte Carlo sampling error via hierarchical ordering of pixels. ACM TOG 39(6), SIGGRAPH Asia 2020.",
    ahmed2022 => "A. G. M. Ahmed, J. Ren, P. Wonka. Gaussian blue noise. ACM TOG 41(6), SIGGRAPH Asia 2022.",
    ahmed2023xi => "A. G. M. Ahmed, M. Skopenkov, M. Hadwiger, P. Wonka. Analysis and synthesis of digital dyadic sequences. ACM Trans. Graph. 42(6), SIGGRAPH Asia 2023; the default xi-sequence of its supplemental code (xi.h).",
    ahmed2025sz => "A. G. M. Ahmed, M. Pharr, V. Ostromoukhov, H. Huang. SZ sequences: binary-constructed (0, 2^q)-sequences. ACM Trans. Graph. (SIGGRAPH Asia), 2025; the q = 2 matrices as OpenQMC builds them (its pull request #108).",
    antonov1979 => "I. A. Antonov, V. M. Saleev. An economic method of computing LP_tau-sequences. USSR Comput. Math. Math. Phys. 19(1), 1979.",
    balzer2009 => "M. Balzer, T. Schlömer, O. Deussen. Capacity-constrained point distributions: a variant of Lloyd's method. ACM TOG 28(3), SIGGRAPH 2009.",
    blinn1977 => "J. F. Blinn. Models of light reflection for computer synthesized pictures. SIGGRAPH 1977.",
    bonneel2025onetwo => "N. Bonneel, D. Coeurjolly, J.-C. Iehl, V. Ostromoukhov. Sobol' sequences with guaranteed-quality 2D projections. ACM Trans. Graph. 44(4), SIGGRAPH 2025; its direction numbers (github.com/liris-origami/OneTwoSobolSequences), which net:directions=FILE reads, are not shipped.",
    bratley1988 => "P. Bratley, B. L. Fox. Algorithm 659: implementing Sobol's quasirandom sequence generator. ACM TOMS 14(1), 1988.",
    bratley1992 => "P. Bratley, B. L. Fox, H. Niederreiter. Implementation and tests of low-discrepancy sequences. ACM TOMACS 2(3), 1992.",
    bridson2007 => "R. Bridson. Fast Poisson disk sampling in arbitrary dimensions. SIGGRAPH sketches, 2007.",
    burley2020 => "B. Burley. Practical hash-based Owen scrambling. JCGT 9(4), 2020.",
    chizhov2022 => "V. Chizhov, I. Georgiev, K. Myszkowski, G. Singh. Perceptual error optimization for Monte Carlo rendering. ACM TOG 41(3), 2022.",
    christensen2018 => "P. Christensen, A. Kensler, C. Kilpatrick. Progressive multi-jittered sample sequences. EGSR 2018.",
    cook1986 => "R. L. Cook. Stochastic sampling in computer graphics. ACM TOG 5(1), 1986.",
    cools2006 => "R. Cools, F. Y. Kuo, D. Nuyens. Constructing embedded lattice rules for multivariate integration. SIAM J. Sci. Comput. 28(6), 2006.",
    cranley1976 => "R. Cranley, T. N. L. Patterson. Randomization of number theoretic methods for multiple integration. SIAM J. Numer. Anal. 13(6), 1976.",
    cycles => "Blender Cycles, the production path tracer of Blender (Apache-2.0), github.com/blender/cycles: its sampling patterns (kernel/sample/pattern.h, sobol_burley.h, tabulated_sobol.h; scene/integrator.cpp, tabulated_sobol.cpp), reproduced bit for bit from commit 97dbe6f (2026-07-13).",
    du1999 => "Q. Du, V. Faber, M. Gunzburger. Centroidal Voronoi tessellations: applications and algorithms. SIAM Review 41(4), 1999.",
    ebeida2012 => "M. Ebeida, S. Mitchell, A. Patney, A. Davidson, J. Owens. A simple algorithm for maximal Poisson-disk sampling in high dimensions. Eurographics 2012.",
    fattal2011 => "R. Fattal. Blue-noise point sampling using kernel density model. ACM TOG 30(4), SIGGRAPH 2011.",
    faure1982 => "H. Faure. Discrepance de suites associees a un systeme de numeration (en dimension s). Acta Arith. 41, 1982.",
    genz1984 => "A. Genz. Testing multidimensional integration routines. Tools, Methods and Languages for Scientific and Engineering Computation, North-Holland, 1984 (the six test families).",
    georgiev2016 => "I. Georgiev, M. Fajardo. Blue-noise dithered sampling. ACM SIGGRAPH 2016 Talks.",
    halton1960 => "J. H. Halton. On the efficiency of certain quasi-random sequences of points in evaluating multi-dimensional integrals. Numer. Math. 2, 1960.",
    hammersley1964 => "J. M. Hammersley, D. C. Handscomb. Monte Carlo Methods. Methuen, 1964.",
    heck2013 => "D. Heck, T. Schlömer, O. Deussen. Blue noise sampling with controlled aliasing. ACM TOG 32(3), 2013 (the PCF by a Gaussian kernel, the effective Nyquist frequency and oscillation, step and single-peak blue noise).",
    heitz2019 => "E. Heitz, L. Belcour, V. Ostromoukhov, D. Coeurjolly, J.-C. Iehl. A low-discrepancy sampler that distributes Monte Carlo errors as a blue noise in screen space. ACM SIGGRAPH 2019 Talks.",
    helmer2021 => "A. Helmer, P. Christensen, A. Kensler. Stochastic generation of (t,s) sample sequences. EGSR 2021.",
    hickernell2000 => "F. J. Hickernell, H. S. Hong, P. L'Ecuyer, C. Lemieux. Extensible lattice sequences for quasi-Monte Carlo quadrature. SIAM J. Sci. Comput. 22(3), 2000.",
    hickernell2002 => "F. J. Hickernell. Obtaining O(N^-2+e) convergence for lattice quadrature rules. Monte Carlo and Quasi-Monte Carlo Methods 2000, Springer, 2002.",
    hilbert1891 => "D. Hilbert. Über die stetige Abbildung einer Linie auf ein Flächenstück. Math. Ann. 38, 1891.",
    ishigami1990 => "T. Ishigami, T. Homma. An importance quantification technique in uncertainty analysis for computer models. ISUMA 1990.",
    joe2008 => "S. Joe, F. Y. Kuo. Constructing Sobol sequences with better two-dimensional projections. SIAM J. Sci. Comput. 30(5), 2008.",
    keister1996 => "B. D. Keister. Multidimensional quadrature algorithms. Computers in Physics 10(2), 1996.",
    kensler2013 => "A. Kensler. Correlated multi-jittered sampling. Pixar Technical Memo 13-01, 2013.",
    korobov1959 => "N. M. Korobov. The approximate computation of multiple integrals. Dokl. Akad. Nauk SSSR 124, 1959.",
    lagae2008 => "A. Lagae, P. Dutré. A comparison of methods for generating Poisson disk distributions. Computer Graphics Forum 27(1), 2008 (the relative radius).",
    laine2011 => "S. Laine, T. Karras. Stratified sampling for stochastic transparency. EGSR 2011.",
    larcher2003 => "G. Larcher, F. Pillichshammer. Sums of distances to the nearest integer and the discrepancy of digital nets. Acta Arithmetica 106(4), 2003.",
    lloyd1982 => "S. P. Lloyd. Least squares quantization in PCM. IEEE Trans. Inf. Theory 28(2), 1982.",
    matousek1998 => "J. Matousek. On the L2-discrepancy for anchored boxes. J. Complexity 14, 1998 (random digit scrambling).",
    mckay1979 => "M. D. McKay, R. J. Beckman, W. J. Conover. A comparison of three methods for selecting values of input variables. Technometrics 21(2), 1979.",
    niederreiter1988 => "H. Niederreiter. Low-discrepancy and low-dispersion sequences. J. Number Theory 30, 1988.",
    niederreiter1992 => "H. Niederreiter. Random Number Generation and Quasi-Monte Carlo Methods. SIAM, 1992.",
    nuyens2006 => "D. Nuyens, R. Cools. Fast algorithms for component-by-component construction of rank-1 lattice rules in shift-invariant reproducing kernel Hilbert spaces. Math. Comp. 75, 2006.",
    openqmc => "OpenQMC: quasi-Monte Carlo sampling for production rendering. Academy Software Foundation, github.com/AcademySoftwareFoundation/openqmc; used through its Rust port openqmc-rs 0.2.4 (crates.io), which reproduces its values bit for bit.",
    ostromoukhov2024quad => "V. Ostromoukhov, N. Bonneel, D. Coeurjolly, J.-C. Iehl. Quad-optimized low-discrepancy sequences. SIGGRAPH 2024 Conference Papers; the initialization table of its code (github.com/liris-origami/Quad-Optimized-LDS), which net:directions=FILE,base=3 reads, is not shipped.",
    owen1992 => "A. B. Owen. Orthogonal arrays for computer experiments, integration and visualization. Statistica Sinica 2, 1992.",
    owen1995 => "A. B. Owen. Randomly permuted (t,m,s)-nets and (t,s)-sequences. Monte Carlo and Quasi-Monte Carlo Methods, 1995.",
    owen1997 => "A. B. Owen. Monte Carlo variance of scrambled net quadrature. SIAM J. Numer. Anal. 34(5), 1997.",
    paulin2020 => "L. Paulin, N. Bonneel, D. Coeurjolly, J.-C. Iehl, A. Webanck, M. Desbrun, V. Ostromoukhov. Sliced optimal transport sampling. ACM TOG 39(4), 2020.",
    paulin2021cascaded => "L. Paulin, D. Coeurjolly, J.-C. Iehl, N. Bonneel, A. Keller, V. Ostromoukhov. Cascaded Sobol' sampling. ACM Trans. Graph. 40(6), SIGGRAPH Asia 2021.",
    petersen1962 => "D. P. Petersen, D. Middleton. Sampling and reconstruction of wave-number-limited functions in N-dimensional Euclidean spaces. Information and Control 5, 1962.",
    pharr2023 => "M. Pharr, W. Jakob, G. Humphreys. Physically Based Rendering: From Theory to Implementation, 4th edition (pbrt-v4). MIT Press, 2023.",
    psa2012 => "T. Schlömer, D. Heck. psa: point set analysis, software, University of Konstanz, 2012 (thresholds and normalization of the effective Nyquist frequency and oscillation).",
    purgathofer1994 => "W. Purgathofer, R. Tobler, M. Geiler. Forced random dithering: improved threshold matrices for ordered dithering. ICIP 1994.",
    ramamoorthi2012 => "R. Ramamoorthi, J. Anderson, M. Meyer, D. Nowrouzezahrai. A theory of Monte Carlo visibility sampling. ACM TOG 31(5), 2012.",
    roberts2018 => "M. Roberts. The unreasonable effectiveness of quasirandom sequences. extremelearning.com.au, 2018 (the generalized golden ratio R_d).",
    roberts2018jitter => "M. Roberts. A simple method to construct isotropic quasirandom blue noise point sequences. extremelearning.com.au, 2018 (the R_2 sequence jittered by a fraction of its spacing).",
    sbert2006 => "M. Sbert, J. Rigau, M. Feixas, L. Neumann. Systematic sampling in image synthesis. ICCSA 2006.",
    shirley1991 => "P. Shirley. Discrepancy as a quality measure for sample distributions. Eurographics 1991.",
    shirley1997 => "P. Shirley, K. Chiu. A low distortion map between disk and square. JGT 2(3), 1997.",
    sloan1994 => "I. H. Sloan, S. Joe. Lattice Methods for Multiple Integration. Oxford University Press, 1994.",
    sobol1967 => "I. M. Sobol'. On the distribution of points in a cube and the approximate evaluation of integrals. USSR Comput. Math. Math. Phys. 7(4), 1967.",
    subr2013 => "K. Subr, J. Kautz. Fourier analysis of stochastic sampling strategies for assessing bias and variance in integration. ACM TOG 32(4), 2013.",
    tang1993 => "B. Tang. Orthogonal array-based Latin hypercubes. J. Amer. Statist. Assoc. 88(424), 1993.",
    ulichney1993 => "R. Ulichney. The void-and-cluster method for dither array generation. Proc. SPIE 1913, Human Vision, Visual Processing, and Digital Display IV, 1993.",
    vegdahl2021 => "N. Vegdahl. Building a better LK hash. psychopath.io blog, 2021 (constants of the Owen hash).",
    weyl1916 => "H. Weyl. Über die Gleichverteilung von Zahlen mod. Eins. Math. Ann. 77, 1916.",
    yuksel2015 => "C. Yuksel. Sample elimination for generating Poisson disk sample sets. Computer Graphics Forum 34(2), Eurographics 2015.",
    zinterhof1976 => "P. Zinterhof. Über einige Abschätzungen bei der Approximation von Funktionen mit Gleichverteilungsmethoden. Sitzungsber. Österr. Akad. Wiss. Math.-Natur. Kl. II 185, 1976 (the diaphony).",
}

/// The reference for `key`, if it exists.
pub fn lookup(key: &str) -> Option<&'static Reference> {
    ALL.iter().find(|r| r.key == key)
}

#[cfg(test)]
mod tests {
    #[test]
    fn keys_unique_and_sorted() {
        let keys: Vec<_> = super::ALL.iter().map(|r| r.key).collect();
        let mut sorted = keys.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(keys, sorted);
    }
}
