//! Signed SVD of a 3×3 matrix: analytic V from FᵀF, then a Gram–Schmidt QR of F V.
//!
//! 1. F is scaled by a power of two so its largest entry lies in [1, 2)
//!    (exact; keeps FᵀF away from overflow/underflow).
//! 2. V = eigenvectors of FᵀF by [`crate::sym::sym3_eigen`] (descending
//!    eigenvalues, det V = +1). Only the *directions* are used; the eigenvalues
//!    σ² would lose the small σ to rounding.
//! 3. B = F V is factored B = U R by Gram–Schmidt on its first two columns
//!    (re-orthogonalised when cancellation is severe) and u_2 = u_0 × u_1, so
//!    U ∈ SO(3) to rounding, R₀₀, R₁₁ ≥ 0 and R₂₂ = u_2·b_2 has the sign of
//!    det F. With V exact, R is diagonal; the off-diagonal residue (≈ ε‖F‖) is
//!    dropped, so ‖F − U diag(σ) Vᵀ‖ ≈ ε‖F‖ with σ_i = R_ii.
//!    If σ_1 ≪ σ_0 the trailing eigenvectors of FᵀF are unresolvable (their
//!    eigenvalues sit below ε σ_0²) and R₁₂ is not negligible; the trailing
//!    2×2 block of R then gets its own closed-form signed SVD.
//! 4. A final fix-up restores |σ_0| ≥ |σ_1| ≥ |σ_2| (rounding can swap nearly
//!    equal magnitudes) and moves any negative sign into σ_2, flipping pairs of
//!    columns so U, V stay in SO(3).

use super::{Svd, non_finite, signed_svd2};
use crate::sym::{cross, dot, sym3_eigen_scaled};
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
    // FᵀF (symmetric; entries ≤ 12 after scaling, so no further scaling).
    let col = |j: usize| [fm[0][j], fm[1][j], fm[2][j]];
    let (c0, c1, c2) = (col(0), col(1), col(2));
    let ftf = [
        [dot(&c0, &c0), dot(&c0, &c1), dot(&c0, &c2)],
        [dot(&c0, &c1), dot(&c1, &c1), dot(&c1, &c2)],
        [dot(&c0, &c2), dot(&c1, &c2), dot(&c2, &c2)],
    ];
    let (_, mut vcols) = sym3_eigen_scaled(&ftf);

    // Columns b_j = F v_j, then Gram–Schmidt: R is upper triangular with
    // R₀₀ = ‖b_0‖ > 0, R₁₁ ≥ 0, and u_2 = u_0 × u_1 makes det U = +1, so
    // R₂₂ = u_2·b_2 carries the sign of det F.
    let fv = |v: &[f64; 3]| [dot(&fm[0], v), dot(&fm[1], v), dot(&fm[2], v)];
    let (b0, b1, b2) = (fv(&vcols[0]), fv(&vcols[1]), fv(&vcols[2]));
    let r00 = dot(&b0, &b0).sqrt();
    let u0 = scale3(&b0, 1.0 / r00);
    let u1 = orthonormal_against(&u0, &b1, r00);
    let u2 = cross(&u0, &u1);
    let r12 = dot(&u1, &b2);
    let mut sigma = [r00, dot(&u1, &b1), dot(&u2, &b2)];
    let mut ucols = [u0, u1, u2];
    // When σ_1 ≪ σ_0, FᵀF cannot resolve the trailing eigenvectors (their
    // eigenvalues are below ε σ_0²) and R keeps a significant R₁₂: finish with
    // the closed-form SVD of the trailing 2×2 block.
    if r12.abs() > TRAILING_TOL * r00 {
        trailing_2x2(sigma[1], r12, sigma[2], &mut sigma, &mut ucols, &mut vcols);
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
    r11: f64,
    r12: f64,
    r22: f64,
    sigma: &mut [f64; 3],
    u: &mut [[f64; 3]; 3],
    v: &mut [[f64; 3]; 3],
) {
    let blk = Matrix2::new(r11, r12, 0.0, r22);
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
    let bits = (big.to_bits() >> 52) & 0x7ff;
    let e = if bits == 0 {
        big.log2().floor() as i32 // subnormal: rare, take the slow path
    } else {
        bits as i32 - 1023
    };
    let half = e / 2;
    (exp2i(-half), exp2i(half - e))
}

/// 2^k exactly, for |k| ≤ 1022.
fn exp2i(k: i32) -> f64 {
    f64::from_bits(((k + 1023) as u64) << 52)
}

#[inline]
fn scale3(a: &[f64; 3], s: f64) -> [f64; 3] {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Unit vector along b − (u·b)u (u a unit vector, `r00` the scale of the
/// problem). A second Gram–Schmidt pass runs when the first one cancelled more
/// than 10⁻⁴ of b ("twice is enough"); if nothing is left (b ∥ u, rank ≤ 1),
/// any unit vector orthogonal to u is returned.
#[inline]
fn orthonormal_against(u: &[f64; 3], b: &[f64; 3], r00: f64) -> [f64; 3] {
    let c = dot(u, b);
    let mut r = [b[0] - c * u[0], b[1] - c * u[1], b[2] - c * u[2]];
    let mut n2 = dot(&r, &r);
    if n2 <= 1e-8 * dot(b, b) {
        let c2 = dot(u, &r);
        r = [r[0] - c2 * u[0], r[1] - c2 * u[1], r[2] - c2 * u[2]];
        n2 = dot(&r, &r);
        if n2.is_nan() || n2 <= (f64::EPSILON * f64::EPSILON) * r00 * r00 {
            // Rank ≤ 1: complete u to an orthonormal pair.
            let w = if u[0].abs() > u[1].abs() {
                [-u[2], 0.0, u[0]]
            } else {
                [0.0, u[2], -u[1]]
            };
            return scale3(&w, 1.0 / dot(&w, &w).sqrt());
        }
    }
    scale3(&r, 1.0 / n2.sqrt())
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
