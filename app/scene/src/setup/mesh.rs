//! `[mesh]`: read a file or generate a shape, scale and move it, validate it.
//!
//! Triangle meshes whose every z is 0 are *planar* (2D deformation);
//! other triangle meshes are *surfaces* (parameterisation only). Tet meshes
//! are volumes. Validation (ecc-mesh) rejects degenerate or inverted
//! elements and drops unreferenced vertices; `vertex_map` keeps the file's
//! ids so that `handles.ids` can refer to them.

use ecc_mesh::{
    AnyMesh, MeshError, TetMesh, TriMesh, ValidationOptions, bar_tet, box_tet, disk_tri, grid_tri,
    read_mesh, validate_tet, validate_tri,
};

use crate::error::SceneError;
use crate::handles::rotation;
use crate::spec::{SceneFile, Shape};

/// A validated mesh of one of the three kinds.
#[derive(Clone, Debug)]
pub enum MeshKind {
    /// Triangles in the plane z = 0.
    Planar(TriMesh),
    /// Triangles in 3D.
    Surface(TriMesh),
    /// Tetrahedra.
    Volume(TetMesh),
}

/// The body's mesh and where it came from.
#[derive(Clone, Debug)]
pub struct LoadedMesh {
    /// The mesh.
    pub kind: MeshKind,
    /// File id → body id (`None`: unreferenced vertex, dropped).
    pub vertex_map: Vec<Option<usize>>,
    /// "path/to/file" or "generated bar (resolution 2)".
    pub source: String,
    /// Validation notes (dropped vertices, several components).
    pub warnings: Vec<String>,
}

impl LoadedMesh {
    /// "planar triangle", "surface triangle" or "tetrahedral".
    pub fn kind_name(&self) -> &'static str {
        match self.kind {
            MeshKind::Planar(_) => "planar triangle",
            MeshKind::Surface(_) => "surface triangle",
            MeshKind::Volume(_) => "tetrahedral",
        }
    }

    /// (vertices, elements).
    pub fn counts(&self) -> (usize, usize) {
        match &self.kind {
            MeshKind::Planar(m) | MeshKind::Surface(m) => (m.positions.len(), m.triangles.len()),
            MeshKind::Volume(m) => (m.positions.len(), m.tets.len()),
        }
    }
}

fn mesh_error(key: &str, e: MeshError) -> SceneError {
    SceneError::invalid(key, e.to_string())
}

/// Read a mesh file named in the scene at `key`.
pub fn read_file(
    file: &SceneFile,
    key: &str,
    written: &str,
) -> Result<(AnyMesh, String), SceneError> {
    let path = file.resolve(written);
    if !path.exists() {
        let hint = if written.starts_with("data:") {
            " (set ECC_DATA_DIR to the folder with the public meshes)"
        } else {
            " (paths are relative to the scene file)"
        };
        return Err(SceneError::invalid(
            key,
            format!("file not found: {}{hint}", path.display()),
        ));
    }
    let mesh = read_mesh(&path).map_err(|e| mesh_error(key, e))?;
    Ok((mesh, path.display().to_string()))
}

fn generate(file: &SceneFile, shape: Shape) -> (AnyMesh, String) {
    let m = &file.scene.mesh;
    match shape {
        Shape::Bar => {
            let r = m.resolution.unwrap_or(2);
            (
                AnyMesh::Tet(bar_tet(r)),
                format!("generated bar (resolution {r})"),
            )
        }
        Shape::Box => {
            let c = m.cells.clone().unwrap_or(vec![4, 4, 4]);
            let s = m.size.clone().unwrap_or(vec![1.0, 1.0, 1.0]);
            (
                AnyMesh::Tet(box_tet(c[0], c[1], c[2], [s[0], s[1], s[2]])),
                format!("generated box ({}×{}×{} cells)", c[0], c[1], c[2]),
            )
        }
        Shape::Disk => {
            let rings = m.rings.unwrap_or(8);
            let radius = m.radius.unwrap_or(1.0);
            (
                AnyMesh::Tri(disk_tri(rings, radius)),
                format!("generated disk ({rings} rings)"),
            )
        }
        Shape::Grid => {
            let c = m.cells.clone().unwrap_or(vec![8, 8]);
            let s = m.size.clone().unwrap_or(vec![1.0, 1.0]);
            (
                AnyMesh::Tri(grid_tri(c[0], c[1], s[0], s[1])),
                format!("generated grid ({}×{} cells)", c[0], c[1]),
            )
        }
    }
}

/// The rotation matrix of `mesh.rotate` (degrees), if any.
fn rotation_of(file: &SceneFile, tri: bool) -> Result<Option<[[f64; 3]; 3]>, SceneError> {
    let Some(r) = &file.scene.mesh.rotate else {
        return Ok(None);
    };
    let r: [f64; 3] = match r.len() {
        3 => [r[0], r[1], r[2]],
        1 if tri => [0.0, 0.0, r[0]],
        n => {
            return Err(SceneError::invalid(
                "mesh.rotate",
                format!(
                    "expected a rotation vector [x, y, z] in degrees{}, got {n} components",
                    if tri {
                        " or [angle] for a planar mesh"
                    } else {
                        ""
                    }
                ),
            ));
        }
    };
    Ok(Some(rotation::<3>(r.map(f64::to_radians))))
}

/// Apply `scale`, `rotate` (about the bounding-box centre) and `translate`
/// (2 or 3 components; 2 only for triangle meshes).
fn transform(file: &SceneFile, positions: &mut [[f64; 3]], tri: bool) -> Result<(), SceneError> {
    let m = &file.scene.mesh;
    if let Some(r) = rotation_of(file, tri)? {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in positions.iter() {
            for c in 0..3 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
        let ctr: [f64; 3] = std::array::from_fn(|c| 0.5 * (lo[c] + hi[c]));
        for p in positions.iter_mut() {
            let d: [f64; 3] = std::array::from_fn(|c| p[c] - ctr[c]);
            *p = std::array::from_fn(|i| ctr[i] + (0..3).map(|j| r[i][j] * d[j]).sum::<f64>());
        }
    }
    let s = m.scale.unwrap_or(1.0);
    let t = match &m.translate {
        None => [0.0; 3],
        Some(v) if v.len() == 3 => [v[0], v[1], v[2]],
        Some(v) if v.len() == 2 && tri => [v[0], v[1], 0.0],
        Some(v) => {
            return Err(SceneError::invalid(
                "mesh.translate",
                format!(
                    "expected {} components, got {}",
                    if tri { "2 or 3" } else { "3" },
                    v.len()
                ),
            ));
        }
    };
    for p in positions.iter_mut() {
        for c in 0..3 {
            p[c] = p[c] * s + t[c];
        }
    }
    Ok(())
}

/// An axis-aligned box (min, max).
type Aabb = ([f64; 3], [f64; 3]);

/// The `crop` box (3 components; 2 allowed for triangle meshes, z unbounded).
fn crop_box(file: &SceneFile, tri: bool) -> Result<Option<Aabb>, SceneError> {
    let Some(b) = &file.scene.mesh.crop else {
        return Ok(None);
    };
    let get = |key: &str, v: &Vec<f64>, fill: f64| -> Result<[f64; 3], SceneError> {
        match v.len() {
            3 => Ok([v[0], v[1], v[2]]),
            2 if tri => Ok([v[0], v[1], fill]),
            n => Err(SceneError::invalid(
                key,
                format!(
                    "expected {} components, got {n}",
                    if tri { "2 or 3" } else { "3" }
                ),
            )),
        }
    };
    let lo = get("mesh.crop.min", &b.min, f64::NEG_INFINITY)?;
    let hi = get("mesh.crop.max", &b.max, f64::INFINITY)?;
    if lo.iter().chain(&hi).any(|c| c.is_nan()) || (0..3).any(|c| lo[c] > hi[c]) {
        return Err(SceneError::invalid(
            "mesh.crop",
            "`min` must be ≤ `max` in every component (and not NaN)",
        ));
    }
    Ok(Some((lo, hi)))
}

/// Keep the elements whose vertices are all inside the box.
fn crop<const K: usize>(
    elements: Vec<[usize; K]>,
    positions: &[[f64; 3]],
    (lo, hi): Aabb,
) -> Result<Vec<[usize; K]>, SceneError> {
    let inside = |v: usize| {
        positions
            .get(v)
            .is_some_and(|p| (0..3).all(|c| p[c] >= lo[c] && p[c] <= hi[c]))
    };
    let kept: Vec<[usize; K]> = elements
        .into_iter()
        .filter(|e| e.iter().all(|&v| inside(v)))
        .collect();
    if kept.is_empty() {
        return Err(SceneError::invalid(
            "mesh.crop",
            "no element lies inside the box",
        ));
    }
    Ok(kept)
}

/// Load `[mesh]` (file or generated), transform and validate it.
/// `surface_ok`: a non-planar triangle mesh is acceptable (parameterisation).
pub fn load(file: &SceneFile, surface_ok: bool) -> Result<LoadedMesh, SceneError> {
    let spec = &file.scene.mesh;
    let (mesh, source) = match (&spec.file, spec.generate) {
        (Some(f), _) => read_file(file, "mesh.file", f)?,
        (None, Some(shape)) => generate(file, shape),
        (None, None) => return Err(SceneError::invalid("mesh", "no mesh given")),
    };
    let key = if spec.file.is_some() {
        "mesh.file"
    } else {
        "mesh"
    };
    let min_quality = spec.min_quality.unwrap_or(0.0);
    if !(min_quality.is_finite() && min_quality >= 0.0) {
        return Err(SceneError::invalid(
            "mesh.min_quality",
            format!("must be a finite number ≥ 0, got {min_quality}"),
        ));
    }
    // Cropping leaves vertices without elements on purpose.
    let opts = ValidationOptions {
        drop_unreferenced: spec.drop_unreferenced.unwrap_or(false) || spec.crop.is_some(),
        min_quality,
        ..Default::default()
    };
    let invalid = |e: ecc_mesh::ValidationError| {
        let hint = match e {
            ecc_mesh::ValidationError::UnreferencedVertices { .. } => {
                " (set `drop_unreferenced = true` in [mesh] to drop unused vertices)"
            }
            ecc_mesh::ValidationError::LowQualityElements { .. } => {
                " (lower or remove `min_quality` in [mesh] to accept them)"
            }
            _ => "",
        };
        SceneError::invalid(key, format!("the mesh is not usable: {e}{hint}"))
    };
    match mesh {
        AnyMesh::Tri(mut m) => {
            transform(file, &mut m.positions, true)?;
            if let Some(bx) = crop_box(file, true)? {
                m.triangles = crop(std::mem::take(&mut m.triangles), &m.positions, bx)?;
            }
            let planar = !surface_ok && m.positions.iter().all(|p| p[2] == 0.0);
            if !planar && !surface_ok {
                return Err(SceneError::invalid(
                    key,
                    "a triangle surface in 3D can only be parameterised (add \
                     [effects.parameterize]); deformation needs a planar (z = 0) \
                     triangle mesh or a tet mesh",
                ));
            }
            let v = validate_tri(m, planar, &opts).map_err(invalid)?;
            Ok(LoadedMesh {
                kind: if planar {
                    MeshKind::Planar(v.mesh)
                } else {
                    MeshKind::Surface(v.mesh)
                },
                vertex_map: v.vertex_map,
                source,
                warnings: v.warnings,
            })
        }
        AnyMesh::Tet(mut m) => {
            if surface_ok {
                return Err(SceneError::invalid(
                    key,
                    "a parameterisation needs a triangle surface mesh, got a tetrahedral mesh",
                ));
            }
            transform(file, &mut m.positions, false)?;
            if let Some(bx) = crop_box(file, false)? {
                m.tets = crop(std::mem::take(&mut m.tets), &m.positions, bx)?;
            }
            let v = validate_tet(m, &opts).map_err(invalid)?;
            Ok(LoadedMesh {
                kind: MeshKind::Volume(v.mesh),
                vertex_map: v.vertex_map,
                source,
                warnings: v.warnings,
            })
        }
    }
}
