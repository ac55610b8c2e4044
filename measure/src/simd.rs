//! Run-time dispatch to SIMD-compiled copies of data-parallel loops.
//!
//! A loop body is written once as an `#[inline(always)]` function over slices; `dispatch!` calls
//! a copy compiled with AVX-512 or AVX2+FMA enabled when the CPU has them (checked at run time,
//! so the binary still runs on any x86-64), and the portable copy otherwise. The environment
//! variable `ROUGE_SIMD` (`avx512`, `avx2` or `portable`) caps the level, for benchmarks that
//! compare them and for debugging.

use std::sync::OnceLock;

/// Instruction-set levels the fast paths are compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SimdLevel {
    /// Baseline x86-64 (SSE2) or another architecture.
    Portable,
    /// AVX2 with FMA.
    Avx2,
    /// AVX-512 F/DQ/VL with FMA.
    Avx512,
}

/// The level the fast paths run at: the best the CPU has, capped by `ROUGE_SIMD`.
pub fn simd_level() -> SimdLevel {
    static LEVEL: OnceLock<SimdLevel> = OnceLock::new();
    *LEVEL.get_or_init(|| {
        #[cfg(target_arch = "x86_64")]
        let cpu = if std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512dq")
            && std::arch::is_x86_feature_detected!("avx512vl")
            && std::arch::is_x86_feature_detected!("fma")
        {
            SimdLevel::Avx512
        } else if std::arch::is_x86_feature_detected!("avx2") && std::arch::is_x86_feature_detected!("fma") {
            SimdLevel::Avx2
        } else {
            SimdLevel::Portable
        };
        #[cfg(not(target_arch = "x86_64"))]
        let cpu = SimdLevel::Portable;
        let cap = match std::env::var("ROUGE_SIMD").as_deref() {
            Ok("portable") => SimdLevel::Portable,
            Ok("avx2") => SimdLevel::Avx2,
            _ => SimdLevel::Avx512,
        };
        cpu.min(cap)
    })
}

/// `dispatch!(generic, avx2, avx512, (args...))`: calls the best variant [`simd_level`] allows.
macro_rules! dispatch {
    ($generic:ident, $avx2:ident, $avx512:ident, ($($arg:expr),*)) => {{
        #[cfg(target_arch = "x86_64")]
        {
            match $crate::simd::simd_level() {
                // SAFETY: simd_level() returns Avx512 only when the CPU has AVX-512F/DQ/VL and FMA.
                $crate::simd::SimdLevel::Avx512 => unsafe { $avx512($($arg),*) },
                // SAFETY: simd_level() returns Avx2 only when the CPU has AVX2 and FMA.
                $crate::simd::SimdLevel::Avx2 => unsafe { $avx2($($arg),*) },
                $crate::simd::SimdLevel::Portable => $generic($($arg),*),
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        {
            $generic($($arg),*)
        }
    }};
}
