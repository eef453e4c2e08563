//! Run-time choice of vector instructions: hot loops are written as plain loops over
//! arrays, and [`wide`] compiles them for AVX-512 or AVX2 where the processor has them.
//! Every lane does the same operations in the same order on each instruction set (no fused
//! multiply-add), so the results are the same bits; [`on_each_instruction_set`] lets tests
//! check it.

/// `f()` compiled for the widest vector instructions the processor has (AVX-512, AVX2 or the
/// baseline), chosen at run time. `f` and everything it calls must be inlined into it
/// (`#[inline(always)]`, including on the closure) to be compiled wide.
#[inline(always)]
pub fn wide<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor supports AVX-512F, checked just above.
            return unsafe { avx512(f) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2, checked just above.
            return unsafe { avx2(f) };
        }
    }
    f()
}

/// `f()` on every instruction set this processor has (baseline, AVX2, AVX-512), for tests
/// that they give the same bits.
pub fn on_each_instruction_set<R>(f: impl Fn() -> R) -> Vec<R> {
    #[allow(unused_mut)] // one entry only off x86-64
    let mut out = vec![f()];
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor supports AVX2, checked just above.
            out.push(unsafe { avx2(&f) });
        }
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor supports AVX-512F, checked just above.
            out.push(unsafe { avx512(&f) });
        }
    }
    out
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn avx512<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}
