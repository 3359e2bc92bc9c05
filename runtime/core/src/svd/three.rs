//! Signed SVD of a 3×3 matrix: analytic V from FᵀF, then a Givens QR of F V.
//!
//! 1. F is scaled by a power of two so its largest entry lies in [1, 2)
//!    (exact; keeps FᵀF away from overflow/underflow).
//! 2. V = eigenvectors of FᵀF by [`crate::sym::sym3_eigen`] (descending
//!    eigenvalues, det V = +1). Only the *directions* are used; the eigenvalues
//!    σ² would lose the small σ to rounding.
//! 3. B = F V is reduced to upper-triangular R by three Givens rotations
//!    (zeroing B₁₀, B₂₀, B₂₁) whose angles make R₀₀, R₁₁ ≥ 0; U is their
//!    product, so U ∈ SO(3) to rounding and det R = det F. With V exact, R is
//!    diagonal; the off-diagonal residue (≈ ε‖F‖) is dropped, so
//!    ‖F − U diag(σ) Vᵀ‖ ≈ ε‖F‖ and σ_i = R_ii carries det F's sign in R₂₂.
//!    If σ_1 ≪ σ_0 the trailing eigenvectors of FᵀF are unresolvable (their
//!    eigenvalues sit below ε σ_0²) and R₁₂ is not negligible; the trailing
//!    2×2 block of R then gets its own closed-form signed SVD.
//! 4. A final fix-up restores |σ_0| ≥ |σ_1| ≥ |σ_2| (rounding can swap nearly
//!    equal magnitudes) and moves any negative sign into σ_2, flipping pairs of
//!    columns so U, V stay in SO(3).

use super::{Svd, non_finite, signed_svd2};
use crate::sym::sym3_eigen;
use nalgebra::{Matrix2, Matrix3};

/// Signed SVD of a 3×3 matrix (see the module docs for the algorithm).
pub fn signed_svd3(f: &Matrix3<f64>) -> Svd<3> {
    let mut fm = [[0.0; 3]; 3];
    let mut big = 0.0f64;
    for (i, row) in fm.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = f[(i, j)];
            big = big.max(x.abs());
        }
    }
    if !big.is_finite() || f.iter().any(|x| x.is_nan()) {
        return non_finite();
    }
    if big == 0.0 {
        return Svd {
            u: Matrix3::identity(),
            sigma: [0.0; 3],
            v: Matrix3::identity(),
        };
    }
    let (s1, s2) = pow2_scale(big);
    for row in fm.iter_mut() {
        for x in row.iter_mut() {
            *x = *x * s1 * s2;
        }
    }
    // FᵀF (symmetric, upper triangle suffices).
    let col = |j: usize| [fm[0][j], fm[1][j], fm[2][j]];
    let (c0, c1, c2) = (col(0), col(1), col(2));
    let d = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let ftf = [
        [d(&c0, &c0), d(&c0, &c1), d(&c0, &c2)],
        [0.0, d(&c1, &c1), d(&c1, &c2)],
        [0.0, 0.0, d(&c2, &c2)],
    ];
    let (_, vcols) = sym3_eigen(&ftf);

    // B = F V, row-major.
    let mut b = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            b[i][j] = d(&fm[i], &vcols[j]);
        }
    }
    // Qᵀ accumulated as rows: start from I, apply the same row rotations as to B.
    let mut qt = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    givens_rows(&mut b, &mut qt, 0, 1, 0);
    givens_rows(&mut b, &mut qt, 0, 2, 0);
    givens_rows(&mut b, &mut qt, 1, 2, 1);

    let mut sigma = [b[0][0], b[1][1], b[2][2]];
    // U = Q: column j of U is row j of Qᵀ.
    let mut ucols = qt;
    let mut vcols = vcols;
    // When σ_1 ≪ σ_0, FᵀF cannot resolve the trailing eigenvectors (their
    // eigenvalues are below ε σ_0²) and R keeps a significant R₁₂: finish with
    // the closed-form SVD of the trailing 2×2 block.
    if b[1][2].abs() > TRAILING_TOL * b[0][0] {
        trailing_2x2(&b, &mut sigma, &mut ucols, &mut vcols);
    }
    fix_order(&mut sigma, &mut ucols, &mut vcols);
    for s in sigma.iter_mut() {
        *s = *s / s1 / s2;
    }
    Svd {
        u: Matrix3::from_fn(|i, j| ucols[j][i]),
        sigma,
        v: Matrix3::from_fn(|i, j| vcols[j][i]),
    }
}

/// |R₁₂| / R₀₀ above which the trailing 2×2 block is diagonalised explicitly
/// (below it, dropping R₁₂ perturbs F by less than a few ulps of ‖F‖).
const TRAILING_TOL: f64 = 4.0 * f64::EPSILON;

/// Replace the trailing block [[R₁₁, R₁₂], [0, R₂₂]] by its signed SVD
/// U₂ diag(s) V₂ᵀ and fold U₂, V₂ into columns 1, 2 of U and V.
fn trailing_2x2(
    b: &[[f64; 3]; 3],
    sigma: &mut [f64; 3],
    u: &mut [[f64; 3]; 3],
    v: &mut [[f64; 3]; 3],
) {
    let blk = Matrix2::new(b[1][1], b[1][2], 0.0, b[2][2]);
    let s2 = signed_svd2(&blk);
    let mix = |cols: &mut [[f64; 3]; 3], r: &Matrix2<f64>| {
        let (c1, c2) = (cols[1], cols[2]);
        for k in 0..3 {
            cols[1][k] = c1[k] * r[(0, 0)] + c2[k] * r[(1, 0)];
            cols[2][k] = c1[k] * r[(0, 1)] + c2[k] * r[(1, 1)];
        }
    };
    mix(u, &s2.u);
    mix(v, &s2.v);
    sigma[1] = s2.sigma[0];
    sigma[2] = s2.sigma[1];
}

/// Two power-of-two factors whose product 2^-e brings `big` into [1, 2)
/// (split so each stays a normal number even for subnormal or huge `big`;
/// multiplying and dividing by them is exact).
fn pow2_scale(big: f64) -> (f64, f64) {
    let e = big.log2().floor() as i32;
    let half = e / 2;
    (exp2i(-half), exp2i(half - e))
}

/// 2^k exactly, for |k| ≤ 1022.
fn exp2i(k: i32) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// Apply the Givens rotation that zeroes `b[r1][c]` against `b[r0][c]` (making
/// `b[r0][c]` = hypot ≥ 0) to rows r0, r1 of `b` and of `qt`.
#[inline]
fn givens_rows(b: &mut [[f64; 3]; 3], qt: &mut [[f64; 3]; 3], r0: usize, r1: usize, c: usize) {
    let x = b[r0][c];
    let y = b[r1][c];
    let n2 = x * x + y * y;
    if n2 == 0.0 {
        return;
    }
    let inv = 1.0 / n2.sqrt();
    let (cs, sn) = (x * inv, y * inv);
    for m in [&mut *b, &mut *qt] {
        for k in 0..3 {
            let p = m[r0][k];
            let q = m[r1][k];
            m[r0][k] = cs * p + sn * q;
            m[r1][k] = -sn * p + cs * q;
        }
    }
    b[r1][c] = 0.0;
}

/// Enforce |σ_0| ≥ |σ_1| ≥ |σ_2| with only σ_2 possibly negative, keeping
/// U diag(σ) Vᵀ and det U = det V = +1.
fn fix_order(sigma: &mut [f64; 3], u: &mut [[f64; 3]; 3], v: &mut [[f64; 3]; 3]) {
    let neg = |x: &mut [f64; 3]| *x = [-x[0], -x[1], -x[2]];
    // Swapping columns i, j of both U and V flips both determinants; negating
    // column i of both restores them (σ_i's sign is unchanged by the pair).
    let mut swap = |sigma: &mut [f64; 3], i: usize, j: usize| {
        sigma.swap(i, j);
        u.swap(i, j);
        v.swap(i, j);
        neg(&mut u[i]);
        neg(&mut v[i]);
    };
    if sigma[0].abs() < sigma[1].abs() {
        swap(sigma, 0, 1);
    }
    if sigma[1].abs() < sigma[2].abs() {
        swap(sigma, 1, 2);
    }
    if sigma[0].abs() < sigma[1].abs() {
        swap(sigma, 0, 1);
    }
    // Move negative signs into the last slot in pairs (negate u_i, u_2 together).
    for i in 0..2 {
        if sigma[i] < 0.0 {
            sigma[i] = -sigma[i];
            sigma[2] = -sigma[2];
            neg(&mut u[i]);
            neg(&mut u[2]);
        }
    }
}
