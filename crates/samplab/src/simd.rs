//! Run-time choice of vector instructions: hot loops are written as plain loops over
//! arrays, and [`wide`] compiles them for AVX-512 or AVX2 where the processor has them.
//! The AVX-512 tier asks for the byte, word and bit-reversal extensions too (BW, DQ, VL,
//! GFNI: Ice Lake, Zen 4 and later), which turn the bit reversals of Owen-scrambled
//! Sobol' points into two instructions; an older AVX-512 processor takes the AVX2 tier.
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
        if has_avx512() {
            // SAFETY: the processor supports the tier's features, checked just above.
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
        if has_avx512() {
            // SAFETY: the processor supports the tier's features, checked just above.
            out.push(unsafe { avx512(&f) });
        }
    }
    out
}

/// Whether the processor has every feature of the AVX-512 tier: detected once, then one load
/// per call (wide runs per pixel in the renderer).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn has_avx512() -> bool {
    use std::arch::is_x86_feature_detected as has;
    use std::sync::atomic::{AtomicU8, Ordering};
    // 0: not yet detected, 1: no, 2: yes
    static TIER: AtomicU8 = AtomicU8::new(0);
    match TIER.load(Ordering::Relaxed) {
        0 => {
            let yes = has!("avx512f") && has!("avx512bw") && has!("avx512dq") && has!("avx512vl") && has!("gfni");
            TIER.store(1 + u8::from(yes), Ordering::Relaxed);
            yes
        }
        tier => tier == 2,
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512bw,avx512dq,avx512vl,gfni")]
unsafe fn avx512<R>(f: impl FnOnce() -> R) -> R {
    f()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn avx2<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// Ask the processor to bring the cache line holding `value` closer (a hint: no effect on
/// results, none at all off x86-64). For loops whose next addresses are known early and
/// would each miss the cache.
#[inline(always)]
pub fn prefetch<T>(value: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: prefetching has no observable effect and cannot fault; SSE is baseline on x86-64.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>((value as *const T).cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = value;
}
