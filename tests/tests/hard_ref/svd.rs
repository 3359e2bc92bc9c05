//! Signed singular values of a d×d matrix in double-double, by one-sided
//! (Hestenes) Jacobi: rotate column pairs of A until they are orthogonal;
//! the column norms are then |σ|. One-sided Jacobi gives small singular
//! values to high relative accuracy (Demmel & Veselić 1992), which the
//! σ = 1e-6 cases need.
//!
//! The signed convention of the runtime is reproduced from the values
//! alone: |σ0| ≥ |σ1| ≥ |σ2| and the last one carries the sign of det F
//! (computed in double-double from the entries). Nothing here shares code
//! with the runtime's SVD.

use super::dd::Dd;

/// det of a d×d matrix given column-major (d = 2 or 3), in double-double.
pub fn det(a: &[Dd], d: usize) -> Dd {
    let m = |r: usize, c: usize| a[c * d + r];
    if d == 2 {
        m(0, 0) * m(1, 1) - m(0, 1) * m(1, 0)
    } else {
        m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
            - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
            + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0))
    }
}

fn dot(x: &[Dd], y: &[Dd]) -> Dd {
    x.iter().zip(y).fold(Dd::ZERO, |s, (p, q)| s + *p * *q)
}

/// The signed singular values of A (column-major, d = 2 or 3).
#[allow(clippy::needless_range_loop)] // rows r of two columns at once
pub fn signed_sigma(a: &[Dd], d: usize) -> Vec<Dd> {
    let mut cols: Vec<Vec<Dd>> = (0..d).map(|c| a[c * d..(c + 1) * d].to_vec()).collect();
    for _sweep in 0..60 {
        let mut rotated = false;
        for p in 0..d {
            for q in p + 1..d {
                let alpha = dot(&cols[p], &cols[p]);
                let beta = dot(&cols[q], &cols[q]);
                let gamma = dot(&cols[p], &cols[q]);
                if gamma.hi == 0.0 || gamma.abs().hi <= 1e-33 * (alpha * beta).sqrt().hi {
                    continue;
                }
                rotated = true;
                // tan of the rotation angle: the smaller root of t² + 2ζt − 1 = 0.
                let zeta = (beta - alpha) / gamma.scale(2.0);
                let root = (Dd::ONE + zeta * zeta).sqrt();
                let t = if zeta.hi >= 0.0 {
                    Dd::ONE / (zeta + root)
                } else {
                    -(Dd::ONE / (root - zeta))
                };
                let c = Dd::ONE / (Dd::ONE + t * t).sqrt();
                let s = c * t;
                for r in 0..d {
                    let (x, y) = (cols[p][r], cols[q][r]);
                    cols[p][r] = c * x - s * y;
                    cols[q][r] = s * x + c * y;
                }
            }
        }
        if !rotated {
            break;
        }
    }
    let mut s: Vec<Dd> = cols.iter().map(|c| dot(c, c).sqrt()).collect();
    s.sort_by(|x, y| y.partial_cmp(x).unwrap_or(std::cmp::Ordering::Equal));
    if det(a, d).hi < 0.0 {
        s[d - 1] = -s[d - 1];
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_recovers_known_singular_values() {
        // F = R(θ) diag(3, 1e-6, −2) with a rotation in the 0-1 plane
        // (cos, sin = 0.6, 0.8): the values come back sorted by magnitude
        // with the sign of det F on the smallest.
        let (c, s) = (0.6, 0.8);
        let f = [
            Dd::from_f64(3.0 * c),
            Dd::from_f64(3.0 * s),
            Dd::ZERO,
            Dd::from_f64(-1e-6 * s),
            Dd::from_f64(1e-6 * c),
            Dd::ZERO,
            Dd::ZERO,
            Dd::ZERO,
            Dd::from_f64(-2.0),
        ];
        let sig = signed_sigma(&f, 3);
        // 1e-15: the f64 products 3·0.6 etc. are rounded, the values are not exact.
        for (g, w) in sig.iter().zip([3.0, 2.0, -1e-6]) {
            assert!(((g.to_f64() - w) / w).abs() < 1e-15, "{sig:?}");
        }
        // The columns are nearly orthogonal: |σ2| is the norm of column 1 to
        // double-double accuracy (1e-28 relative ≈ 2000 u).
        let n1 = (f[3] * f[3] + f[4] * f[4]).sqrt();
        let err = ((sig[2] + n1) / n1).to_f64();
        assert!(err.abs() < 1e-28, "{err:e}");
    }
}
