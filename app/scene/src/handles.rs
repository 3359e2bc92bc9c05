//! Handles: vertex sets held by exact Dirichlet constraints (the solver's
//! fixed vertices), pinned at rest or driven by keyframed rigid transforms
//! (volume deformation, Smith et al. 2019 §6.2).
//!
//! A key at frame f holds a rotation (rotation vector r = angle·axis in 3D,
//! an angle in 2D, degrees in the file) about the handle's centre c and a
//! translation t: p ↦ c + R(r)(p − c) + t. Between keys, r and t are
//! interpolated linearly in the frame number (exact for rotations about a
//! fixed axis) and R(r) is Rodrigues' formula
//! R = I + sin θ K + (1 − cos θ) K², θ = |r|, K = [r/θ]×. Before the first
//! key the handle rests (identity at frame 0 unless frame 0 is keyed);
//! after the last key it holds.

use crate::error::SceneError;
use crate::spec::{HandleSpec, KeySpec};

/// One rigid key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key<const D: usize> {
    /// Frame number (may be fractional).
    pub frame: f64,
    /// Translation.
    pub translate: [f64; D],
    /// Rotation vector in radians (2D: only the last entry is used, the angle).
    pub rotate: [f64; 3],
}

/// A handle ready to drive vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct Handle<const D: usize> {
    /// Label.
    pub name: String,
    /// Vertex ids (sorted, unique).
    pub vertices: Vec<usize>,
    /// Rest positions of those vertices.
    pub rest: Vec<[f64; D]>,
    /// Rotation centre.
    pub center: [f64; D],
    /// Keys sorted by frame (empty: pinned).
    pub keys: Vec<Key<D>>,
}

/// R(r) as a D×D matrix (row-major).
pub fn rotation<const D: usize>(r: [f64; 3]) -> [[f64; D]; D] {
    let mut m = [[0.0; D]; D];
    if D == 2 {
        let (s, c) = r[2].sin_cos();
        m[0][0] = c;
        m[0][1] = -s;
        m[1][0] = s;
        m[1][1] = c;
        return m;
    }
    let theta = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    for (i, row) in m.iter_mut().enumerate() {
        row[i] = 1.0;
    }
    if theta == 0.0 {
        return m;
    }
    let k = [r[0] / theta, r[1] / theta, r[2] / theta];
    let kx = [[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]];
    let (s, c) = theta.sin_cos();
    for i in 0..3 {
        for j in 0..3 {
            let k2: f64 = (0..3).map(|l| kx[i][l] * kx[l][j]).sum();
            m[i][j] += s * kx[i][j] + (1.0 - c) * k2;
        }
    }
    m
}

impl<const D: usize> Handle<D> {
    /// The interpolated key at `frame` (identity before any key).
    pub fn key_at(&self, frame: f64) -> Key<D> {
        let identity = Key {
            frame: 0.0,
            translate: [0.0; D],
            rotate: [0.0; 3],
        };
        let Some(first) = self.keys.first() else {
            return identity;
        };
        let (mut lo, mut hi) = if first.frame > 0.0 {
            (identity, *first)
        } else {
            (*first, *first)
        };
        for k in &self.keys {
            if k.frame <= frame {
                lo = *k;
                hi = *k;
            } else {
                hi = *k;
                break;
            }
        }
        if frame <= lo.frame || hi.frame <= lo.frame {
            return if frame >= hi.frame { hi } else { lo };
        }
        let s = ((frame - lo.frame) / (hi.frame - lo.frame)).clamp(0.0, 1.0);
        Key {
            frame,
            translate: std::array::from_fn(|c| {
                lo.translate[c] + s * (hi.translate[c] - lo.translate[c])
            }),
            rotate: std::array::from_fn(|c| lo.rotate[c] + s * (hi.rotate[c] - lo.rotate[c])),
        }
    }

    /// Positions of the handle's vertices at `frame`.
    pub fn positions_at(&self, frame: f64) -> Vec<[f64; D]> {
        let k = self.key_at(frame);
        let r = rotation::<D>(k.rotate);
        self.rest
            .iter()
            .map(|p| {
                // p + (R − I)(p − c) + t: exactly p for the identity (pinned handles)
                std::array::from_fn(|i| {
                    let rp: f64 = (0..D)
                        .map(|j| {
                            (r[i][j] - if i == j { 1.0 } else { 0.0 }) * (p[j] - self.center[j])
                        })
                        .sum();
                    p[i] + rp + k.translate[i]
                })
            })
            .collect()
    }

    /// The last key frame (0 when pinned).
    pub fn last_frame(&self) -> f64 {
        self.keys.last().map_or(0.0, |k| k.frame)
    }
}

/// A vector value of length D from the file (the length is checked).
pub fn vector<const D: usize>(key: &str, v: &[f64]) -> Result<[f64; D], SceneError> {
    if v.len() != D {
        return Err(SceneError::invalid(
            key,
            format!(
                "expected {D} components for this {D}D scene, got {}",
                v.len()
            ),
        ));
    }
    if let Some(i) = v.iter().position(|c| !c.is_finite()) {
        return Err(SceneError::invalid(
            key,
            format!("component {i} is not finite"),
        ));
    }
    Ok(std::array::from_fn(|i| v[i]))
}

fn key_from_spec<const D: usize>(path: &str, k: &KeySpec) -> Result<Key<D>, SceneError> {
    if !k.frame.is_finite() || k.frame < 0.0 {
        return Err(SceneError::invalid(
            format!("{path}.frame"),
            format!("must be a frame number ≥ 0, got {}", k.frame),
        ));
    }
    let translate = match &k.translate {
        Some(t) => vector::<D>(&format!("{path}.translate"), t)?,
        None => [0.0; D],
    };
    let rotate = match &k.rotate {
        None => [0.0; 3],
        Some(r) => {
            let want = if D == 2 { 1 } else { 3 };
            let rk = format!("{path}.rotate");
            if r.len() != want {
                let what = if D == 2 {
                    "`[angle]` (degrees) in 2D"
                } else {
                    "a rotation vector `[x, y, z]` (axis × degrees) in 3D"
                };
                return Err(SceneError::invalid(
                    rk,
                    format!("expected {what}, got {} components", r.len()),
                ));
            }
            if r.iter().any(|c| !c.is_finite()) {
                return Err(SceneError::invalid(rk, "must be finite"));
            }
            let rad = |d: f64| d.to_radians();
            if D == 2 {
                [0.0, 0.0, rad(r[0])]
            } else {
                [rad(r[0]), rad(r[1]), rad(r[2])]
            }
        }
    };
    Ok(Key {
        frame: k.frame,
        translate,
        rotate,
    })
}

/// The vertices `spec` selects (`ids` through `vertex_map`, a `box` or a
/// half-space `plane`), unsorted.
fn select<const D: usize>(
    path: &str,
    spec: &HandleSpec,
    rest: &[[f64; D]],
    vertex_map: &[Option<usize>],
) -> Result<Vec<usize>, SceneError> {
    let vertices: Vec<usize> = if let Some(ids) = &spec.ids {
        let mut out = Vec::with_capacity(ids.len());
        for &id in ids {
            match vertex_map.get(id) {
                Some(Some(v)) => out.push(*v),
                Some(None) => {
                    return Err(SceneError::invalid(
                        format!("{path}.ids"),
                        format!("vertex {id} is not used by any element (it was dropped)"),
                    ));
                }
                None => {
                    return Err(SceneError::invalid(
                        format!("{path}.ids"),
                        format!(
                            "vertex {id} does not exist (the mesh has {} vertices)",
                            vertex_map.len()
                        ),
                    ));
                }
            }
        }
        out
    } else if let Some(b) = &spec.bbox {
        let lo = vector::<D>(&format!("{path}.box.min"), &b.min)?;
        let hi = vector::<D>(&format!("{path}.box.max"), &b.max)?;
        if (0..D).any(|c| lo[c] > hi[c]) {
            return Err(SceneError::invalid(
                format!("{path}.box"),
                "`min` must be ≤ `max` in every component",
            ));
        }
        (0..rest.len())
            .filter(|&v| (0..D).all(|c| rest[v][c] >= lo[c] && rest[v][c] <= hi[c]))
            .collect()
    } else {
        let p = spec.plane.as_ref().expect("one selector is present");
        let point = vector::<D>(&format!("{path}.plane.point"), &p.point)?;
        let normal = vector::<D>(&format!("{path}.plane.normal"), &p.normal)?;
        if normal.iter().all(|c| *c == 0.0) {
            return Err(SceneError::invalid(
                format!("{path}.plane.normal"),
                "must not be zero",
            ));
        }
        (0..rest.len())
            .filter(|&v| {
                (0..D)
                    .map(|c| (rest[v][c] - point[c]) * normal[c])
                    .sum::<f64>()
                    >= 0.0
            })
            .collect()
    };
    Ok(vertices)
}

/// Select and build handle `index` of the scene.
///
/// `vertex_map` maps the mesh file's vertex ids to the body's (unreferenced
/// vertices are dropped when a mesh is read); `taken[v]` names the handle
/// that already holds vertex v.
pub fn build_handle<const D: usize>(
    index: usize,
    spec: &HandleSpec,
    rest: &[[f64; D]],
    vertex_map: &[Option<usize>],
    taken: &mut [Option<usize>],
) -> Result<Handle<D>, SceneError> {
    let path = format!("effects.handles[{index}]");
    let name = spec
        .name
        .clone()
        .unwrap_or_else(|| format!("handle{index}"));
    let chosen = [
        spec.ids.is_some(),
        spec.bbox.is_some(),
        spec.plane.is_some(),
    ]
    .iter()
    .filter(|b| **b)
    .count();
    if chosen != 1 {
        return Err(SceneError::invalid(
            path,
            "give exactly one of `ids`, `box` or `plane` to select vertices",
        ));
    }
    let mut vertices = select::<D>(&path, spec, rest, vertex_map)?;
    vertices.sort_unstable();
    vertices.dedup();
    if vertices.is_empty() {
        return Err(SceneError::invalid(
            path,
            "selects no vertex (check the box / plane against the mesh's bounding box)",
        ));
    }
    for &v in &vertices {
        if let Some(other) = taken[v] {
            return Err(SceneError::invalid(
                path,
                format!("vertex {v} is also in handle {other}; handles must not overlap"),
            ));
        }
        taken[v] = Some(index);
    }
    let hrest: Vec<[f64; D]> = vertices.iter().map(|&v| rest[v]).collect();
    let center = match &spec.center {
        Some(c) => vector::<D>(&format!("{path}.center"), c)?,
        None => {
            std::array::from_fn(|c| hrest.iter().map(|p| p[c]).sum::<f64>() / hrest.len() as f64)
        }
    };
    let mut keys = Vec::with_capacity(spec.keys.len());
    for (k, ks) in spec.keys.iter().enumerate() {
        let key = key_from_spec::<D>(&format!("{path}.keys[{k}]"), ks)?;
        if let Some(prev) = keys.last().map(|p: &Key<D>| p.frame)
            && key.frame <= prev
        {
            return Err(SceneError::invalid(
                format!("{path}.keys[{k}].frame"),
                format!("key frames must increase (previous key is at frame {prev})"),
            ));
        }
        keys.push(key);
    }
    Ok(Handle {
        name,
        vertices,
        rest: hrest,
        center,
        keys,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn handle3(keys: Vec<Key<3>>) -> Handle<3> {
        Handle {
            name: "h".into(),
            vertices: vec![0],
            rest: vec![[1.0, 0.0, 0.0]],
            center: [0.0; 3],
            keys,
        }
    }

    #[test]
    fn rotation_is_orthonormal_and_turns_the_right_way() {
        let r = rotation::<3>([0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        // e_x → e_y about +z
        assert!((r[1][0] - 1.0).abs() < 1e-15 && r[0][0].abs() < 1e-15);
        let r = rotation::<3>([0.3, -0.2, 0.9]);
        for i in 0..3 {
            for j in 0..3 {
                let d: f64 = (0..3).map(|k| r[k][i] * r[k][j]).sum();
                assert!((d - f64::from(u8::from(i == j))).abs() < 1e-14);
            }
        }
        let r2 = rotation::<2>([0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        assert!((r2[1][0] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn keys_interpolate_and_hold() {
        let h = handle3(vec![Key {
            frame: 10.0,
            translate: [0.0, 0.0, 2.0],
            rotate: [0.0, 0.0, std::f64::consts::PI],
        }]);
        assert_eq!(h.positions_at(0.0), vec![[1.0, 0.0, 0.0]]);
        let mid = h.positions_at(5.0)[0];
        assert!(
            (mid[0]).abs() < 1e-14 && (mid[1] - 1.0).abs() < 1e-14 && (mid[2] - 1.0).abs() < 1e-14
        );
        let end = h.positions_at(20.0)[0];
        assert!((end[0] + 1.0).abs() < 1e-14 && (end[2] - 2.0).abs() < 1e-14);
        assert_eq!(h.last_frame(), 10.0);
    }

    #[test]
    fn selection_errors_name_the_key() {
        let rest = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let map: Vec<Option<usize>> = (0..3).map(Some).collect();
        let mut taken = vec![None; 3];
        let spec = HandleSpec {
            plane: Some(crate::spec::PlaneSelect {
                point: vec![5.0, 0.0],
                normal: vec![1.0, 0.0],
            }),
            ..Default::default()
        };
        let e = build_handle::<2>(0, &spec, &rest, &map, &mut taken).unwrap_err();
        assert_eq!(e.key(), Some("effects.handles[0]"));
        let spec = HandleSpec {
            ids: Some(vec![0, 7]),
            ..Default::default()
        };
        let e = build_handle::<2>(1, &spec, &rest, &map, &mut taken).unwrap_err();
        assert_eq!(e.key(), Some("effects.handles[1].ids"));
        let ok = HandleSpec {
            ids: Some(vec![1, 0, 1]),
            ..Default::default()
        };
        let h = build_handle::<2>(2, &ok, &rest, &map, &mut taken).unwrap();
        assert_eq!(h.vertices, vec![0, 1]);
        assert_eq!(h.center, [0.5, 0.0]);
        let e = build_handle::<2>(3, &ok, &rest, &map, &mut taken).unwrap_err();
        assert!(e.to_string().contains("also in handle 2"), "{e}");
    }
}
