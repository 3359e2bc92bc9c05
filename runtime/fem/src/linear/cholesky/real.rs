//! The scalar of a split factor's halves: `f64`, or `f32` for the mixed
//! precision of [`super::FactorPrecision::Mixed`].
//!
//! In single precision the halves' supernodal factorisation moves half the
//! bytes and its dense kernels run twice the SIMD lanes: on the
//! 1M-triangle disk the split factorisation took 0.84–0.85 s against
//! 1.65–1.74 s in double, the solves 0.155–0.163 s against 0.23 s
//! (docs/benchmarks/million.md, "Mixed precision"). That only holds with
//! subnormals flushed to zero: the entries of a sparse factor far from the
//! diagonal decay geometrically and reach f32's subnormal range (below
//! 1.2e-38), where every multiply-add takes a microcode assist; without
//! [`FlushSubnormals`] the same f32 factorisation was 2.5–5× *slower* than
//! f64 (faer's own supernodal LLᵀ on a 500×500 grid, 4.8 s against 1.9 s).
//! A flushed subnormal changes an entry by less than 1.2e-38 absolute, far
//! below f32's rounding of any entry that matters.

use std::ops::{Add, AddAssign, Div, Mul, Sub, SubAssign};

/// `f64` or `f32` (see the module docs).
pub(crate) trait Real:
    faer::traits::RealField
    + Copy
    + Default
    + Into<f64>
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + AddAssign
    + SubAssign
    + Send
    + Sync
    + 'static
{
    /// Whether this is the single-precision scalar (subnormals flushed).
    const SINGLE: bool;
    /// `x` rounded to this precision.
    fn of(x: f64) -> Self;
    /// One, for faer's kernels.
    const ONE: Self;

    /// A guard flushing subnormals on this thread while it lives, for the
    /// single-precision scalar only (see the module docs).
    fn flush_subnormals() -> Option<FlushSubnormals> {
        Self::SINGLE.then(FlushSubnormals::on)
    }
}

impl Real for f64 {
    const SINGLE: bool = false;
    const ONE: Self = 1.0;
    fn of(x: f64) -> Self {
        x
    }
}

impl Real for f32 {
    const SINGLE: bool = true;
    const ONE: Self = 1.0;
    fn of(x: f64) -> Self {
        x as f32
    }
}

/// Flush-to-zero and denormals-are-zero on the current thread (x86-64:
/// MXCSR bits 15 and 6) until dropped, when the previous mode is restored,
/// so no other code on the thread (the assembly after the factorisation)
/// sees the changed mode. A no-op on other targets (correct, only slower
/// for f32).
pub(crate) struct FlushSubnormals {
    #[cfg(target_arch = "x86_64")]
    previous: u32,
}

#[cfg(target_arch = "x86_64")]
impl FlushSubnormals {
    const FTZ_DAZ: u32 = 0x8040;

    #[allow(deprecated)] // the intrinsics are the documented way to set MXCSR
    fn on() -> Self {
        use std::arch::x86_64::{_mm_getcsr, _mm_setcsr};
        // SAFETY: SSE is part of x86-64; setting FTZ/DAZ only changes how
        // this thread rounds subnormal results and reads subnormal inputs.
        let previous = unsafe { _mm_getcsr() };
        unsafe { _mm_setcsr(previous | Self::FTZ_DAZ) };
        FlushSubnormals { previous }
    }

    #[cfg(test)]
    #[allow(deprecated)]
    pub(crate) fn mode() -> u32 {
        // SAFETY: reading MXCSR has no effect.
        unsafe { std::arch::x86_64::_mm_getcsr() }
    }
}

#[cfg(target_arch = "x86_64")]
impl Drop for FlushSubnormals {
    #[allow(deprecated)]
    fn drop(&mut self) {
        // SAFETY: restores the mode read in `on`.
        unsafe { std::arch::x86_64::_mm_setcsr(self.previous) };
    }
}

#[cfg(not(target_arch = "x86_64"))]
impl FlushSubnormals {
    fn on() -> Self {
        FlushSubnormals {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `black_box` keeps the compiler from folding the product at compile time.
    fn tiny_product() -> f32 {
        std::hint::black_box(1e-20f32) * std::hint::black_box(1e-20f32)
    }

    #[test]
    fn subnormals_are_flushed_only_inside_the_guard_of_f32() {
        assert!(tiny_product() > 0.0, "1e-40 is a subnormal f32");
        assert!(f64::flush_subnormals().is_none());
        {
            let _guard = f32::flush_subnormals().expect("f32 flushes");
            #[cfg(target_arch = "x86_64")]
            assert_eq!(tiny_product(), 0.0);
        }
        assert!(tiny_product() > 0.0, "the mode is restored on drop");
    }

    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_previous_mode_is_restored_exactly() {
        let before = FlushSubnormals::mode();
        drop(FlushSubnormals::on());
        assert_eq!(FlushSubnormals::mode(), before);
    }

    #[test]
    fn of_rounds_to_the_precision() {
        assert_eq!(f32::of(0.1), 0.1f32);
        assert_eq!(f64::of(0.1), 0.1);
        let x: f64 = f32::of(1.0 + 1e-12).into();
        assert_eq!(x, 1.0);
    }
}
