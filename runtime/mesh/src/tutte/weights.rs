//! Per-triangle contributions to the edge weights `w_ij` of the Tutte
//! system `Σ_j w_ij (u_i − u_j) = 0`.
//!
//! For a triangle with corner `i` and the other corners `j`, `k`, with
//! `a = x_j − x_i`, `b = x_k − x_i`, `α_i` the angle between them:
//! * uniform: `w_ij = 1` per undirected edge (each interior edge is seen by
//!   two triangles, so each triangle adds `1/2`);
//! * cotangent: the corner `i` adds `cot(α_i)/2` to the opposite edge `jk`
//!   (both directions), `cot α = a·b / |a × b|`;
//! * mean value (Floater 2003): the corner `i` adds `tan(α_i/2) / |a|` to
//!   `w_ij` and `tan(α_i/2) / |b|` to `w_ik` (row `i` only),
//!   `tan(α/2) = |a × b| / (|a||b| + a·b)`.
//!
//! Boundary edges see one triangle only; for uniform weights they get `1/2`
//! instead of `1`, which is harmless: boundary–boundary weights never enter
//! the system (both ends are fixed).

use crate::geometry::{cross, dot, norm, sub};
use crate::types::TutteWeights;

/// A directed weight contribution `w_{row, col} += value`.
pub(crate) type Contribution = (usize, usize, f64);

/// Contributions of triangle `t` (vertex positions `positions`, read only
/// by the weights that depend on them). Returns the directed edge whose
/// weight is not finite, if any.
pub(crate) fn triangle_contributions(
    weights: TutteWeights,
    t: [usize; 3],
    positions: &[[f64; 3]],
    out: &mut Vec<Contribution>,
) -> Result<(), [usize; 2]> {
    if weights == TutteWeights::Uniform {
        for c in 0..3 {
            let (i, j) = (t[c], t[(c + 1) % 3]);
            out.extend([(i, j, 0.5), (j, i, 0.5)]);
        }
        return Ok(());
    }
    let p = t.map(|v| positions[v]);
    for c in 0..3 {
        let (i, j, k) = (t[c], t[(c + 1) % 3], t[(c + 2) % 3]);
        let a = sub(p[(c + 1) % 3], p[c]);
        let b = sub(p[(c + 2) % 3], p[c]);
        if weights == TutteWeights::Cotangent {
            let w = 0.5 * dot(a, b) / norm(cross(a, b));
            if !w.is_finite() {
                return Err([j, k]);
            }
            out.extend([(j, k, w), (k, j, w)]);
        } else {
            let (la, lb) = (norm(a), norm(b));
            let half_tan = norm(cross(a, b)) / (la * lb + dot(a, b));
            let (wj, wk) = (half_tan / la, half_tan / lb);
            if !wj.is_finite() {
                return Err([i, j]);
            }
            if !wk.is_finite() {
                return Err([i, k]);
            }
            out.extend([(i, j, wj), (i, k, wk)]);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sum(c: &[Contribution], r: usize, s: usize) -> f64 {
        c.iter().filter(|x| x.0 == r && x.1 == s).map(|x| x.2).sum()
    }

    #[test]
    fn right_triangle_weights() {
        let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let mut c = Vec::new();
        triangle_contributions(TutteWeights::Cotangent, [0, 1, 2], &p, &mut c).unwrap();
        // Right angle at 0: cot = 0 for edge 12; 45° at 1 and 2: cot = 1.
        assert!(sum(&c, 1, 2).abs() < 1e-15);
        assert!((sum(&c, 0, 2) - 0.5).abs() < 1e-15);
        assert!((sum(&c, 2, 0) - 0.5).abs() < 1e-15);
        c.clear();
        triangle_contributions(TutteWeights::MeanValue, [0, 1, 2], &p, &mut c).unwrap();
        // At 0: tan(45°) = 1, edges of length 1.
        assert!((sum(&c, 0, 1) - 1.0).abs() < 1e-15);
        // At 1: tan(22.5°) / 1 toward 0.
        assert!((sum(&c, 1, 0) - (std::f64::consts::PI / 8.0).tan()).abs() < 1e-15);
        c.clear();
        let flat = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        assert!(triangle_contributions(TutteWeights::Cotangent, [0, 1, 2], &flat, &mut c).is_err());
        assert!(triangle_contributions(TutteWeights::MeanValue, [0, 1, 2], &flat, &mut c).is_err());
    }
}
