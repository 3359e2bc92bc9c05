//! The `[fibers]` term: directions from the scene or the mesh file, a
//! hand-written fibre energy, and `ecc_fem::Fibre` over the body's elements.
//!
//! File fields (`field`, `references`) are per element of `mesh.file` in
//! file order and in file coordinates: they are rejected together with
//! `mesh.crop` (which drops elements) or `mesh.rotate` (which would turn
//! them). Generators are evaluated at the element centroids of the body as
//! placed in the scene.

use std::any::Any;
use std::path::Path;
use std::sync::Arc;

use ecc_fem::{Fibre, Term};
use ecc_mesh::{FibreGenerator, check_directions, from_references, read_vtk_fibres};
use ecc_runtime::energies::{FIBRE_NAMES, fibre_by_name};
use ecc_runtime::fibre::{FibreDim, FibreEnergy};
use ecc_runtime::{Dim, Space};

use crate::body::Body;
use crate::error::SceneError;
use crate::spec::{FibreSpec, SceneFile};

fn invalid(key: &str, msg: impl Into<String>) -> SceneError {
    SceneError::invalid(format!("fibers.{key}"), msg)
}

/// A length-`D` vector from the scene.
fn vector<const D: usize>(key: &str, v: &[f64]) -> Result<[f64; D], SceneError> {
    if v.len() != D || !v.iter().all(|x| x.is_finite()) {
        return Err(invalid(
            key,
            format!("expected {D} finite numbers, got {v:?}"),
        ));
    }
    Ok(std::array::from_fn(|i| v[i]))
}

/// The energy with its parameters.
fn energy<const D: usize>(spec: &FibreSpec) -> Result<Arc<dyn FibreEnergy<D>>, SceneError> {
    let name = spec.energy.as_deref().unwrap_or("fibre-stvk");
    if name.ends_with(".psi") {
        return Err(invalid(
            "energy",
            format!(
                "`{name}`: fibre parts of .psi files are not supported by scenes yet; use one of {FIBRE_NAMES:?}"
            ),
        ));
    }
    let mut e = fibre_by_name::<D>(name).ok_or_else(|| {
        invalid(
            "energy",
            format!("unknown fibre energy `{name}` (known: {FIBRE_NAMES:?})"),
        )
    })?;
    for (k, v) in &spec.params {
        e.set_fibre_param(k, *v)
            .map_err(|err| invalid(&format!("params.{k}"), err.to_string()))?;
    }
    Ok(Arc::from(e))
}

/// Element centroids of a flat simplex list.
fn centroids<const D: usize>(rest: &[[f64; D]], el: &[usize]) -> Vec<[f64; D]> {
    el.chunks(D + 1)
        .map(|s| {
            std::array::from_fn(|i| s.iter().map(|&v| rest[v][i]).sum::<f64>() / (D + 1) as f64)
        })
        .collect()
}

/// The mesh file for a file field, after checking nothing reorders or turns elements.
fn mesh_file(file: &SceneFile, key: &str, ext: &str) -> Result<std::path::PathBuf, SceneError> {
    let m = &file.scene.mesh;
    let path = m
        .file
        .as_deref()
        .ok_or_else(|| invalid(key, "needs `mesh.file`"))?;
    if m.crop.is_some() || m.rotate.is_some() {
        return Err(invalid(
            key,
            "file fields cannot be combined with `mesh.crop` or `mesh.rotate`",
        ));
    }
    let path = file.resolve(path);
    if path.extension().and_then(|e| e.to_str()) != Some(ext) {
        return Err(invalid(
            key,
            format!("needs a `.{ext}` mesh file, got {}", path.display()),
        ));
    }
    Ok(path)
}

/// One direction per element from the spec.
fn directions<const D: usize>(
    spec: &FibreSpec,
    file: &SceneFile,
    body: &Body<D>,
) -> Result<Vec<[f64; D]>, SceneError> {
    let n = body.elements.len() / (D + 1);
    let sources = [
        spec.direction.is_some(),
        spec.field.is_some(),
        spec.references.is_some(),
        spec.around.is_some(),
        spec.curve.is_some(),
    ];
    if sources.iter().filter(|s| **s).count() != 1 {
        return Err(invalid(
            "direction",
            "give exactly one of direction, field, references, around, curve",
        ));
    }
    let generate = |g: FibreGenerator<D>, key: &str| {
        g.generate(&centroids(&body.rest, &body.elements))
            .map_err(|e| invalid(key, e.to_string()))
    };
    let dirs = if let Some(d) = &spec.direction {
        generate(
            FibreGenerator::Constant(vector("direction", d)?),
            "direction",
        )?
    } else if let Some(name) = &spec.field {
        let path = mesh_file(file, "field", "vtk")?;
        read_vtk_fibres::<D>(&path, &[name.as_str()])
            .map_err(|e| invalid("field", e.to_string()))?
    } else if let Some(table) = &spec.references {
        read_references(file, table)?
    } else if let Some(a) = &spec.around {
        let point = vector("around.point", &a.point)?;
        let axis = match (&a.axis, D) {
            (Some(ax), _) => vector("around.axis", ax)?,
            (None, 3) => return Err(invalid("around.axis", "needs an axis in 3D")),
            (None, _) => [0.0; D],
        };
        let g = match a.angle {
            Some(t) if t != 0.0 => FibreGenerator::Helix {
                point,
                axis,
                angle: t.to_radians(),
            },
            _ => FibreGenerator::Around { point, axis },
        };
        generate(g, "around")?
    } else {
        let pts = spec.curve.as_deref().unwrap_or_default();
        let pts = pts
            .iter()
            .map(|p| vector("curve", p))
            .collect::<Result<Vec<_>, _>>()?;
        generate(FibreGenerator::Curve(pts), "curve")?
    };
    check_directions(&dirs, n, "fibre directions")
        .map_err(|e| invalid("direction", e.to_string()))?;
    Ok(dirs)
}

/// Directions from the MEDIT references of `mesh.file`.
fn read_references<const D: usize>(
    file: &SceneFile,
    table: &std::collections::BTreeMap<String, Vec<f64>>,
) -> Result<Vec<[f64; D]>, SceneError> {
    let path = mesh_file(file, "references", "mesh")?;
    let text = read_text(&path).map_err(|e| invalid("references", e))?;
    let refs = ecc_mesh::io::fibres::parse_medit_references(&text)
        .map_err(|e| invalid("references", e.at(&path).to_string()))?;
    let mut t = Vec::new();
    for (k, v) in table {
        let r: i64 = k
            .parse()
            .map_err(|_| invalid("references", format!("`{k}` is not an integer reference")))?;
        t.push((r, vector(&format!("references.{k}"), v)?));
    }
    from_references(&refs, &t).map_err(|e| invalid("references", e.to_string()))
}

fn read_text(path: &Path) -> Result<String, String> {
    std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))
}

fn build<const D: usize>(
    spec: &FibreSpec,
    file: &SceneFile,
    body: &Body<D>,
) -> Result<Box<dyn Term<D>>, SceneError>
where
    Space<D>: FibreDim<D> + Dim<D>,
{
    let dirs = directions(spec, file, body)?;
    let term = Fibre::<dyn FibreEnergy<D>, D>::from_flat(
        energy::<D>(spec)?,
        &body.rest,
        &body.elements,
        &dirs,
    )
    .map_err(|e| SceneError::setup("the fibre term", e))?;
    Ok(Box::new(term))
}

/// The rest fibre direction of every element of `[fibers]` (for the picture),
/// if the scene has fibres: the same directions as the term's.
pub(crate) fn picture_directions<const D: usize>(
    file: &SceneFile,
    body: &Body<D>,
) -> Result<Option<Vec<[f64; D]>>, SceneError> {
    match &file.scene.fibers {
        Some(spec) => directions(spec, file, body).map(Some),
        None => Ok(None),
    }
}

/// The fibre term of `[fibers]`, if the scene has one.
pub fn fibre_term<const D: usize>(
    file: &SceneFile,
    body: &Body<D>,
) -> Result<Option<Box<dyn Term<D>>>, SceneError> {
    let Some(spec) = &file.scene.fibers else {
        return Ok(None);
    };
    let any_body: &dyn Any = body;
    let term: Box<dyn Any> = if let Some(b) = any_body.downcast_ref::<Body<2>>() {
        Box::new(build::<2>(spec, file, b)?)
    } else if let Some(b) = any_body.downcast_ref::<Body<3>>() {
        Box::new(build::<3>(spec, file, b)?)
    } else {
        return Err(invalid("direction", format!("unsupported dimension {D}")));
    };
    Ok(Some(*term.downcast::<Box<dyn Term<D>>>().expect("same D")))
}
