//! A solve with a numeric Cholesky factor of the matrix itself: direct for
//! a double factor; for a mixed-precision one (single-precision halves,
//! `cholesky/precision.rs`) CG in double on the matrix, preconditioned by
//! the factor.
//!
//! With M = L̃L̃ᵀ = A + E, ‖E‖ ≈ 2⁻²⁴‖A‖, the preconditioned matrix M⁻¹A has
//! its eigenvalues in 1 ± O(κ(A)·2⁻²⁴), so each CG iteration (one solve with
//! the factor, one product with A in double) cuts the residual by about that
//! much: one iteration is x = α M⁻¹b, the factor's own solution optimally
//! scaled, and its residual b − A x is then measured in double. The solve
//! asks for the relative residual `rel_tol`, capped at [`MIXED_REL_TOL`];
//! if [`MIXED_MAX_CG`] iterations do not reach it (κ too large for single
//! precision) the factor turns double for good and the step is factorised
//! again and solved directly.

use super::SolveInfo;
use super::cholesky::CholeskyFactor;
use super::pcg::Pcg;
use crate::pattern::Pattern;

/// The largest relative residual ‖A x − b‖/‖b‖ a mixed-precision solve
/// accepts, whatever the caller's tolerance.
pub const MIXED_REL_TOL: f64 = 1e-3;

/// CG iterations a mixed-precision solve may take before the factor falls
/// back to double.
pub const MIXED_MAX_CG: usize = 10;

/// Solve `values`·`out` = `rhs` with `f`, the numeric factor of `values`
/// (module docs); `cg` is CG state for `pattern`. A factor that cannot
/// solve (none, or its double fallback failed) leaves NaN in `out`.
pub(crate) fn solve_with_factor(
    f: &mut CholeskyFactor,
    cg: &mut Pcg,
    pattern: &Pattern,
    values: &[f64],
    rhs: &[f64],
    out: &mut [f64],
    rel_tol: f64,
) -> SolveInfo {
    let mut info = SolveInfo::default();
    if f.is_mixed() {
        let tol = rel_tol.min(MIXED_REL_TOL);
        let refined = cg.solve_preconditioned(values, rhs, out, tol, MIXED_MAX_CG, |r, z| {
            z.copy_from_slice(r);
            if !f.solve_in_place(z) {
                z.fill(f64::NAN);
            }
        });
        info.iterations = refined.iterations;
        info.relative_residual = refined.relative_residual;
        if !refined.negative_curvature && refined.relative_residual <= tol {
            return info;
        }
        // single precision is not enough for this matrix: double from now on
        if f.to_double().is_err() || f.factorize(pattern, values).is_err() {
            out.fill(f64::NAN);
            return info;
        }
        info.factorizations = 1;
        info.relative_residual = 0.0;
    }
    out.copy_from_slice(rhs);
    if !f.solve_in_place(out) {
        out.fill(f64::NAN);
    }
    info
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::cholesky::{CholeskyParams, FactorPrecision, FactorizeError};
    use crate::linear::ordering::tests::grid;

    /// A rayon pool of two threads: the split (and so the mixed precision)
    /// needs two.
    fn two_threads<R: Send>(f: impl FnOnce() -> R + Send) -> R {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(f)
    }

    /// A grid large enough to split, a diagonally dominant matrix on it,
    /// and b = A·x* for a smooth x*.
    fn system() -> (Pattern, Vec<f64>, Vec<f64>) {
        let p = grid(100, 100, 2);
        let mut v = vec![-1.0; p.nnz()];
        for j in 0..p.n() {
            v[p.diag_slot(j)] = 31.0;
        }
        let xs: Vec<f64> = (0..p.n()).map(|i| (0.01 * i as f64).sin()).collect();
        let mut b = vec![0.0; p.n()];
        p.sym_matvec(&v, &xs, &mut b);
        (p, v, b)
    }

    fn factor(p: &Pattern, precision: FactorPrecision) -> CholeskyFactor {
        let params = CholeskyParams {
            precision,
            ..Default::default()
        };
        CholeskyFactor::analyze_with(p, params).unwrap()
    }

    fn rel_residual(p: &Pattern, v: &[f64], x: &[f64], b: &[f64]) -> f64 {
        let mut ax = vec![0.0; p.n()];
        p.sym_matvec(v, x, &mut ax);
        let norm = |u: &mut dyn Iterator<Item = f64>| u.map(|a| a * a).sum::<f64>().sqrt();
        norm(&mut ax.iter().zip(b).map(|(a, b)| a - b)) / norm(&mut b.iter().copied())
    }

    #[test]
    fn a_mixed_factor_is_refined_to_the_asked_residual_in_double() {
        two_threads(|| {
            let (p, v, b) = system();
            let mut f = factor(&p, FactorPrecision::Mixed);
            assert!(f.is_mixed(), "as asked, on a split factor");
            f.factorize(&p, &v).unwrap();
            let mut cg = Pcg::new(&p);
            let mut x = vec![0.0; p.n()];
            // the factor's own solve is single precision only
            let mut raw = b.clone();
            assert!(f.solve_in_place(&mut raw));
            let single = rel_residual(&p, &v, &raw, &b);
            assert!(single > 1e-11 && single < 1e-4, "{single:e}");
            for (asked, want) in [(0.1, MIXED_REL_TOL), (1e-10, 1e-9)] {
                let info = solve_with_factor(&mut f, &mut cg, &p, &v, &b, &mut x, asked);
                let res = rel_residual(&p, &v, &x, &b);
                assert!(res <= want, "asked {asked:e}: {res:e}");
                assert!(info.iterations >= 1 && info.factorizations == 0, "{info:?}");
                assert!(
                    info.relative_residual <= asked.min(MIXED_REL_TOL),
                    "{info:?}"
                );
            }
            assert!(f.is_mixed(), "no fallback was needed");
        });
    }

    /// CG that cannot converge with this factor: here the factor of another
    /// matrix (its diagonal scaled by 1 … 10⁶) stands in for a matrix too
    /// ill-conditioned for single precision. The factor turns double, the
    /// step is factorised again and solved directly.
    #[test]
    fn a_mixed_factor_that_cannot_converge_falls_back_to_double() {
        two_threads(|| {
            let (p, v, _) = system();
            let mut w = v.clone();
            for j in 0..p.n() {
                let scale = 10f64.powf(6.0 * ((j * 7919) % 1000) as f64 / 1000.0);
                w[p.diag_slot(j)] *= scale;
            }
            let xs: Vec<f64> = (0..p.n()).map(|i| (0.02 * i as f64).cos()).collect();
            let mut b = vec![0.0; p.n()];
            p.sym_matvec(&w, &xs, &mut b);
            let mut f = factor(&p, FactorPrecision::Mixed);
            f.factorize(&p, &v).unwrap();
            let mut cg = Pcg::new(&p);
            let mut x = vec![0.0; p.n()];
            let info = solve_with_factor(&mut f, &mut cg, &p, &w, &b, &mut x, 1e-6);
            assert_eq!(info.iterations, MIXED_MAX_CG, "{info:?}");
            assert_eq!(info.factorizations, 1, "{info:?}");
            assert!(!f.is_mixed(), "double for good");
            let mut d = factor(&p, FactorPrecision::Double);
            d.factorize(&p, &w).unwrap();
            let mut direct = b.clone();
            assert!(d.solve_in_place(&mut direct));
            assert_eq!(x, direct, "the same solve as a double factor");
        });
    }

    /// A matrix positive definite in double whose rounding to single is
    /// singular (every vertex's 2×2 block [[1, 1 − 10⁻¹⁰], [1 − 10⁻¹⁰, 1]],
    /// 1 − 10⁻¹⁰ = 1 in f32, smallest eigenvalue 10⁻¹⁰, plus a coupling of
    /// norm below 10⁻¹²): the single
    /// factorisation breaks down, the factor turns double and factorises.
    #[test]
    fn a_single_precision_breakdown_factorises_in_double() {
        two_threads(|| {
            let p = grid(100, 100, 2);
            let mut v = vec![0.0; p.nnz()];
            for j in 0..p.n() {
                let col = p.col_ptr()[j]..p.col_ptr()[j + 1];
                for (e, &i) in v[col.clone()].iter_mut().zip(&p.row_idx()[col]) {
                    *e = if i == j {
                        1.0
                    } else if i / 2 == j / 2 {
                        1.0 - 1e-10
                    } else {
                        -1e-12 / 13.0
                    };
                }
            }
            let mut f = factor(&p, FactorPrecision::Mixed);
            assert!(f.is_mixed());
            f.factorize(&p, &v).unwrap();
            assert!(!f.is_mixed(), "single precision broke down: double");
            let mut d = factor(&p, FactorPrecision::Double);
            d.factorize(&p, &v).unwrap();
            let b = vec![1.0; p.n()];
            let (mut x, mut y) = (b.clone(), b.clone());
            assert!(f.solve_in_place(&mut x) && d.solve_in_place(&mut y));
            assert_eq!(x, y);
        });
    }

    /// An indefinite matrix (the raw Hessians of a trust-region step) fails
    /// in double too: reported, and the factor stays mixed; once seen, later
    /// breakdowns are reported without the double retry.
    #[test]
    fn an_indefinite_matrix_is_reported_and_the_factor_stays_mixed() {
        two_threads(|| {
            let (p, v, b) = system();
            let mut bad = v.clone();
            bad[p.diag_slot(p.n() / 3)] = -5.0;
            let mut f = factor(&p, FactorPrecision::Mixed);
            for _ in 0..2 {
                let e = f.factorize(&p, &bad).unwrap_err();
                assert!(matches!(e, FactorizeError::NotPositiveDefinite(_)));
                assert!(f.is_mixed() && f.indefinite_seen());
            }
            f.factorize(&p, &v).unwrap();
            let mut x = vec![0.0; p.n()];
            let info = solve_with_factor(&mut f, &mut Pcg::new(&p), &p, &v, &b, &mut x, 1e-8);
            assert!(info.relative_residual <= 1e-8 && f.is_mixed(), "{info:?}");
        });
    }

    #[test]
    fn a_double_factor_solves_directly() {
        two_threads(|| {
            let (p, v, b) = system();
            let mut f = factor(&p, FactorPrecision::Double);
            assert!(!f.is_mixed() && f.split().is_some());
            f.factorize(&p, &v).unwrap();
            let mut x = vec![0.0; p.n()];
            let info = solve_with_factor(&mut f, &mut Pcg::new(&p), &p, &v, &b, &mut x, 0.1);
            assert_eq!(info, SolveInfo::default());
            assert!(rel_residual(&p, &v, &x, &b) <= 1e-13);
        });
    }
}
