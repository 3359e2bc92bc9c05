//! Small dense linear algebra in any [`Real`] type: the cyclic Jacobi
//! eigensolver for symmetric matrices and a signed SVD built on it.
//!
//! * [`sym_eigen`]: cyclic Jacobi (Golub & Van Loan §8.5) with the stable
//!   rotation formulas; backward stable, converges quadratically; stops when
//!   every off-diagonal is below u·‖A‖_F (u the type's roundoff) or after 60
//!   sweeps.
//! * [`signed_svd`]: V from the eigenvectors of FᵀF (rotated into SO(d)),
//!   u₀ = F v₀/‖F v₀‖, in 3D u₁ = Gram–Schmidt of F v₁ and u₂ = u₀ × u₁, in
//!   2D u₁ = u₀ rotated by 90°; σ_k = u_kᵀ F v_k, so the last one carries the
//!   sign of det F. Because σ_k is a Rayleigh-type quotient of F itself (not a
//!   square root of an eigenvalue of FᵀF) the small singular values keep full
//!   relative accuracy: σ = 10⁻⁶ next to σ = 1 is accurate to ≈ u/10⁻⁶·…
//!   rather than u/10⁻¹². The last one is then replaced by det F/(σ₀σ₁) (3D)
//!   or det F/σ₀ (2D), which is accurate to ≈ u relative whatever its size.

use ecc_tests::real::Real;

/// A dense symmetric matrix in row-major order, n×n.
pub type Dense<R> = Vec<R>;

/// Eigenvalues (ascending) and eigenvectors (columns of a row-major n×n
/// matrix: `vecs[i*n + k]` is component i of eigenvector k) of the
/// symmetric n×n matrix `a` (only its upper triangle is read).
pub fn sym_eigen<R: Real>(a: &[R], n: usize) -> (Vec<R>, Dense<R>) {
    let mut m: Vec<R> = (0..n * n)
        .map(|k| {
            let (i, j) = (k / n, k % n);
            if i <= j { a[i * n + j] } else { a[j * n + i] }
        })
        .collect();
    let mut v: Vec<R> = (0..n * n)
        .map(|k| if k / n == k % n { R::one() } else { R::zero() })
        .collect();
    let fro = m.iter().fold(R::zero(), |s, &x| s + x * x).sqrt();
    let tol = R::from_f64(R::EPS) * fro;
    for _sweep in 0..60 {
        let mut off = R::zero();
        for p in 0..n {
            for q in (p + 1)..n {
                off = off + m[p * n + q].abs();
            }
        }
        if off.partial_cmp(&tol) != Some(std::cmp::Ordering::Greater) {
            break;
        }
        for p in 0..n {
            for q in (p + 1)..n {
                let apq = m[p * n + q];
                if apq == R::zero() {
                    continue;
                }
                let (app, aqq) = (m[p * n + p], m[q * n + q]);
                let theta = (aqq - app) / (R::from_f64(2.0) * apq);
                let t = {
                    let r = (theta * theta + R::one()).sqrt();
                    let t = R::one() / (theta.abs() + r);
                    if theta < R::zero() { -t } else { t }
                };
                let c = R::one() / (t * t + R::one()).sqrt();
                let s = t * c;
                for k in 0..n {
                    let (mkp, mkq) = (m[k * n + p], m[k * n + q]);
                    m[k * n + p] = c * mkp - s * mkq;
                    m[k * n + q] = s * mkp + c * mkq;
                }
                for k in 0..n {
                    let (mpk, mqk) = (m[p * n + k], m[q * n + k]);
                    m[p * n + k] = c * mpk - s * mqk;
                    m[q * n + k] = s * mpk + c * mqk;
                }
                for k in 0..n {
                    let (vkp, vkq) = (v[k * n + p], v[k * n + q]);
                    v[k * n + p] = c * vkp - s * vkq;
                    v[k * n + q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        m[a * n + a]
            .partial_cmp(&m[b * n + b])
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let vals = order.iter().map(|&k| m[k * n + k]).collect();
    let mut vecs = vec![R::zero(); n * n];
    for (newk, &k) in order.iter().enumerate() {
        for i in 0..n {
            vecs[i * n + newk] = v[i * n + k];
        }
    }
    (vals, vecs)
}

/// det of a d×d row-major matrix (d = 2 or 3), by cofactors.
pub fn det<R: Real>(f: &[R], d: usize) -> R {
    if d == 2 {
        f[0] * f[3] - f[1] * f[2]
    } else {
        f[0] * (f[4] * f[8] - f[5] * f[7]) - f[1] * (f[3] * f[8] - f[5] * f[6])
            + f[2] * (f[3] * f[7] - f[4] * f[6])
    }
}

/// Signed SVD of a d×d row-major F: (σ, U, V), U and V row-major in SO(d),
/// |σ₀| ≥ |σ₁| (≥ |σ₂|), only the last σ negative when det F < 0.
pub fn signed_svd<R: Real>(f: &[R], d: usize) -> (Vec<R>, Dense<R>, Dense<R>) {
    // C = FᵀF
    let mut c = vec![R::zero(); d * d];
    for i in 0..d {
        for j in 0..d {
            let mut acc = R::zero();
            for k in 0..d {
                acc = acc + f[k * d + i] * f[k * d + j];
            }
            c[i * d + j] = acc;
        }
    }
    let (_, vecs) = sym_eigen(&c, d);
    // descending order: eigenvector columns reversed
    let mut v = vec![R::zero(); d * d];
    for i in 0..d {
        for k in 0..d {
            v[i * d + k] = vecs[i * d + (d - 1 - k)];
        }
    }
    if det(&v, d) < R::zero() {
        for i in 0..d {
            v[i * d + d - 1] = -v[i * d + d - 1];
        }
    }
    let fv = |k: usize| -> Vec<R> {
        (0..d)
            .map(|i| (0..d).fold(R::zero(), |a, j| a + f[i * d + j] * v[j * d + k]))
            .collect()
    };
    let norm = |x: &[R]| x.iter().fold(R::zero(), |a, &y| a + y * y).sqrt();
    let mut u = vec![R::zero(); d * d];
    let f0 = fv(0);
    let n0 = norm(&f0);
    let u0: Vec<R> = if n0 > R::zero() {
        f0.iter().map(|&x| x / n0).collect()
    } else {
        (0..d)
            .map(|i| if i == 0 { R::one() } else { R::zero() })
            .collect()
    };
    let mut cols = vec![u0.clone()];
    if d == 2 {
        cols.push(vec![-u0[1], u0[0]]);
    } else {
        let f1 = fv(1);
        let dot = (0..3).fold(R::zero(), |a, i| a + u0[i] * f1[i]);
        let mut w: Vec<R> = (0..3).map(|i| f1[i] - dot * u0[i]).collect();
        let nw = norm(&w);
        if nw > R::zero() {
            w.iter_mut().for_each(|x| *x = *x / nw);
        } else {
            // any unit vector orthogonal to u0
            let k = if u0[0].abs() < R::from_f64(0.5) { 0 } else { 1 };
            let mut e = [R::zero(); 3];
            e[k] = R::one();
            let dot = u0[k];
            w = (0..3).map(|i| e[i] - dot * u0[i]).collect();
            let nw = norm(&w);
            w.iter_mut().for_each(|x| *x = *x / nw);
        }
        let u2 = vec![
            u0[1] * w[2] - u0[2] * w[1],
            u0[2] * w[0] - u0[0] * w[2],
            u0[0] * w[1] - u0[1] * w[0],
        ];
        cols.push(w);
        cols.push(u2);
    }
    for k in 0..d {
        for i in 0..d {
            u[i * d + k] = cols[k][i];
        }
    }
    let mut sigma: Vec<R> = (0..d)
        .map(|k| {
            let fk = fv(k);
            (0..d).fold(R::zero(), |a, i| a + cols[k][i] * fk[i])
        })
        .collect();
    let others = sigma[..d - 1].iter().fold(R::one(), |a, &s| a * s);
    if others != R::zero() {
        sigma[d - 1] = det(f, d) / others;
    }
    (sigma, u, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ecc_tests::dd::Dd;

    #[test]
    fn svd_reconstructs_and_keeps_small_sigma_accurate() {
        // F = R1 diag(1.5, 1e-6 ... ) R2 with simple rotations, in double-double
        // Pythagorean rotations (3/5, 4/5), built in double-double so they are orthogonal to ≈1e-32
        let (c, s, o, z) = (
            Dd::from_ratio(3, 5),
            Dd::from_ratio(4, 5),
            Dd::one(),
            Dd::zero(),
        );
        let r1 = [c, -s, z, s, c, z, z, z, o];
        let r2 = [o, z, z, z, c, -s, z, s, c];
        let sig = [1.5, 0.7, -1e-6];
        let mut f = [Dd::zero(); 9];
        for i in 0..3 {
            for j in 0..3 {
                let mut acc = Dd::zero();
                for k in 0..3 {
                    acc = acc + r1[i * 3 + k] * Dd::from_f64(sig[k]) * r2[j * 3 + k];
                }
                f[i * 3 + j] = acc;
            }
        }
        let (sv, _, _) = signed_svd(&f, 3);
        for k in 0..3 {
            let rel = ((sv[k] - Dd::from_f64(sig[k])).to_f64() / sig[k]).abs();
            assert!(rel < 1e-24, "sigma {k}: {:?} rel {rel:e}", sv[k]);
        }
        let (s64, u, v) = signed_svd(&f.map(|x| x.to_f64()), 3);
        for i in 0..3 {
            for j in 0..3 {
                let rec: f64 = (0..3).map(|k| u[i * 3 + k] * s64[k] * v[j * 3 + k]).sum();
                assert!((rec - f[i * 3 + j].to_f64()).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn jacobi_eigen_of_a_known_matrix() {
        let a = [2.0, 1.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 5.0];
        let (vals, _) = sym_eigen(&a, 3);
        for (got, want) in vals.iter().zip([1.0, 3.0, 5.0]) {
            assert!((got - want).abs() < 1e-14);
        }
    }
}
