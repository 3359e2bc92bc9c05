//! Mesh validation: reasons and element ids for everything a solver or a
//! parameterisation cannot work with.
//!
//! Always checked, in this order (the first problem found is returned;
//! once the indices are in range, check 4, checks 5–6 and the topology
//! checks run side by side, and the first problem in this order is still
//! the one reported):
//! 1. at least one element ([`ValidationError::NoElements`]);
//! 2. uvs, if any: one per vertex, finite for referenced vertices;
//! 3. indices in range, no vertex repeated inside an element;
//! 4. no duplicate element (same vertex set);
//! 5. finite coordinates of referenced vertices; `z = 0` for planar meshes;
//! 6. rest measures, each element against its own longest edge `L`
//!    (scale-invariant, the same rule as the element library
//!    `ecc_runtime::Rest`): degenerate if the measure `m` or `L` is not
//!    finite or `|det Dm| = den·|m| ≤ 1e-12 · L^d` ([`crate::DEGENERATE_REL_TOL`];
//!    `d` = 2, `den` = 2 for triangles, `d` = 3, `den` = 6 for tets);
//!    inverted if the signed area (planar meshes) or the signed volume
//!    (tets) is negative. Surfaces in 3D have no sign, only area. The
//!    quality `q = |m| / L^d` (√3/4 ≈ 0.43 for an equilateral triangle,
//!    1/(6√2) ≈ 0.118 for a regular tet) below
//!    [`ValidationOptions::min_quality`] is refused
//!    ([`ValidationError::LowQualityElements`], ids named); below
//!    [`ValidationOptions::sliver_quality`] it is a warning naming the
//!    elements.
//!
//! On request ([`ValidationOptions`]): manifoldness, consistent
//! orientation, a single connected component. Several components are
//! otherwise reported as a warning.
//!
//! Finally vertices that no element uses are refused
//! ([`ValidationError::UnreferencedVertices`]) or, with
//! [`ValidationOptions::drop_unreferenced`], dropped (with a warning) and
//! the indices renumbered; [`Validated::vertex_map`] keeps old → new ids.
//!
//! **Why per element, and why `1e-12`.** Round-off in `det Dm` computed
//! from edges of length `≤ L` is about `1e-16 · L^d`, so below
//! `1e-12 · L^d` an element carries no usable rest shape (its `Dm⁻¹` would
//! amplify noise by `≥ 1e12`). Measuring against the element's own edges
//! (not the whole mesh's bounding box) makes the rule independent of the
//! rest of the mesh: a disk surface whose smallest triangle has area
//! `5.3e-12` but quality `9e-6` is a genuine triangle and validates (with
//! a sliver warning), as the element library and the solvers accept it.

mod common;
mod manifold;

use crate::error::ValidationError;
use crate::geometry::{signed_area_2d, tet_signed_volume, triangle_area};
use crate::topology::{components, sorted_sides};
use crate::types::{TetMesh, TriMesh, Validated, ValidationOptions};
use common::*;

pub(crate) use common::{check_all_finite, check_indices, referenced};

fn check_components<const K: usize>(
    elements: &[[usize; K]],
    opts: &ValidationOptions,
    warnings: &mut Vec<String>,
) -> Result<(), ValidationError> {
    let count = components(elements).count;
    if count > 1 {
        if opts.require_single_component {
            return Err(ValidationError::MultipleComponents { count });
        }
        warnings.push(format!("the mesh has {count} connected components"));
    }
    Ok(())
}

/// The rest-measure rule of `opts` for elements of dimension `dimension`.
fn rule(dimension: usize, signed: bool, opts: &ValidationOptions) -> MeasureRule {
    MeasureRule {
        dimension,
        den: if dimension == 2 { 2.0 } else { 6.0 },
        signed,
        min_quality: opts.min_quality,
        sliver_quality: opts.sliver_quality,
    }
}

/// Checks 5–6 of a triangle mesh: which vertices are used, finite
/// coordinates and uvs where used, `z = 0` for planar meshes, the rest
/// areas; with the warnings of the last.
fn tri_geometry(
    mesh: &TriMesh,
    planar: bool,
    opts: &ValidationOptions,
) -> Result<(Vec<bool>, Vec<String>), ValidationError> {
    let used = referenced(&mesh.triangles, mesh.positions.len());
    check_finite(&mesh.positions, &used)?;
    if let Some(uvs) = &mesh.uvs
        && let Some((vertex, uv)) = uvs
            .iter()
            .enumerate()
            .find(|(v, uv)| used[*v] && !(uv[0].is_finite() && uv[1].is_finite()))
    {
        return Err(ValidationError::NonFiniteUv { vertex, uv: *uv });
    }
    if planar
        && let Some((vertex, p)) = mesh
            .positions
            .iter()
            .enumerate()
            .find(|(v, p)| used[*v] && p[2] != 0.0)
    {
        return Err(ValidationError::NotPlanar { vertex, z: p[2] });
    }
    let pos = &mesh.positions;
    let measures = mesh.triangles.iter().map(|t| {
        let (a, b, c) = (pos[t[0]], pos[t[1]], pos[t[2]]);
        let m = if planar {
            signed_area_2d(a, b, c)
        } else {
            triangle_area(a, b, c)
        };
        (m, longest_edge(pos, t))
    });
    let mut warnings = Vec::new();
    check_measures(measures, &rule(2, planar, opts), &mut warnings)?;
    Ok((used, warnings))
}

/// The requested manifoldness and orientation of a triangle mesh, then
/// its components; with the components' warning.
fn tri_topology(
    tris: &[[usize; 3]],
    n: usize,
    opts: &ValidationOptions,
) -> Result<Vec<String>, ValidationError> {
    if opts.require_manifold || opts.require_oriented {
        let sides = sorted_sides(tris);
        manifold::check_edges(&sides, opts.require_manifold, opts.require_oriented)?;
    }
    if opts.require_manifold {
        manifold::check_fans(tris, n)?;
    }
    let mut warnings = Vec::new();
    check_components(tris, opts, &mut warnings)?;
    Ok(warnings)
}

/// Validate a triangle mesh: planar (`z = 0`, signed areas must be
/// positive) or a surface in 3D (areas must be non-degenerate). See the
/// module docs for the checks and their order.
pub fn validate_tri(
    mesh: TriMesh,
    planar: bool,
    opts: &ValidationOptions,
) -> Result<Validated<TriMesh>, ValidationError> {
    let n = mesh.positions.len();
    if mesh.triangles.is_empty() {
        return Err(ValidationError::NoElements);
    }
    if let Some(uvs) = &mesh.uvs
        && uvs.len() != n
    {
        return Err(ValidationError::UvCountMismatch {
            uvs: uvs.len(),
            vertices: n,
        });
    }
    let Checked {
        vertex_map,
        kept,
        warnings,
    } = checked(
        &mesh.triangles,
        n,
        opts,
        || tri_geometry(&mesh, planar, opts),
        || tri_topology(&mesh.triangles, n, opts),
    )?;
    let positions = kept.iter().map(|&v| mesh.positions[v]).collect();
    let uvs = mesh.uvs.map(|uvs| kept.iter().map(|&v| uvs[v]).collect());
    let triangles = renumber(mesh.triangles, &vertex_map);
    Ok(Validated {
        mesh: TriMesh {
            positions,
            triangles,
            uvs,
        },
        vertex_map,
        warnings,
    })
}

/// The module docs' checks from 3 on, for the elements of a mesh with `n`
/// vertices: indices in range (check 3); then, independent once they are,
/// check 4, the mesh's `geometry` (checks 5–6: the used vertices, with
/// their warnings) and its `topology` (the requested manifoldness, the
/// components) side by side on rayon's threads, the first problem in the
/// docs' order reported; finally the unreferenced vertices. Returns the
/// compaction and every warning in order.
fn checked<const K: usize>(
    elements: &[[usize; K]],
    n: usize,
    opts: &ValidationOptions,
    geometry: impl FnOnce() -> Result<(Vec<bool>, Vec<String>), ValidationError> + Send,
    topology: impl FnOnce() -> Result<Vec<String>, ValidationError> + Send,
) -> Result<Checked, ValidationError> {
    check_indices(elements, n)?;
    let (duplicates, (geometry, topology)) = rayon::join(
        || check_duplicates(elements),
        || rayon::join(geometry, topology),
    );
    duplicates?;
    let (used, mut warnings) = geometry?;
    warnings.extend(topology?);
    check_unreferenced(&used, opts.drop_unreferenced)?;
    let (vertex_map, kept, warning) = compaction(&used);
    warnings.extend(warning);
    Ok(Checked {
        vertex_map,
        kept,
        warnings,
    })
}

/// What [`checked`] returns: the compaction's old → new vertex map and the
/// kept vertices (old ids, in order), and the warnings.
struct Checked {
    vertex_map: Vec<Option<usize>>,
    kept: Vec<usize>,
    warnings: Vec<String>,
}

/// Checks 5–6 of a tet mesh: which vertices are used, finite coordinates
/// where used, the signed rest volumes; with the warnings of the last.
fn tet_geometry(
    mesh: &TetMesh,
    opts: &ValidationOptions,
) -> Result<(Vec<bool>, Vec<String>), ValidationError> {
    let used = referenced(&mesh.tets, mesh.positions.len());
    check_finite(&mesh.positions, &used)?;
    let pos = &mesh.positions;
    let measures = mesh.tets.iter().map(|t| {
        let m = tet_signed_volume(pos[t[0]], pos[t[1]], pos[t[2]], pos[t[3]]);
        (m, longest_edge(pos, t))
    });
    let mut warnings = Vec::new();
    check_measures(measures, &rule(3, true, opts), &mut warnings)?;
    Ok((used, warnings))
}

/// The requested manifoldness of a tet mesh, then its components; with
/// the components' warning.
fn tet_topology(
    tets: &[[usize; 4]],
    opts: &ValidationOptions,
) -> Result<Vec<String>, ValidationError> {
    if opts.require_manifold {
        manifold::check_tet_faces(tets)?;
    }
    let mut warnings = Vec::new();
    check_components(tets, opts, &mut warnings)?;
    Ok(warnings)
}

/// Validate a tet mesh (signed volumes must be positive). See the module
/// docs for the checks and their order.
pub fn validate_tet(
    mesh: TetMesh,
    opts: &ValidationOptions,
) -> Result<Validated<TetMesh>, ValidationError> {
    let n = mesh.positions.len();
    if mesh.tets.is_empty() {
        return Err(ValidationError::NoElements);
    }
    let Checked {
        vertex_map,
        kept,
        warnings,
    } = checked(
        &mesh.tets,
        n,
        opts,
        || tet_geometry(&mesh, opts),
        || tet_topology(&mesh.tets, opts),
    )?;
    let positions = kept.iter().map(|&v| mesh.positions[v]).collect();
    let tets = renumber(mesh.tets, &vertex_map);
    Ok(Validated {
        mesh: TetMesh { positions, tets },
        vertex_map,
        warnings,
    })
}
