//! Inversion-free step bounds (Smith & Schaefer 2015).
//!
//! Along x + α·d the edge matrix of a simplex is D(α) = D + α·Δ, so
//! det D(α) is a polynomial in α: quadratic for a triangle in 2D,
//!
//!   det[e₁+αf₁, e₂+αf₂] = e₁×e₂ + α(e₁×f₂ + f₁×e₂) + α² f₁×f₂,
//!
//! and cubic for a tet, with coefficients that are sums of mixed
//! determinants (see [`tet_det_poly`]). The element stays uninverted on
//! [0, α*) where α* is the smallest positive root.
//!
//! Closed-form roots lose everything when the leading coefficients nearly
//! vanish (the common case: most elements barely deform along d), so instead
//! [`first_nonpositive`] splits the search interval at the critical points of
//! p (roots of the quadratic p′, computed with the cancellation-free formula),
//! on each monotone piece checks the sign at the right end, and bisects the
//! first piece where p becomes ≤ 0. It returns the *left* end of the final
//! bracket, where p > 0, so the bound is conservative. No special cases for
//! degenerate degrees are needed.

/// Coefficients (c₀, c₁, c₂) of det[e₁+αf₁, e₂+αf₂] for a triangle with edge
/// vectors e = x₁−x₀, x₂−x₀ and direction differences f = d₁−d₀, d₂−d₀.
#[inline]
pub fn tri_det_poly(e1: [f64; 2], e2: [f64; 2], f1: [f64; 2], f2: [f64; 2]) -> [f64; 4] {
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    [
        cross(e1, e2),
        cross(e1, f2) + cross(f1, e2),
        cross(f1, f2),
        0.0,
    ]
}

/// Coefficients (c₀…c₃) of det[a+αda, b+αdb, c+αdc] (columns).
#[inline]
pub fn tet_det_poly(
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
    da: [f64; 3],
    db: [f64; 3],
    dc: [f64; 3],
) -> [f64; 4] {
    let det = |x: [f64; 3], y: [f64; 3], z: [f64; 3]| {
        x[0] * (y[1] * z[2] - y[2] * z[1]) - y[0] * (x[1] * z[2] - x[2] * z[1])
            + z[0] * (x[1] * y[2] - x[2] * y[1])
    };
    [
        det(a, b, c),
        det(da, b, c) + det(a, db, c) + det(a, b, dc),
        det(a, db, dc) + det(da, b, dc) + det(da, db, c),
        det(da, db, dc),
    ]
}

#[inline]
fn eval(c: &[f64; 4], t: f64) -> f64 {
    ((c[3] * t + c[2]) * t + c[1]) * t + c[0]
}

/// Real roots of a + b t + c t² (0, 1 or 2 of them; a zero polynomial has none).
fn quadratic_roots(a: f64, b: f64, c: f64) -> ([f64; 2], usize) {
    if c == 0.0 {
        if b == 0.0 {
            return ([0.0; 2], 0);
        }
        return ([-a / b, 0.0], 1);
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return ([0.0; 2], 0);
    }
    // q = −(b + sign(b)√disc)/2; roots q/c and a/q (no cancellation)
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        // b = 0 and disc = 0 ⇒ a = 0: double root at 0
        return ([0.0, 0.0], 2);
    }
    ([q / c, a / q], 2)
}

/// For p(t) = c₀ + c₁t + c₂t² + c₃t³ with p(0) = c₀ > 0: the largest
/// `t ≤ t_max` such that p > 0 on [0, t), returned conservatively (within
/// ~1e-14·t_max below the first root). `None` if p > 0 on all of [0, t_max].
/// Returns `Some(0.0)` if p(0) ≤ 0 or any coefficient is not finite.
pub fn first_nonpositive(c: [f64; 4], t_max: f64) -> Option<f64> {
    if c.iter().any(|v| !v.is_finite()) || c[0] <= 0.0 {
        return Some(0.0);
    }
    // breakpoints: 0, critical points in (0, t_max), t_max
    let (crit, n) = quadratic_roots(c[1], 2.0 * c[2], 3.0 * c[3]);
    let mut pts = [0.0, t_max, t_max, t_max];
    let mut m = 1;
    for &r in &crit[..n] {
        if r > 0.0 && r < t_max {
            pts[m] = r;
            m += 1;
        }
    }
    pts[m] = t_max;
    pts[1..=m].sort_by(f64::total_cmp);
    for k in 0..m {
        let (lo0, hi0) = (pts[k], pts[k + 1]);
        if eval(&c, hi0) > 0.0 {
            continue;
        }
        // p(lo0) > 0 ≥ p(hi0) and p is monotone on [lo0, hi0]: bisect
        let (mut lo, mut hi) = (lo0, hi0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if eval(&c, mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        return Some(lo);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simple_roots() {
        // p = 1 − 2t: root 0.5
        let r = first_nonpositive([1.0, -2.0, 0.0, 0.0], 2.0).unwrap();
        assert!((r - 0.5).abs() < 1e-14 && r <= 0.5);
        // p = (1 − t)(1 − 3t)·… : 1 − 4t + 3t², first root 1/3
        let r = first_nonpositive([1.0, -4.0, 3.0, 0.0], 2.0).unwrap();
        assert!((r - 1.0 / 3.0).abs() < 1e-14);
        // cubic (1−t)(2−t)(0.25+t)... roots 1, 2, −0.25 ⇒ first positive 1
        // (1−t)(2−t) = 2 − 3t + t²; ×(0.25+t) = 0.5 + 1.25t −2.75t²... compute:
        let c = [0.5, 2.0 - 0.75, 0.25 - 3.0, 1.0];
        let r = first_nonpositive(c, 3.0).unwrap();
        assert!((r - 1.0).abs() < 1e-12, "{r}");
        // positive everywhere
        assert_eq!(first_nonpositive([1.0, 1.0, 1.0, 1.0], 2.0), None);
        assert_eq!(first_nonpositive([1.0, 0.0, 0.0, 0.0], 2.0), None);
        // root beyond t_max
        assert_eq!(first_nonpositive([1.0, -0.1, 0.0, 0.0], 2.0), None);
        // not positive at 0
        assert_eq!(first_nonpositive([0.0, 1.0, 0.0, 0.0], 2.0), Some(0.0));
        assert_eq!(first_nonpositive([1.0, f64::NAN, 0.0, 0.0], 2.0), Some(0.0));
    }

    #[test]
    fn tangent_and_tiny_leading_coefficients() {
        // double root at 0.5: (1 − 2t)² touches zero without a sign change
        let r = first_nonpositive([1.0, -4.0, 4.0, 0.0], 2.0).unwrap();
        assert!((r - 0.5).abs() < 1e-7, "{r}");
        // nearly linear: 1 − t + 1e-30 t³
        let r = first_nonpositive([1.0, -1.0, 0.0, 1e-30], 2.0).unwrap();
        assert!((r - 1.0).abs() < 1e-14);
        // huge leading coefficient: 1 + 1e12 t² − 1e12 t³ → root just above 1
        let r = first_nonpositive([1.0, 0.0, 1e12, -1e12], 2.0).unwrap();
        assert!(r > 1.0 && r < 1.0 + 1e-11, "{r}");
    }

    #[test]
    fn det_polynomials_match_direct_evaluation() {
        let (e1, e2, f1, f2) = ([1.0, 0.2], [-0.3, 0.9], [0.5, -1.1], [0.7, 0.4]);
        let c = tri_det_poly(e1, e2, f1, f2);
        for t in [0.0, 0.3, 1.7] {
            let a = [e1[0] + t * f1[0], e1[1] + t * f1[1]];
            let b = [e2[0] + t * f2[0], e2[1] + t * f2[1]];
            assert!((eval(&c, t) - (a[0] * b[1] - a[1] * b[0])).abs() < 1e-12);
        }
        let (a, b, cc) = ([1.0, 0.1, -0.2], [0.3, 1.2, 0.1], [-0.1, 0.2, 0.8]);
        let (da, db, dc) = ([0.4, -0.5, 0.3], [-0.2, 0.6, 0.9], [1.1, 0.1, -0.7]);
        let p = tet_det_poly(a, b, cc, da, db, dc);
        for t in [0.0, 0.45, 2.0] {
            let m = |x: [f64; 3], d: [f64; 3]| [x[0] + t * d[0], x[1] + t * d[1], x[2] + t * d[2]];
            let q = tet_det_poly(m(a, da), m(b, db), m(cc, dc), [0.0; 3], [0.0; 3], [0.0; 3]);
            assert!((eval(&p, t) - q[0]).abs() < 1e-12);
        }
    }
}
