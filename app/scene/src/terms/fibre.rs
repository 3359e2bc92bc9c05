//! The `[fibers]` term: directions from the scene or the mesh file, a
//! fibre energy from the [`EnergySource`], and `ecc_fem::Fibre` over the
//! body's elements.
//!
//! The fibre energy ψ(I4, I5) is exactly one of:
//!
//! * `[fibers] energy = "NAME"` (default `fibre-stvk`): a named fibre energy
//!   of the provider (the `ecc` CLI and the Python package: the generated
//!   library, `energies/psi/fibre_*.psi`; [`crate::RuntimeEnergies`]: the
//!   runtime's hand-written ones), with `[fibers] params`;
//! * `[fibers] energy = "x.psi"`: the fibre part of that file, with
//!   `[fibers] params` (the file's parameters). A file whose isotropic part
//!   is not 0 is refused (the provider's error names the fix: give it as
//!   `[energy] psi`), since taking ψ alone would drop Ψ_iso;
//! * `[energy] psi = "x.psi"` declaring `fiber a`: its fibre part, with
//!   `[energy] params` (shared by both parts, as in the file), while its
//!   isotropic part is the body's energy. `[fibers]` is then required (it
//!   gives the directions), and `[fibers] energy` / `[fibers] params` are
//!   refused as conflicting.
//!
//! A parameterisation takes no fibre term (`[fibers]`, or a `.psi` with a
//! fibre part, is refused there).
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
use ecc_runtime::fibre::{FibreDim, FibreEnergy};
use ecc_runtime::{Dim, Space};

use crate::body::Body;
use crate::energy::{EnergyError, EnergyRequest, EnergySource};
use crate::error::SceneError;
use crate::spec::{FibreSpec, SceneFile};

/// The fibre energy of a `[fibers]` table without `energy`.
pub const DEFAULT_FIBRE: &str = "fibre-stvk";

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

/// The scene's fibre energy (see the module docs), given the fibre part of
/// the body's energy (`body_fibre`, from [`EnergySource::body2`]/`body3`):
/// `None` when the scene has no fibre term.
pub fn fibre_energy<const D: usize>(
    file: &SceneFile,
    source: &dyn EnergySource,
    body_fibre: Option<Box<dyn FibreEnergy<D>>>,
) -> Result<Option<Arc<dyn FibreEnergy<D>>>, SceneError> {
    let psi = file.scene.energy.psi.as_deref().unwrap_or_default();
    match (&file.scene.fibers, body_fibre) {
        (None, None) => Ok(None),
        (None, Some(_)) => Err(SceneError::invalid(
            "energy.psi",
            format!(
                "`{psi}` has a fibre part ψ(I4, I5) (`fiber`), which needs one direction per \
                 element: add a `[fibers]` section with one of direction, field, references, \
                 around, curve (its energy and parameters are the file's)"
            ),
        )),
        (Some(spec), Some(f)) => {
            for (key, given) in [
                ("energy", spec.energy.is_some()),
                ("params", !spec.params.is_empty()),
            ] {
                if given {
                    return Err(invalid(
                        key,
                        format!(
                            "conflicts with energy.psi: the fibre part of `{psi}` is the fibre \
                             energy, with the file's parameters set in `[energy] params` (shared \
                             by both parts); remove fibers.{key}"
                        ),
                    ));
                }
            }
            Ok(Some(Arc::from(f)))
        }
        (Some(spec), None) => provided::<D>(file, source, spec).map(Some),
    }
}

/// `[fibers] energy` (a name or a `.psi` path) with `[fibers] params`, from the provider.
fn provided<const D: usize>(
    file: &SceneFile,
    source: &dyn EnergySource,
    spec: &FibreSpec,
) -> Result<Arc<dyn FibreEnergy<D>>, SceneError> {
    let written = spec.energy.as_deref().unwrap_or(DEFAULT_FIBRE);
    let path = written.ends_with(".psi").then(|| file.resolve(written));
    let params: Vec<(String, f64)> = spec.params.iter().map(|(k, v)| (k.clone(), *v)).collect();
    let req = EnergyRequest {
        name: path.is_none().then_some(written),
        psi: path.as_deref(),
        params: &params,
    };
    let made: Box<dyn Any> = match D {
        2 => Box::new(source.fibre2(&req)),
        3 => Box::new(source.fibre3(&req)),
        _ => return Err(invalid("energy", format!("unsupported dimension {D}"))),
    };
    let made = *made
        .downcast::<Result<Box<dyn FibreEnergy<D>>, EnergyError>>()
        .expect("same D");
    made.map(Arc::from).map_err(fibre_error)
}

/// A provider's error at the `[fibers]` key at fault.
fn fibre_error(e: EnergyError) -> SceneError {
    match e {
        EnergyError::Param(m) => invalid("params", m),
        EnergyError::UnknownName { name, known } => {
            let refs: Vec<&str> = known.iter().map(String::as_str).collect();
            let hint = crate::spec::suggest_name(&name, &refs)
                .map(|s| format!("; did you mean `{s}`?"))
                .unwrap_or_default();
            invalid(
                "energy",
                format!(
                    "unknown fibre energy `{name}` (known: {}, or a .psi file with a fibre part){hint}",
                    known.join(", ")
                ),
            )
        }
        other => invalid("energy", other.to_string()),
    }
}

/// A parameterisation takes no fibre term: refuse `[fibers]` and a body
/// energy with a fibre part (`has_fibre_part`) instead of ignoring them.
pub fn refuse_in_parameterisation(
    file: &SceneFile,
    has_fibre_part: bool,
) -> Result<(), SceneError> {
    if file.scene.fibers.is_some() {
        return Err(SceneError::invalid(
            "fibers",
            "a parameterisation takes no fibre term (remove [fibers] or effects.parameterize)",
        ));
    }
    if has_fibre_part {
        let psi = file.scene.energy.psi.as_deref().unwrap_or_default();
        return Err(SceneError::invalid(
            "energy.psi",
            format!(
                "`{psi}` has a fibre part ψ(I4, I5) (`fiber`): a parameterisation takes no fibre \
                 term (use an isotropic energy)"
            ),
        ));
    }
    Ok(())
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
    energy: Arc<dyn FibreEnergy<D>>,
) -> Result<Box<dyn Term<D>>, SceneError>
where
    Space<D>: FibreDim<D> + Dim<D>,
{
    let dirs = directions(spec, file, body)?;
    let term = Fibre::<dyn FibreEnergy<D>, D>::from_flat(energy, &body.rest, &body.elements, &dirs)
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

/// The fibre term: `energy` ([`fibre_energy`]) on the `[fibers]`
/// directions; `None` without a fibre energy.
pub fn fibre_term<const D: usize>(
    file: &SceneFile,
    body: &Body<D>,
    energy: Option<Arc<dyn FibreEnergy<D>>>,
) -> Result<Option<Box<dyn Term<D>>>, SceneError> {
    let Some(energy) = energy else {
        return Ok(None);
    };
    let Some(spec) = &file.scene.fibers else {
        return Err(SceneError::invalid(
            "fibers",
            "a fibre energy needs a [fibers] section",
        ));
    };
    let any_body: &dyn Any = body;
    let any_energy: Box<dyn Any> = Box::new(energy);
    let term: Box<dyn Any> = if let Some(b) = any_body.downcast_ref::<Body<2>>() {
        let e = any_energy
            .downcast::<Arc<dyn FibreEnergy<2>>>()
            .expect("same D");
        Box::new(build::<2>(spec, file, b, *e)?)
    } else if let Some(b) = any_body.downcast_ref::<Body<3>>() {
        let e = any_energy
            .downcast::<Arc<dyn FibreEnergy<3>>>()
            .expect("same D");
        Box::new(build::<3>(spec, file, b, *e)?)
    } else {
        return Err(invalid("direction", format!("unsupported dimension {D}")));
    };
    Ok(Some(*term.downcast::<Box<dyn Term<D>>>().expect("same D")))
}
