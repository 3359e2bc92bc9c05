//! How pictures look at a scene: camera, up direction, ground plane.

use crate::spec::SceneFile;

pub(crate) fn camera(file: &SceneFile) -> (f64, f64) {
    match &file.scene.output.camera {
        Some(c) => (c[0], c[1]),
        None => (35.0, 25.0),
    }
}

/// Up for pictures: −gravity, else the ground normal, else +y.
pub(crate) fn up_direction(file: &SceneFile) -> [f64; 3] {
    let fx = &file.scene.effects;
    let pad = |v: &Vec<f64>| [v[0], v[1], v.get(2).copied().unwrap_or(0.0)];
    if let Some(g) = &fx.gravity
        && g.iter().any(|c| *c != 0.0)
    {
        let p = pad(g);
        return [-p[0], -p[1], -p[2]];
    }
    if let Some(n) = fx.ground.as_ref().and_then(|g| g.normal.as_ref()) {
        return pad(n);
    }
    [0.0, 1.0, 0.0]
}

pub(crate) fn ground_plane(file: &SceneFile) -> Option<([f64; 3], f64)> {
    let g = file.scene.effects.ground.as_ref()?;
    let n = match &g.normal {
        Some(v) => [v[0], v[1], v.get(2).copied().unwrap_or(0.0)],
        None => [0.0, 1.0, 0.0],
    };
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    Some((n.map(|c| c / len), g.height))
}
