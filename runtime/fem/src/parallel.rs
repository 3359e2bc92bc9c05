//! Small parallel helpers shared by the assembler and the linear solvers.
//!
//! Reductions are *deterministic*: a slice is cut into fixed-size chunks, each
//! chunk is summed sequentially (in parallel across chunks) into a
//! preallocated partial-sum buffer, and the partials are added in order. The
//! result therefore does not depend on rayon's work stealing, so two runs on
//! the same input produce bit-identical energies (line-search comparisons and
//! reported numbers are reproducible).

use rayon::prelude::*;

/// Elements per chunk of a deterministic reduction.
pub(crate) const CHUNK: usize = 2048;

/// Passes over fewer items than this run on the calling thread. Waking the
/// pool's other thread for each colour of an assembly, each reduction and
/// each line-search bound costs more than it saves on small meshes:
/// hand_1_i_f5000 (4999 triangles, SD, 2026-12-02) assembled in 2.3–2.7 ms
/// per Newton step on two threads against 1.6 ms on one, and its solve took
/// 0.41–0.44 s against 0.34 s; camelhead (22.7k) assembles 1.36× faster on
/// two.
pub(crate) const MIN_PARALLEL: usize = 8192;

/// rayon's `with_min_len` for a pass over `n` items with grain `grain`:
/// no split at all (the calling thread runs it) below [`MIN_PARALLEL`].
#[inline]
pub(crate) fn min_len(n: usize, grain: usize) -> usize {
    if n < MIN_PARALLEL { usize::MAX } else { grain }
}

/// Number of partial sums needed to reduce `n` items.
#[inline]
pub(crate) fn n_chunks(n: usize) -> usize {
    n.div_ceil(CHUNK).max(1)
}

/// Σ_i f(i) for i in 0..n, deterministic, using `partials` (resized only if
/// too short, i.e. never after the first call with the same `n`).
pub(crate) fn sum_indexed<F>(n: usize, partials: &mut Vec<f64>, f: F) -> f64
where
    F: Fn(usize) -> f64 + Sync,
{
    let m = n_chunks(n);
    if partials.len() < m {
        partials.resize(m, 0.0);
    }
    let grain = min_len(n, 1);
    partials[..m]
        .par_iter_mut()
        .with_min_len(grain)
        .enumerate()
        .for_each(|(c, p)| {
            let lo = c * CHUNK;
            let hi = (lo + CHUNK).min(n);
            let mut s = 0.0;
            for i in lo..hi {
                s += f(i);
            }
            *p = s;
        });
    partials[..m].iter().sum()
}

/// min_i f(i) for i in 0..n (exact, hence order independent). `+∞` when n = 0.
pub(crate) fn min_indexed<F>(n: usize, f: F) -> f64
where
    F: Fn(usize) -> f64 + Sync + Send,
{
    (0..n)
        .into_par_iter()
        .with_min_len(min_len(n, 256))
        .map(f)
        .reduce(|| f64::INFINITY, f64::min)
}

/// Deterministic dot product.
pub(crate) fn dot(a: &[f64], b: &[f64], partials: &mut Vec<f64>) -> f64 {
    debug_assert_eq!(a.len(), b.len());
    sum_indexed(a.len(), partials, |i| a[i] * b[i])
}

/// max_i |a_i| (0 for an empty slice; NaN entries propagate as NaN).
pub(crate) fn norm_inf(a: &[f64]) -> f64 {
    a.par_iter().with_min_len(4096).map(|v| v.abs()).reduce(
        || 0.0,
        |x, y| {
            if x.is_nan() || y.is_nan() {
                f64::NAN
            } else {
                x.max(y)
            }
        },
    )
}

/// A raw pointer that may be shared across rayon tasks.
///
/// Used for scatter-adds where the caller *proves* disjointness: within one
/// colour of the stencil colouring no two stencils share a free vertex, so
/// they write disjoint gradient entries and disjoint Hessian slots.
#[derive(Clone, Copy)]
pub(crate) struct SharedMut(*mut f64);

// SAFETY: the pointer is only dereferenced at indices that the colouring
// guarantees are written by exactly one task at a time (see `assembly`).
unsafe impl Send for SharedMut {}
unsafe impl Sync for SharedMut {}

impl SharedMut {
    pub(crate) fn new(s: &mut [f64]) -> Self {
        SharedMut(s.as_mut_ptr())
    }

    /// `*p[i] += v`.
    ///
    /// # Safety
    /// `i` is in bounds of the slice this was created from, the slice
    /// outlives every use, and no other task accesses index `i` concurrently.
    #[inline]
    pub(crate) unsafe fn add(self, i: usize, v: f64) {
        unsafe { *self.0.add(i) += v };
    }

    /// `*p[i] = v`, with the same contract as [`SharedMut::add`].
    #[inline]
    pub(crate) unsafe fn set(self, i: usize, v: f64) {
        unsafe { *self.0.add(i) = v };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_are_exact_on_integers_and_deterministic() {
        let n = 3 * CHUNK + 17;
        let mut p = Vec::new();
        let s = sum_indexed(n, &mut p, |i| i as f64);
        assert_eq!(s, (n * (n - 1) / 2) as f64);
        let a: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let d1 = dot(&a, &a, &mut p);
        let d2 = dot(&a, &a, &mut p);
        assert_eq!(d1.to_bits(), d2.to_bits());
        assert_eq!(sum_indexed(0, &mut p, |_| 1.0), 0.0);
    }

    #[test]
    fn min_and_norm() {
        assert_eq!(min_indexed(0, |_| 1.0), f64::INFINITY);
        assert_eq!(min_indexed(10, |i| 5.0 - i as f64), -4.0);
        assert_eq!(norm_inf(&[1.0, -3.0, 2.0]), 3.0);
        assert!(norm_inf(&[1.0, f64::NAN]).is_nan());
        assert_eq!(norm_inf(&[]), 0.0);
    }
}
