//! Second rest shapes for interpolation, as deformations of the first.
//!
//! Along an axis a with extent [lo, hi] (length L) and cross-section centre c:
//!
//! * **twist** by Θ: the cross-section at s = (p_a − lo)/L ∈ [0, 1] turns
//!   by θ = Θ(s − ½) about the axis (3D only);
//! * **bend** by Φ into a circular arc of radius R = L/Φ curving towards
//!   the next axis b (x→y, y→z, z→x; in 2D the other axis): with arc
//!   length u = p_a − mid and offset q = p_b − c_b, r = R − q, α = u/R,
//!   p_a ← mid + r sin α, p_b ← c_b + R − r cos α. Its Jacobian in the
//!   (a, b) plane has determinant r/R, so elements keep their orientation
//!   as long as every q < R (checked).

use crate::error::SceneError;

/// Axis index from its name.
pub fn axis_index(name: Option<&str>) -> usize {
    match name {
        Some("y") => 1,
        Some("z") => 2,
        _ => 0,
    }
}

fn extent<const D: usize>(x: &[[f64; D]], c: usize) -> (f64, f64) {
    x.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p[c]), hi.max(p[c]))
        })
}

/// Twist (3D) then bend the positions `x` along `axis` (see the module docs).
pub fn twist_bend<const D: usize>(
    x: &[[f64; D]],
    axis: usize,
    twist_deg: Option<f64>,
    bend_deg: Option<f64>,
) -> Result<Vec<[f64; D]>, SceneError> {
    let key = "effects.interpolate";
    if axis >= D {
        return Err(SceneError::invalid(
            format!("{key}.axis"),
            format!("a {D}D mesh has no axis {}", ["x", "y", "z"][axis]),
        ));
    }
    let (lo, hi) = extent(x, axis);
    let len = hi - lo;
    if !(len > 0.0) {
        return Err(SceneError::invalid(
            format!("{key}.axis"),
            "the mesh has no extent along this axis",
        ));
    }
    let mut out = x.to_vec();
    if let Some(tw) = twist_deg.filter(|t| *t != 0.0) {
        if D != 3 {
            return Err(SceneError::invalid(
                format!("{key}.twist"),
                "a twist needs a 3D (tet) mesh",
            ));
        }
        let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
        let cb = {
            let (l, h) = extent(x, b);
            0.5 * (l + h)
        };
        let cc = {
            let (l, h) = extent(x, c);
            0.5 * (l + h)
        };
        for p in out.iter_mut() {
            let s = (p[axis] - lo) / len;
            let (sn, cs) = (tw.to_radians() * (s - 0.5)).sin_cos();
            let (u, v) = (p[b] - cb, p[c] - cc);
            p[b] = cb + cs * u - sn * v;
            p[c] = cc + sn * u + cs * v;
        }
    }
    if let Some(bd) = bend_deg.filter(|b| *b != 0.0) {
        let b = (axis + 1) % D;
        let phi = bd.to_radians();
        let radius = len / phi;
        let mid = 0.5 * (lo + hi);
        let cb = {
            let (l, h) = extent(&out, b);
            0.5 * (l + h)
        };
        for p in out.iter_mut() {
            let (u, q) = (p[axis] - mid, p[b] - cb);
            let r = radius - q;
            if r / radius <= 0.0 {
                return Err(SceneError::invalid(
                    format!("{key}.bend"),
                    format!(
                        "bending by {bd}° folds the mesh: the arc radius {:.3} is smaller than its thickness",
                        radius.abs()
                    ),
                ));
            }
            let alpha = u / radius;
            p[axis] = mid + r * alpha.sin();
            p[b] = cb + radius - r * alpha.cos();
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twist_turns_the_ends_and_bend_keeps_the_neutral_length() {
        let x = vec![[-2.0, 0.5, 0.0], [2.0, 0.5, 0.0], [0.0, -0.5, 0.0]];
        let t = twist_bend::<3>(&x, 0, Some(180.0), None).unwrap();
        // ends turn by ∓90° about x
        assert!(
            (t[0][1]).abs() < 1e-12 && (t[0][2] + 0.5).abs() < 1e-12,
            "{:?}",
            t[0]
        );
        assert!(
            (t[1][1]).abs() < 1e-12 && (t[1][2] - 0.5).abs() < 1e-12,
            "{:?}",
            t[1]
        );
        let y = vec![
            [-2.0, 0.0],
            [2.0, 0.0],
            [0.0, 0.0],
            [0.0, 0.25],
            [0.0, -0.25],
        ];
        let b = twist_bend::<2>(&y, 0, None, Some(90.0)).unwrap();
        // the arc through the centre line has radius 4/(π/2)
        let r = 4.0 / std::f64::consts::FRAC_PI_2;
        let d = ((b[0][0] - 0.0).powi(2) + (b[0][1] - r).powi(2)).sqrt();
        assert!((d - r).abs() < 1e-12);
        assert!(twist_bend::<2>(&y, 0, Some(10.0), None).is_err());
        assert!(twist_bend::<2>(&y, 0, None, Some(2000.0)).is_err());
    }
}
