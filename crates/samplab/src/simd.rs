//! Run-time choice of vector instructions: hot loops are written as plain loops over
//! arrays, and [`wide`] compiles them for AVX-512 or AVX2 where the processor has them.
//! The AVX-512 tier asks for the byte, word and bit-reversal extensions too (BW, DQ, VL,
//! GFNI: Ice Lake, Zen 4 and later), which turn the bit reversals of Owen-scrambled
//! Sobol' points into two instructions; an older AVX-512 processor takes the AVX2 tier.
//! Every lane does the same operations in the same order on each instruction set (no fused
//! multiply-add), so the results are the same bits; [`on_each_instruction_set`] lets tests
//! check it for a kernel, and [`LIMIT_VARIABLE`] (`SAMPLAB_SIMD=avx2`) runs a whole process
//! on a narrower tier, so that a command's bytes can be compared across tiers (the CLI's
//! test `every_instruction_set_makes_the_same_bytes`) and a narrower path timed on a wider
//! machine.

use crate::error::{Error, Result};

/// An instruction set [`wide`] compiles hot loops for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
#[non_exhaustive]
pub enum Tier {
    /// x86-64's baseline (SSE2), or whatever the target has off x86-64.
    Baseline,
    /// AVX2.
    Avx2,
    /// AVX-512 with BW, DQ, VL and GFNI.
    Avx512,
}

/// The environment variable that limits [`wide`] to a narrower tier than the processor's
/// (`baseline`, `avx2` or `avx512`): to test and time a narrower path on a wider machine.
pub const LIMIT_VARIABLE: &str = "SAMPLAB_SIMD";

impl Tier {
    /// Every tier, narrowest first.
    pub const ALL: [Tier; 3] = [Tier::Baseline, Tier::Avx2, Tier::Avx512];

    /// Its name, as [`LIMIT_VARIABLE`] takes it.
    pub fn name(self) -> &'static str {
        match self {
            Tier::Baseline => "baseline",
            Tier::Avx2 => "avx2",
            Tier::Avx512 => "avx512",
        }
    }

    /// The widest tier this processor has.
    pub fn detected() -> Tier {
        #[cfg(target_arch = "x86_64")]
        {
            use std::arch::is_x86_feature_detected as has;
            if has!("avx512f") && has!("avx512bw") && has!("avx512dq") && has!("avx512vl") && has!("gfni") {
                return Tier::Avx512;
            }
            if has!("avx2") {
                return Tier::Avx2;
            }
        }
        Tier::Baseline
    }

    /// The tier [`LIMIT_VARIABLE`] asks for (unset: the processor's).
    ///
    /// # Errors
    /// [`Error::Parse`] for a word that names no tier, or a tier this processor lacks.
    pub fn from_environment() -> Result<Tier> {
        let detected = Tier::detected();
        let Some(value) = std::env::var_os(LIMIT_VARIABLE) else { return Ok(detected) };
        let word = value.to_string_lossy();
        let bad = |reason: String| Error::Parse { location: format!("{LIMIT_VARIABLE}={word}"), reason };
        let tier = Tier::ALL
            .into_iter()
            .find(|t| t.name() == word)
            .ok_or_else(|| bad("not an instruction set (baseline, avx2 or avx512)".into()))?;
        if tier > detected {
            return Err(bad(format!("this processor has {} at most", detected.name())));
        }
        Ok(tier)
    }
}

/// The tier [`wide`] uses: [`Tier::from_environment`], or the processor's where the
/// variable is not valid (a front end that wants the error calls `from_environment` itself
/// first, as the CLI does). Read once, then one load per call (wide runs per pixel in the
/// renderer).
#[inline(always)]
pub fn tier() -> Tier {
    use std::sync::atomic::{AtomicU8, Ordering};
    // 0: not yet read, else 1 + the tier's place in Tier::ALL
    static TIER: AtomicU8 = AtomicU8::new(0);
    match TIER.load(Ordering::Relaxed) {
        0 => {
            let tier = Tier::from_environment().unwrap_or_else(|_| Tier::detected());
            TIER.store(1 + tier as u8, Ordering::Relaxed);
            tier
        }
        n => Tier::ALL[usize::from(n - 1)],
    }
}

/// `f()` compiled for the widest vector instructions [`tier`] allows (AVX-512, AVX2 or the
/// baseline), chosen at run time. `f` and everything it calls must be inlined into it
/// (`#[inline(always)]`, including on the closure) to be compiled wide.
#[inline(always)]
pub fn wide<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    match tier() {
        // SAFETY: the processor supports the tier's features (`tier` is at most the detected one).
        Tier::Avx512 => return unsafe { avx512(f) },
        // SAFETY: as above.
        Tier::Avx2 => return unsafe { avx2(f) },
        Tier::Baseline => {}
    }
    f()
}

/// `f()` on every instruction set this processor has (baseline, AVX2, AVX-512), for tests
/// that they give the same bits. (Only `f`'s own code is compiled for each: a [`wide`]
/// inside it chooses by [`tier`]; a whole command runs on one tier with [`LIMIT_VARIABLE`].)
pub fn on_each_instruction_set<R>(f: impl Fn() -> R) -> Vec<R> {
    #[allow(unused_mut)] // one entry only off x86-64
    let mut out = vec![f()];
    #[cfg(target_arch = "x86_64")]
    {
        let detected = Tier::detected();
        if detected >= Tier::Avx2 {
            // SAFETY: the processor supports AVX2, checked just above.
            out.push(unsafe { avx2(&f) });
        }
        if detected == Tier::Avx512 {
            // SAFETY: the processor supports the tier's features, checked just above.
            out.push(unsafe { avx512(&f) });
        }
    }
    out
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
