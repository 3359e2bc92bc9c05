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
