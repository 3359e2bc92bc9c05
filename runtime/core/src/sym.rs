//! Closed-form eigen-decompositions of small symmetric matrices (2×2, 3×3).
//!
//! Used for the scaling block A = ∂²Ψ/∂σ² when it does not decouple, and by
//! the 3×3 signed SVD (eigenvectors of FᵀF).
//!
//! **2×2** [[a, b], [b, c]]: λ = m ± r with m = (a+c)/2, r = |((a−c)/2, b)|;
//! the eigenvector of m + r is the normalised half-angle vector of
//! ((a−c)/2, b), formed without cancellation.
//!
//! **3×3** (robust analytic method): the input is scaled by its largest entry,
//! the eigenvalues come from the trigonometric solution of the characteristic
//! cubic (q = tr/3, p = ‖A − qI‖_F/√6, λ = q + 2p·cos(φ + 2πk/3)), the
//! eigenvector of the eigenvalue with the *largest gap* (gap ≥ 1.5p) is the
//! largest cross product of two rows of A − λI, and the remaining 2×2 block in
//! its orthogonal complement is diagonalised by one exact Jacobi rotation, so
//! repeated or nearly repeated eigenvalues never divide by a small gap.
//! Eigenvalues are the Rayleigh quotients of the returned orthonormal vectors.
//! Accuracy: residual ‖A v − λ v‖ ≲ 10 ε ‖A‖ (backward stable); eigenvalues
//! have absolute error ≈ ε ‖A‖ like any backward-stable symmetric solver.

/// Eigen-decomposition of a symmetric 2×2 matrix `[[a, b], [b, c]]`.
///
/// Returns `(values, vectors)` with values descending and `vectors[k]` the unit
/// eigenvector of `values[k]`; the vectors form a rotation (det = +1).
/// Non-finite input gives NaN values and the identity basis.
pub fn sym2_eigen(a: f64, b: f64, c: f64) -> ([f64; 2], [[f64; 2]; 2]) {
    if !(a.is_finite() && b.is_finite() && c.is_finite()) {
        return ([f64::NAN; 2], [[1.0, 0.0], [0.0, 1.0]]);
    }
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 {
        return ([0.0; 2], [[1.0, 0.0], [0.0, 1.0]]);
    }
    let inv = 1.0 / scale;
    let (v, z) = sym2_eigen_scaled(a * inv, b * inv, c * inv);
    ([v[0] * scale, v[1] * scale], z)
}

/// [`sym2_eigen`] for finite entries of magnitude ≤ O(1) (no overflow guard).
#[inline]
fn sym2_eigen_scaled(a: f64, b: f64, c: f64) -> ([f64; 2], [[f64; 2]; 2]) {
    let m = 0.5 * (a + c);
    let h = 0.5 * (a - c);
    let r = (h * h + b * b).sqrt();
    if r == 0.0 {
        return ([a, c], [[1.0, 0.0], [0.0, 1.0]]);
    }
    // Half-angle vector of (h, b)/r = (cos 2θ, sin 2θ): (cos θ, sin θ).
    let (x, y) = if h >= 0.0 { (h + r, b) } else { (b, r - h) };
    let n = 1.0 / (x * x + y * y).sqrt();
    let (cs, sn) = (x * n, y * n);
    ([m + r, m - r], [[cs, sn], [-sn, cs]])
}

/// Eigen-decomposition of a symmetric 3×3 matrix (row-major, only the upper
/// triangle is read).
///
/// Returns `(values, vectors)` with values descending and `vectors[k]` the unit
/// eigenvector of `values[k]`; the vectors form a rotation (det = +1).
/// Non-finite input gives NaN values and the identity basis.
pub fn sym3_eigen(m: &[[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let s = [m[0][0], m[1][1], m[2][2], m[0][1], m[0][2], m[1][2]];
    let scale = s.iter().fold(0.0f64, |acc, x| acc.max(x.abs()));
    if !scale.is_finite() || s.iter().any(|x| x.is_nan()) {
        return ([f64::NAN; 3], IDENTITY);
    }
    if scale == 0.0 {
        return ([0.0; 3], IDENTITY);
    }
    let inv = 1.0 / scale;
    let a = [
        [s[0] * inv, s[3] * inv, s[4] * inv],
        [s[3] * inv, s[1] * inv, s[5] * inv],
        [s[4] * inv, s[5] * inv, s[2] * inv],
    ];
    let (vals, vecs) = sym3_eigen_scaled(&a);
    sorted([vals[0] * scale, vals[1] * scale, vals[2] * scale], vecs)
}

const IDENTITY: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// a · b (also the 3×3 SVD's).
#[inline]
pub(crate) fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a × b (also the 3×3 SVD's).
#[inline]
pub(crate) fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
fn mat_vec(a: &[[f64; 3]; 3], v: &[f64; 3]) -> [f64; 3] {
    [dot(&a[0], v), dot(&a[1], v), dot(&a[2], v)]
}

/// The largest root c ∈ [√3/2, 1] of g(c) = 4c³ − 3c − t for t ∈ [0, 1], i.e.
/// cos(acos(t)/3): a degree-5 fit (interpolation at Chebyshev nodes, error
/// < 7·10⁻⁷; the root is analytic on [0, 1]) refined by one Halley step
/// c ← c − 2gg′/(2g′² − gg″). The root is simple (g′ = 12c² − 3 ∈ [6, 9]) and
/// Halley converges cubically, so one step reaches ≈ ε; one division instead
/// of acos + cos (checked against them in the unit test).
#[inline]
fn trisect(t: f64) -> f64 {
    let c = 0.866_026_061_058_833_1
        + t * (0.166_618_856_515_035_4
            + t * (-0.047_525_013_932_435_26
                + t * (0.021_899_627_345_145_625
                    + t * (-0.008_966_451_200_158_584 + t * 0.001_947_301_610_416_935_6))));
    let g = c * (4.0 * c * c - 3.0) - t;
    let g1 = 12.0 * c * c - 3.0;
    c - 2.0 * g * g1 / (2.0 * g1 * g1 - g * 24.0 * c)
}

/// The best-separated eigenpair of a symmetric 3×3 matrix: the eigenvalue
/// with the largest gap to the other two (λ_max when `is_max`, else λ_min)
/// and its unit eigenvector, accurate to ≈ ε‖A‖/gap with gap ≥ 1.5p.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Isolated {
    pub value: f64,
    pub vector: [f64; 3],
    pub is_max: bool,
}

/// [`Isolated`] for a matrix with entries of order 1 (see
/// [`sym3_eigen_scaled`]); `None` when all eigenvalues are equal to rounding.
pub(crate) fn isolated_scaled(a: &[[f64; 3]; 3]) -> Option<Isolated> {
    let q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    let p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    let d = [a[0][0] - q, a[1][1] - q, a[2][2] - q];
    let p2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    if p <= 4.0 * f64::EPSILON {
        return None;
    }
    // B = (A − qI)/p has eigenvalues 2cos(φ + 2πk/3) with cos 3φ = det(B)/2 = r.
    let ip = 1.0 / p;
    let b00 = d[0] * ip;
    let b11 = d[1] * ip;
    let b22 = d[2] * ip;
    let b01 = a[0][1] * ip;
    let b02 = a[0][2] * ip;
    let b12 = a[1][2] * ip;
    let det_b = b00 * (b11 * b22 - b12 * b12) - b01 * (b01 * b22 - b12 * b02)
        + b02 * (b01 * b12 - b11 * b02);
    let r = (0.5 * det_b).clamp(-1.0, 1.0);
    // With φ = acos(r)/3 ∈ [0, π/3], λ_max = q + 2p cos φ, λ_min = q + 2p cos(φ + 2π/3)
    // and λ_mid = q + 2p cos(φ + 4π/3). The largest gap is above λ_mid exactly when
    // cos(φ + 4π/3) ≤ 0, i.e. φ ≤ π/6, i.e. r ≥ 0. The cosines are the roots of
    // 4c³ − 3c = r; the one needed is the largest root for r ≥ 0 and the smallest
    // for r < 0, i.e. ±(largest root of 4c³ − 3c = |r|) (see `trisect`).
    let c = trisect(r.abs());
    let is_max = r >= 0.0;
    let iso = if is_max {
        q + 2.0 * p * c
    } else {
        q - 2.0 * p * c
    };

    // Eigenvector: the largest cross product of two rows of A − λI.
    let r0 = [a[0][0] - iso, a[0][1], a[0][2]];
    let r1 = [a[0][1], a[1][1] - iso, a[1][2]];
    let r2 = [a[0][2], a[1][2], a[2][2] - iso];
    let cr = [cross(&r0, &r1), cross(&r0, &r2), cross(&r1, &r2)];
    let n = [
        dot(&cr[0], &cr[0]),
        dot(&cr[1], &cr[1]),
        dot(&cr[2], &cr[2]),
    ];
    let k = if n[0] >= n[1] && n[0] >= n[2] {
        0
    } else if n[1] >= n[2] {
        1
    } else {
        2
    };
    if n[k].is_nan() || n[k] <= 0.0 {
        // Unreachable for p > 4ε (A − λI has rank 2); report "no answer".
        return None;
    }
    let inv_n = 1.0 / n[k].sqrt();
    let v0 = [cr[k][0] * inv_n, cr[k][1] * inv_n, cr[k][2] * inv_n];
    Some(Isolated {
        value: dot(&v0, &mat_vec(a, &v0)),
        vector: v0,
        is_max,
    })
}

/// A finite symmetric matrix divided by its largest |entry| (returned as the
/// second value, > 0); `None` for a zero or non-finite matrix.
pub(crate) fn normalised(m: &[[f64; 3]; 3]) -> Option<([[f64; 3]; 3], f64)> {
    let scale = m.iter().flatten().fold(0.0f64, |acc, x| acc.max(x.abs()));
    if !scale.is_finite() || scale == 0.0 {
        return None;
    }
    let inv = 1.0 / scale;
    Some((
        std::array::from_fn(|i| std::array::from_fn(|j| m[i][j] * inv)),
        scale,
    ))
}

/// The core on a matrix whose largest entry has magnitude of order 1 (the
/// thresholds assume it; used directly by the SVD, whose FᵀF is pre-scaled).
pub(crate) fn sym3_eigen_scaled(a: &[[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    complete_scaled(a, isolated_scaled(a).as_ref())
}

/// The full decomposition of an order-1 matrix from its isolated eigenpair
/// (`None`: all eigenvalues equal to rounding, any orthonormal basis works).
/// The vectors form a rotation and the values are descending up to rounding
/// (ties may come out in either order; [`sym3_eigen`] sorts strictly).
pub(crate) fn complete_scaled(
    a: &[[f64; 3]; 3],
    iso: Option<&Isolated>,
) -> ([f64; 3], [[f64; 3]; 3]) {
    let Some(&Isolated {
        vector: v0,
        value: l0,
        ..
    }) = iso
    else {
        return sorted([a[0][0], a[1][1], a[2][2]], IDENTITY);
    };

    // Orthonormal complement {w1, w2} of v0 with w1 × w2 = v0, without a square
    // root (Duff et al. 2017, "Building an orthonormal basis, revisited").
    let sign = 1f64.copysign(v0[2]);
    let ia = -1.0 / (sign + v0[2]);
    let bb = v0[0] * v0[1] * ia;
    let w1 = [1.0 + sign * v0[0] * v0[0] * ia, sign * bb, -sign * v0[0]];
    let w2 = [bb, sign + v0[1] * v0[1] * ia, -v0[1]];
    // The 2×2 block of A in that complement, diagonalised by one Jacobi rotation.
    let aw1 = mat_vec(a, &w1);
    let aw2 = mat_vec(a, &w2);
    let (ev, evec) = sym2_eigen_scaled(dot(&w1, &aw1), dot(&w1, &aw2), dot(&w2, &aw2));
    let y1 = [
        evec[0][0] * w1[0] + evec[0][1] * w2[0],
        evec[0][0] * w1[1] + evec[0][1] * w2[1],
        evec[0][0] * w1[2] + evec[0][1] * w2[2],
    ];
    let y2 = [
        evec[1][0] * w1[0] + evec[1][1] * w2[0],
        evec[1][0] * w1[1] + evec[1][1] * w2[1],
        evec[1][0] * w1[2] + evec[1][1] * w2[2],
    ];
    // (v0, y1, y2) is right-handed and ev is descending, so both orders below
    // are descending (to rounding) rotations: no comparisons needed.
    match iso {
        Some(i) if !i.is_max => ([ev[0], ev[1], l0], [y1, y2, v0]),
        _ => ([l0, ev[0], ev[1]], [v0, y1, y2]),
    }
}

/// Sort eigenpairs by descending value and make the basis a rotation.
fn sorted(mut vals: [f64; 3], mut vecs: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    if vals[0] < vals[1] {
        vals.swap(0, 1);
        vecs.swap(0, 1);
    }
    if vals[1] < vals[2] {
        vals.swap(1, 2);
        vecs.swap(1, 2);
    }
    if vals[0] < vals[1] {
        vals.swap(0, 1);
        vecs.swap(0, 1);
    }
    if dot(&cross(&vecs[0], &vecs[1]), &vecs[2]) < 0.0 {
        vecs[2] = [-vecs[2][0], -vecs[2][1], -vecs[2][2]];
    }
    (vals, vecs)
}

#[cfg(test)]
mod tests {
    use super::trisect;

    #[test]
    fn trisect_matches_acos_cos() {
        let mut worst: f64 = 0.0;
        for k in 0..=100_000 {
            let t = k as f64 / 100_000.0;
            let want = (t.acos() / 3.0).cos();
            worst = worst.max((trisect(t) - want).abs());
        }
        assert!(worst < 4.0 * f64::EPSILON, "worst error {worst:e}");
    }
}
