//! The second rest shape of an interpolation (Ψt = (1−t)Ψ₁ + tΨ₂): a
//! target mesh with the same vertices and elements, or the twisted and bent
//! rest shape.

use crate::body::Body;
use crate::error::SceneError;
use crate::setup::mesh::{LoadedMesh, MeshKind, read_file};
use crate::setup::shape::{axis_index, twist_bend};
use crate::spec::SceneFile;

/// Read an interpolation target mesh with the same transform and elements.
fn target_positions(
    file: &SceneFile,
    loaded: &LoadedMesh,
    written: &str,
) -> Result<Vec<[f64; 3]>, SceneError> {
    let key = "effects.interpolate.target";
    let (mesh, _) = read_file(file, key, written)?;
    let m = &file.scene.mesh;
    let s = m.scale.unwrap_or(1.0);
    let t = m.translate.clone().unwrap_or_default();
    let tr = |p: [f64; 3]| {
        std::array::from_fn::<f64, 3, _>(|c| p[c] * s + t.get(c).copied().unwrap_or(0.0))
    };
    let same = |n: usize, elements_equal: bool| -> Result<(), SceneError> {
        let (nv, _) = loaded.counts();
        if n != nv || !elements_equal {
            return Err(SceneError::invalid(
                key,
                "the target must have the same vertices and elements as the mesh",
            ));
        }
        Ok(())
    };
    match (mesh, &loaded.kind) {
        (ecc_mesh::AnyMesh::Tet(tm), MeshKind::Volume(b)) => {
            same(tm.positions.len(), tm.tets == b.tets)?;
            Ok(tm.positions.into_iter().map(tr).collect())
        }
        (ecc_mesh::AnyMesh::Tri(tm), MeshKind::Planar(b)) => {
            same(tm.positions.len(), tm.triangles == b.triangles)?;
            Ok(tm.positions.into_iter().map(tr).collect())
        }
        (other, _) => Err(SceneError::invalid(
            key,
            format!(
                "the target is a {} mesh, the body is {}",
                other.kind(),
                loaded.kind_name()
            ),
        )),
    }
}

pub(crate) fn second_rest_3d(
    file: &SceneFile,
    body: &Body<3>,
    loaded: &LoadedMesh,
) -> Result<Option<Vec<[f64; 3]>>, SceneError> {
    let Some(i) = &file.scene.effects.interpolate else {
        return Ok(None);
    };
    if let Some(t) = &i.target {
        return target_positions(file, loaded, t).map(Some);
    }
    twist_bend::<3>(&body.rest, axis_index(i.axis.as_deref()), i.twist, i.bend).map(Some)
}

pub(crate) fn second_rest_2d(
    file: &SceneFile,
    body: &Body<2>,
    loaded: &LoadedMesh,
) -> Result<Option<Vec<[f64; 2]>>, SceneError> {
    let Some(i) = &file.scene.effects.interpolate else {
        return Ok(None);
    };
    if let Some(t) = &i.target {
        let p = target_positions(file, loaded, t)?;
        if p.iter().any(|q| q[2] != 0.0) {
            return Err(SceneError::invalid(
                "effects.interpolate.target",
                "the target of a planar mesh must be planar (z = 0)",
            ));
        }
        return Ok(Some(p.into_iter().map(|q| [q[0], q[1]]).collect()));
    }
    twist_bend::<2>(&body.rest, axis_index(i.axis.as_deref()), i.twist, i.bend).map(Some)
}
