//! Mesh validation: reasons and element ids for everything a solver or a
//! parameterisation cannot work with.
//!
//! Always checked, in this order (the first problem found is returned):
//! 1. at least one element ([`ValidationError::NoElements`]);
//! 2. uvs, if any: one per vertex, finite for referenced vertices;
//! 3. indices in range, no vertex repeated inside an element;
//! 4. no duplicate element (same vertex set);
//! 5. finite coordinates of referenced vertices; `z = 0` for planar meshes;
//! 6. rest measures: degenerate if `|m| ≤ tol · L^d` (`L` the bbox
//!    diagonal of the referenced vertices, `d` = 2 for triangles, 3 for
//!    tets, `tol` = [`ValidationOptions::rest_measure_tolerance`]);
//!    inverted if the signed area (planar meshes) or the signed volume
//!    (tets) is negative. Surfaces in 3D have no sign, only area.
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
//! **Why `tol = 1e-12` by default.** Round-off in an area computed from
//! coordinates of size `L` is about `1e-16 · L²`, so anything below
//! `1e-12 · L^d` carries no usable rest shape (its inverse rest matrix
//! would amplify noise by `≥ 1e12`). Real meshes' smallest elements sit
//! above it: camelhead.off's 4 folded faces around vertex 901 have area
//! `~4e-8` with `L ≈ 1.25` (`2.6e-8 · L²`): tiny, nearly flat, but
//! genuine triangles, so they must validate; hand.mesh's smallest sliver
//! has volume `4.5e-10` with `L ≈ 2.03` (`5.4e-11 · L³`). Raise the
//! tolerance to reject slivers a solver should not see.

mod common;
mod manifold;

use crate::error::ValidationError;
use crate::geometry::{signed_area_2d, tet_signed_volume, triangle_area};
use crate::topology::{components, sorted_sides};
use crate::types::{TetMesh, TriMesh, Validated, ValidationOptions};
use common::*;

pub(crate) use common::check_indices;

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
    check_indices(&mesh.triangles, n)?;
    check_duplicates(&mesh.triangles)?;
    let used = referenced(&mesh.triangles, n);
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
    let l = reference_length(&mesh.positions, &used);
    let tol = opts.rest_measure_tolerance * l * l;
    let pos = &mesh.positions;
    let measures = mesh.triangles.iter().map(|t| {
        let (a, b, c) = (pos[t[0]], pos[t[1]], pos[t[2]]);
        if planar {
            signed_area_2d(a, b, c)
        } else {
            triangle_area(a, b, c)
        }
    });
    check_measures(measures, tol, planar, 2)?;
    if opts.require_manifold || opts.require_oriented {
        let sides = sorted_sides(&mesh.triangles);
        manifold::check_edges(&sides, opts.require_manifold, opts.require_oriented)?;
    }
    if opts.require_manifold {
        manifold::check_fans(&mesh.triangles, n)?;
    }
    let mut warnings = Vec::new();
    check_components(&mesh.triangles, opts, &mut warnings)?;
    check_unreferenced(&used, opts.drop_unreferenced)?;
    let (vertex_map, kept, warning) = compaction(&used);
    warnings.extend(warning);
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
    check_indices(&mesh.tets, n)?;
    check_duplicates(&mesh.tets)?;
    let used = referenced(&mesh.tets, n);
    check_finite(&mesh.positions, &used)?;
    let l = reference_length(&mesh.positions, &used);
    let tol = opts.rest_measure_tolerance * l * l * l;
    let pos = &mesh.positions;
    let measures = mesh
        .tets
        .iter()
        .map(|t| tet_signed_volume(pos[t[0]], pos[t[1]], pos[t[2]], pos[t[3]]));
    check_measures(measures, tol, true, 3)?;
    if opts.require_manifold {
        manifold::check_tet_faces(&mesh.tets)?;
    }
    let mut warnings = Vec::new();
    check_components(&mesh.tets, opts, &mut warnings)?;
    check_unreferenced(&used, opts.drop_unreferenced)?;
    let (vertex_map, kept, warning) = compaction(&used);
    warnings.extend(warning);
    let positions = kept.iter().map(|&v| mesh.positions[v]).collect();
    let tets = renumber(mesh.tets, &vertex_map);
    Ok(Validated {
        mesh: TetMesh { positions, tets },
        vertex_map,
        warnings,
    })
}
