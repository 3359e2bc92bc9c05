//! Cyclic Jacobi eigensolver for the small symmetric matrices of the exact
//! element projection (the congruence C of [`super::congruence`], 4×4 for
//! triangles and 9×9 for tetrahedra): fixed-size arrays, no heap, no
//! nalgebra dimension machinery.
//!
//! **Method** (Golub & Van Loan, *Matrix Computations*, 4th ed., §8.5.2–8.5.3;
//! the rotation of Rutishauser 1966). A sweep visits every off-diagonal pair
//! (p, q), p < q, in rounds of disjoint pairs ([`tournament`]) and annihilates
//! a_pq with the plane rotation J(p, q, θ):
//!
//! (1) ϑ = (a_qq − a_pp) / (2 a_pq),  t = sign(ϑ) / (|ϑ| + √(ϑ² + 1)),
//!     c = 1/√(t² + 1),  s = t c  (|θ| ≤ π/4, the smaller root),
//!
//! (2) a_pp ← a_pp − t a_pq,  a_qq ← a_qq + t a_pq,  a_pq ← 0,
//!     a_rp ← c a_rp − s a_rq,  a_rq ← s a_rp + c a_rq  (r ≠ p, q),
//!
//! and accumulates the same rotation into the eigenvector rows
//! v_p ← c v_p − s v_q, v_q ← s v_p + c v_q. off(A)² = Σ_{p≠q} a_pq² falls by
//! 2 a_pq² per rotation, and the sweep order converges quadratically once
//! off(A) is below the smallest eigenvalue gap (ultimately also for repeated
//! eigenvalues): 4×4 matrices take 3–5 sweeps, 9×9 ones 5–8.
//!
//! **Stopping rule.** A rotation is skipped when |a_pq| ≤ τ = ε_mach max|a_ij|
//! (of the input; ‖A‖_F, invariant under the rotations, is between max|a_ij|
//! and R max|a_ij|, and is not formed: its square would overflow above 1e154);
//! the iteration stops after a sweep without any rotation. Then
//! ‖A − V Λ Vᵀ‖_F ≲ R τ plus the rounding
//! of the rotations (each orthogonal to working precision): the eigensystem
//! is backward stable to a small multiple of ε_mach ‖A‖, as nalgebra's
//! `SymmetricEigen` (tridiagonalisation + implicit QR) is, and Jacobi's
//! eigenvalues are in addition accurate relative to |λ| on graded matrices
//! (Demmel & Veselić 1992).
//!
//! **Failure.** A non-finite entry, or no convergence within
//! [`MAX_SWEEPS`] sweeps (never observed: the bound is a guard), returns
//! `None`, and the caller falls back to a general eigensolver.

/// Upper bound on the number of sweeps (quadratic convergence needs < 10 for
/// R ≤ 9; the bound only guards against non-termination).
pub const MAX_SWEEPS: usize = 40;

/// The pairs (p, q) of one sweep in the round-robin ("tournament") order of
/// Brent & Luk (1985): R − 1 rounds (R even) or R rounds (R odd) of ⌊R/2⌋
/// disjoint pairs. Rotations of disjoint pairs commute and their angles (1)
/// depend on disjoint entries, so a round computes all its angles first and
/// the latencies of their square roots and divisions overlap. The ordering
/// converges quadratically like the row-cyclic one. `N` = R rounded up to
/// even; a pair containing the dummy index R (R odd) is a bye, q = `usize::MAX`.
const fn tournament<const N: usize>(r: usize) -> [[(usize, usize); 5]; 9] {
    let mut out = [[(usize::MAX, usize::MAX); 5]; 9];
    let mut round = 0;
    while round < N - 1 {
        let mut k = 0;
        while k < N / 2 {
            // Circle method: player 0 fixed, the others rotate.
            let (a, b) = (circle::<N>(k, round), circle::<N>(N - 1 - k, round));
            let (p, q) = if a < b { (a, b) } else { (b, a) };
            out[round][k] = if q >= r { (p, usize::MAX) } else { (p, q) };
            k += 1;
        }
        round += 1;
    }
    out
}

/// Seat `i`'s player in round `round` of the circle method (seat 0 fixed).
const fn circle<const N: usize>(i: usize, round: usize) -> usize {
    if i == 0 {
        0
    } else {
        (i + round - 1) % (N - 1) + 1
    }
}

/// Pairs per sweep: rounds × slots (R = 4: 3 × 2; R = 9: 9 × 5, one bye each).
const ROUNDS4: [[(usize, usize); 5]; 9] = tournament::<4>(4);
const ROUNDS9: [[(usize, usize); 5]; 9] = tournament::<10>(9);

/// Eigenvalues (unsorted) and unit eigenvectors (`vecs[k]` belongs to
/// `vals[k]`) of the symmetric R×R matrix `a` (only its upper triangle is
/// read), or `None` when `a` is not finite or the sweeps did not converge.
/// R must be 4 or 9 (the congruence sizes); other sizes return `None`.
pub fn jacobi_eigen<const R: usize>(a: &[[f64; R]; R]) -> Option<([f64; R], [[f64; R]; R])> {
    let (rounds, nr, slots) = match R {
        4 => (&ROUNDS4, 3, 2),
        9 => (&ROUNDS9, 9, 5),
        _ => return None,
    };
    let mut a = symmetrised(a)?;
    let mut v = [[0.0; R]; R];
    for (k, row) in v.iter_mut().enumerate() {
        row[k] = 1.0;
    }
    let tau = f64::EPSILON * a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for _ in 0..MAX_SWEEPS {
        let mut rotated = false;
        for round in &rounds[..nr] {
            // Angles of the round's pairs (independent), then the rotations.
            let mut rot = [(0usize, 0usize, 0.0f64, 0.0f64, 0.0f64); 5];
            let mut n = 0;
            for &(p, q) in &round[..slots] {
                if q != usize::MAX && a[p][q].abs() > tau {
                    let (t, c, s) = angle(a[p][p], a[q][q], a[p][q]);
                    rot[n] = (p, q, t, c, s);
                    n += 1;
                }
            }
            for &(p, q, t, c, s) in &rot[..n] {
                rotate(&mut a, &mut v, p, q, t, c, s);
            }
            rotated |= n > 0;
        }
        if !rotated {
            return Some((std::array::from_fn(|k| a[k][k]), v));
        }
    }
    None
}

/// `a` with its lower triangle copied from the upper one; `None` if not finite.
fn symmetrised<const R: usize>(a: &[[f64; R]; R]) -> Option<[[f64; R]; R]> {
    let mut s = *a;
    for p in 0..R {
        for q in p..R {
            if !a[p][q].is_finite() {
                return None;
            }
            s[q][p] = a[p][q];
        }
    }
    Some(s)
}

/// (t, c, s) of eq. (1) for a_pp, a_qq, a_pq ≠ 0.
#[inline(always)]
fn angle(app: f64, aqq: f64, apq: f64) -> (f64, f64, f64) {
    let theta = (aqq - app) / (2.0 * apq);
    // For |ϑ| > 1e150, ϑ² would overflow: t = 1/(2ϑ) to working precision.
    let t = if theta.abs() > 1e150 {
        0.5 / theta
    } else {
        theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
    };
    let c = 1.0 / (t * t + 1.0).sqrt();
    (t, c, t * c)
}

/// The Jacobi rotation (2) annihilating a_pq, accumulated into `v`.
#[inline(always)]
fn rotate<const R: usize>(
    a: &mut [[f64; R]; R],
    v: &mut [[f64; R]; R],
    p: usize,
    q: usize,
    t: f64,
    c: f64,
    s: f64,
) {
    let apq = a[p][q];
    a[p][p] -= t * apq;
    a[q][q] += t * apq;
    a[p][q] = 0.0;
    a[q][p] = 0.0;
    for r in 0..R {
        if r != p && r != q {
            let (arp, arq) = (a[r][p], a[r][q]);
            let (np, nq) = (c * arp - s * arq, s * arp + c * arq);
            a[r][p] = np;
            a[p][r] = np;
            a[r][q] = nq;
            a[q][r] = nq;
        }
    }
    for i in 0..R {
        let (vp, vq) = (v[p][i], v[q][i]);
        v[p][i] = c * vp - s * vq;
        v[q][i] = s * vp + c * vq;
    }
}

#[cfg(test)]
mod tests {
    use super::jacobi_eigen;

    /// ‖A − Σ λ v vᵀ‖_max and ‖VᵀV − I‖_max.
    fn residuals<const R: usize>(a: &[[f64; R]; R]) -> (f64, f64) {
        let (vals, vecs) = jacobi_eigen(a).expect("converges");
        let mut rec = 0.0f64;
        let mut orth = 0.0f64;
        for i in 0..R {
            for j in 0..R {
                let s: f64 = (0..R).map(|k| vals[k] * vecs[k][i] * vecs[k][j]).sum();
                rec = rec.max((s - a[i][j]).abs());
                let d: f64 = (0..R).map(|l| vecs[i][l] * vecs[j][l]).sum();
                orth = orth.max((d - f64::from(u8::from(i == j))).abs());
            }
        }
        (rec, orth)
    }
    #[test]
    fn a_sweep_visits_every_pair_once() {
        for (rounds, nr, slots, r) in [(&super::ROUNDS4, 3, 2, 4), (&super::ROUNDS9, 9, 5, 9)] {
            let mut seen = vec![0; r * r];
            for round in &rounds[..nr] {
                let mut used = vec![false; r];
                for &(p, q) in &round[..slots] {
                    if q == usize::MAX {
                        continue;
                    }
                    assert!(p < q && q < r && !used[p] && !used[q], "{p} {q}");
                    used[p] = true;
                    used[q] = true;
                    seen[p * r + q] += 1;
                }
            }
            for p in 0..r {
                for q in p + 1..r {
                    assert_eq!(seen[p * r + q], 1, "pair ({p}, {q}) of {r}");
                }
            }
        }
    }

    #[test]
    fn diagonal_and_zero_matrices_need_no_rotation() {
        let mut d = [[0.0; 4]; 4];
        for (k, row) in d.iter_mut().enumerate() {
            row[k] = k as f64 - 1.5;
        }
        let (vals, vecs) = jacobi_eigen(&d).unwrap();
        assert_eq!(vals, [-1.5, -0.5, 0.5, 1.5]);
        assert_eq!(vecs[2], [0.0, 0.0, 1.0, 0.0]);
        let (vals, _) = jacobi_eigen(&[[0.0; 9]; 9]).unwrap();
        assert_eq!(vals, [0.0; 9]);
    }

    #[test]
    fn non_finite_input_is_refused() {
        let mut a = [[1.0; 4]; 4];
        a[1][3] = f64::NAN;
        assert!(jacobi_eigen(&a).is_none());
        a[1][3] = f64::INFINITY;
        assert!(jacobi_eigen(&a).is_none());
    }

    #[test]
    fn extreme_scales_and_repeated_values() {
        // All-equal entries (eigenvalues R·x, 0 repeated R−1 times), huge and tiny.
        for x in [1e-300, 1.0, 1e150, 1e300] {
            let (rec, orth) = residuals(&[[x; 9]; 9]);
            assert!(
                rec <= 1e-14 * 9.0 * x && orth < 1e-14,
                "{x}: {rec:e} {orth:e}"
            );
        }
        // A 2×2 block with |ϑ| > 1e150 (a_pq tiny against the diagonal gap).
        let mut a = [[0.0; 4]; 4];
        a[0][0] = 1e200;
        a[0][1] = 1e30;
        a[1][0] = 1e30;
        a[2][2] = -1.0;
        let (rec, orth) = residuals(&a);
        assert!(rec <= 1e-15 * 1e200 && orth < 1e-15, "{rec:e} {orth:e}");
    }

    /// Random symmetric matrices Q Λ Qᵀ with prescribed spectrum: a chosen
    /// number of negative eigenvalues, magnitudes over 16 decades, repeated
    /// values and values ≈ 0 (to 1e-14 of the largest).
    mod prescribed_inertia {
        use super::super::jacobi_eigen;
        use nalgebra::{DMatrix, SymmetricEigen};
        use proptest::prelude::*;

        fn spectrum(r: usize) -> impl Strategy<Value = Vec<f64>> {
            let value = (0usize..4, -8i32..8, 0.5f64..2.0).prop_map(|(kind, e, m)| match kind {
                0 => 0.0,       // exactly zero
                1 => 1e-14 * m, // ≈ 0 against O(1)
                _ => m * 10f64.powi(e),
            });
            (
                prop::collection::vec(value, r),
                prop::collection::vec(any::<bool>(), r),
                0usize..3,
            )
                .prop_map(|(mut v, neg, repeat)| {
                    for (x, n) in v.iter_mut().zip(neg) {
                        if n {
                            *x = -*x;
                        }
                    }
                    for k in 1..=repeat.min(v.len() - 1) {
                        v[k] = v[0]; // a repeated eigenvalue
                    }
                    v
                })
        }

        /// Q Λ Qᵀ with Q orthogonal (QR of a random matrix).
        fn assemble<const R: usize>(lam: &[f64], g: &[f64]) -> [[f64; R]; R] {
            let q = DMatrix::from_column_slice(R, R, g).qr().q();
            let a = &q
                * DMatrix::from_fn(R, R, |i, j| if i == j { lam[i] } else { 0.0 })
                * q.transpose();
            std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (a[(i, j)] + a[(j, i)])))
        }

        /// Σ max(λ, 0) v vᵀ.
        fn clamp(r: usize, vals: &[f64], vec: impl Fn(usize, usize) -> f64) -> DMatrix<f64> {
            DMatrix::from_fn(r, r, |i, j| {
                (0..r)
                    .map(|k| vals[k].max(0.0) * vec(k, i) * vec(k, j))
                    .sum()
            })
        }

        fn check<const R: usize>(lam: &[f64], g: &[f64]) -> Result<(), TestCaseError> {
            let a = assemble::<R>(lam, g);
            let scale = lam
                .iter()
                .fold(0.0f64, |m, x| m.max(x.abs()))
                .max(f64::MIN_POSITIVE);
            let (vals, vecs) = jacobi_eigen(&a).expect("converges");
            // Backward error and orthogonality.
            for i in 0..R {
                for j in 0..R {
                    let rec: f64 = (0..R).map(|k| vals[k] * vecs[k][i] * vecs[k][j]).sum();
                    prop_assert!((rec - a[i][j]).abs() <= 1e-14 * R as f64 * scale);
                    let d: f64 = (0..R).map(|l| vecs[i][l] * vecs[j][l]).sum();
                    prop_assert!((d - f64::from(u8::from(i == j))).abs() <= 1e-14 * R as f64);
                }
            }
            // Eigenvalues (Weyl: |Δλ| ≤ ‖ΔA‖) and hence the inertia.
            let mut got = vals.to_vec();
            let mut want = lam.to_vec();
            got.sort_by(f64::total_cmp);
            want.sort_by(f64::total_cmp);
            for (x, y) in got.iter().zip(&want) {
                prop_assert!(
                    (x - y).abs() <= 1e-14 * R as f64 * scale,
                    "{got:?} vs {want:?}"
                );
            }
            let big = |l: &&f64| l.abs() > 1e-12 * scale;
            let neg = |v: &[f64]| v.iter().filter(big).filter(|l| **l < 0.0).count();
            prop_assert_eq!(neg(&got), neg(&want));
            // The clamp projection equals nalgebra's.
            let eig = SymmetricEigen::new(DMatrix::from_fn(R, R, |i, j| a[i][j]));
            let ours = clamp(R, &vals, |k, i| vecs[k][i]);
            let theirs = clamp(R, eig.eigenvalues.as_slice(), |k, i| {
                eig.eigenvectors[(i, k)]
            });
            prop_assert!((ours - theirs).amax() <= 1e-13 * R as f64 * scale);
            Ok(())
        }

        proptest! {
            #![proptest_config(ProptestConfig::with_cases(400))]
            #[test]
            fn four_by_four(lam in spectrum(4), g in prop::collection::vec(-1.0f64..1.0, 16)) {
                check::<4>(&lam, &g)?;
            }

            #[test]
            fn nine_by_nine(lam in spectrum(9), g in prop::collection::vec(-1.0f64..1.0, 81)) {
                check::<9>(&lam, &g)?;
            }
        }
    }
}
