//! Leave the vector unit clean after runtime-dispatched AVX/AVX-512 code.
//!
//! faer's dense kernels (the `gemm` and `pulp` crates) choose AVX-512 or
//! AVX2 at run time and can return with the upper halves of the vector
//! registers still marked in use. Until that state is cleared, every
//! legacy-SSE instruction on the same thread (glibc's `atan2` and `sincos`,
//! and all of ecc's own code, which is compiled for baseline x86-64) waits
//! on the whole register: on this project's 2-core Xeon the Hessian
//! assembly ran 1.8–2× slower on rayon workers that had just run part of a
//! split Cholesky factorisation (docs/benchmarks/threads.md, "The vector
//! unit"). [`clear_upper_simd`] is `vzeroupper`: call it on a thread after it
//! ran such a kernel and before it runs scalar maths again.

/// `vzeroupper` on the calling thread when the CPU has AVX; nothing
/// otherwise (and on other architectures).
pub fn clear_upper_simd() {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx") {
        // SAFETY: `vzeroupper` needs AVX, checked just above. It zeroes bits
        // 128 and up of the vector registers, which no Rust value keeps live
        // across a function call (they are caller-saved), so no state of the
        // caller is lost.
        unsafe { std::arch::x86_64::_mm256_zeroupper() };
    }
}

/// Whether the upper halves of the vector registers xmm0–15 (bits 128 and
/// up: the AVX and AVX-512 "ZMM_Hi256" state components) are in use on the
/// calling thread, read from the XINUSE bitmap (`xgetbv` with ECX = 1).
/// `None` where the CPU cannot say (no AVX, or no `xgetbv` ECX = 1). For
/// tests of [`clear_upper_simd`]'s placement.
pub fn upper_simd_in_use() -> Option<bool> {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::__cpuid_count;
        if !(std::arch::is_x86_feature_detected!("avx")
            && std::arch::is_x86_feature_detected!("xsave"))
        {
            return None;
        }
        // CPUID.(EAX=0Dh, ECX=1):EAX bit 2: XGETBV with ECX = 1 is supported
        #[allow(unused_unsafe)]
        // SAFETY: CPUID is available on every x86-64 CPU.
        let leaf = unsafe { __cpuid_count(0xD, 1) };
        if leaf.eax & (1 << 2) == 0 {
            return None;
        }
        /// XINUSE, the state components not in their initial state.
        #[target_feature(enable = "xsave")]
        unsafe fn xinuse() -> u64 {
            // SAFETY (of the caller): XSAVE and XGETBV ECX = 1 checked.
            unsafe { std::arch::x86_64::_xgetbv(1) }
        }
        // SAFETY: XSAVE (hence XGETBV) and its ECX = 1 form are supported,
        // checked above.
        let bits = unsafe { xinuse() };
        // bit 2: YMM upper halves of xmm0–15; bit 6: ZMM bits 256–511 of
        // zmm0–15 (both cleared by `vzeroupper`)
        Some(bits & ((1 << 2) | (1 << 6)) != 0)
    }
    #[cfg(not(target_arch = "x86_64"))]
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clearing_leaves_the_upper_halves_unused() {
        clear_upper_simd();
        if let Some(dirty) = upper_simd_in_use() {
            assert!(!dirty, "vzeroupper must leave the upper halves unused");
        }
    }
}
