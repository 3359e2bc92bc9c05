//! Tutte / Floater embedding: a bijective initial map of a disk-topology
//! triangle mesh into the unit disk, the standard starting point of
//! injective parameterisation (the barrier energies need a flip-free start).
//!
//! **Boundary.** The single boundary loop (in the direction of its
//! triangles' edges) is mapped to the unit circle counter-clockwise by arc
//! length: with `s_i` the 3D length of the loop up to vertex `i` and `S`
//! the total, `u_i = (cos 2π s_i/S, sin 2π s_i/S)`.
//!
//! **Interior.** Each interior vertex is the weighted average of its
//! neighbours, `Σ_j w_ij (u_i − u_j) = 0`, a sparse linear system in the
//! interior unknowns (two right-hand sides: u and v). Symmetric weights
//! (uniform, cotangent) are solved with a sparse Cholesky factorisation,
//! mean-value weights with a sparse LU (faer).
//!
//! **Bijectivity.** With positive weights and a convex boundary polygon the
//! map is a bijection (Tutte 1963, Floater 2003): uniform and mean-value
//! weights always qualify; cotangent weights are negative across edges
//! whose opposite angles sum to more than π, and the map may then fold.
//! Because the boundary follows the triangles' orientation, a consistently
//! oriented mesh maps to positively oriented (counter-clockwise) triangles.
//! [`tutte_embedding`] insists on that (every signed area `> 0`);
//! [`tutte_embedding_report`] returns the map with the list of flipped
//! triangles instead.

mod linear;
mod weights;

use crate::error::{TutteError, ValidationError};
use crate::geometry::{norm, signed_area_uv, sub};
use crate::topology::{boundary_loops, components};
use crate::types::{TriMesh, TutteWeights};
use crate::validate::{check_all_finite, check_indices, referenced};

/// The result of [`tutte_embedding_report`].
#[derive(Clone, Debug, PartialEq)]
pub struct TutteEmbedding {
    /// One uv per vertex; boundary vertices lie on the unit circle.
    pub uv: Vec<[f64; 2]>,
    /// The boundary loop (vertex ids, counter-clockwise in uv).
    pub boundary: Vec<usize>,
    /// Triangles with signed uv area `≤ 0` (empty for a bijection).
    pub flipped: Vec<usize>,
}

/// Tutte embedding of a disk-topology mesh that must be a bijection: an
/// embedding with flipped triangles is returned inside
/// [`TutteError::Flipped`] (nothing is lost). See the module docs.
pub fn tutte_embedding(mesh: &TriMesh, weights: TutteWeights) -> Result<Vec<[f64; 2]>, TutteError> {
    bijective(report(mesh, weights, no_order)?)
}

/// [`tutte_embedding`] factorising the interior system (uniform or
/// cotangent weights) in a fill-reducing `order` of the mesh's vertices
/// computed already (`order[new] = old`, e.g.
/// [`crate::dissection::mesh_dissection`], which the Newton solver's
/// `geometric` ordering can share) restricted to the interior vertices,
/// instead of dissecting the interior graph again. An `order` that is not a
/// permutation of the vertices is not used (the interior is dissected as by
/// [`tutte_embedding`]); mean-value weights (LU) do not use it.
///
/// `order` is asked for only once the mesh is checked and the system
/// assembled (and not at all for mean-value weights), so a caller can
/// compute it meanwhile on another thread; `None` dissects the interior.
pub fn tutte_embedding_in_order<O: AsRef<[usize]>>(
    mesh: &TriMesh,
    weights: TutteWeights,
    order: impl FnOnce() -> Option<O>,
) -> Result<Vec<[f64; 2]>, TutteError> {
    bijective(report(mesh, weights, order)?)
}

/// No vertex order given: the interior is dissected.
fn no_order() -> Option<&'static [usize]> {
    None
}

/// The map of `e`, or [`TutteError::Flipped`] (holding it) when it flips
/// a triangle.
fn bijective(e: TutteEmbedding) -> Result<Vec<[f64; 2]>, TutteError> {
    match e.flipped.first() {
        None => Ok(e.uv),
        Some(&first) => Err(TutteError::Flipped {
            count: e.flipped.len(),
            first,
            uv: e.uv,
        }),
    }
}

/// Tutte embedding with the list of flipped triangles (see the module docs).
///
/// Requirements (else a [`TutteError`]): at least one triangle, indices in
/// range, no repeated vertex in a triangle, finite coordinates, every
/// vertex used, one connected component, manifold edges along a single
/// boundary loop of non-zero length, finite weights.
pub fn tutte_embedding_report(
    mesh: &TriMesh,
    weights: TutteWeights,
) -> Result<TutteEmbedding, TutteError> {
    report(mesh, weights, no_order)
}

/// [`tutte_embedding_report`], in the vertex `order` when given
/// ([`tutte_embedding_in_order`]).
fn report<O: AsRef<[usize]>>(
    mesh: &TriMesh,
    weights: TutteWeights,
    order: impl FnOnce() -> Option<O>,
) -> Result<TutteEmbedding, TutteError> {
    let tris = &mesh.triangles;
    let pos = &mesh.positions;
    let n = pos.len();
    if tris.is_empty() {
        return Err(ValidationError::NoElements.into());
    }
    check_indices(tris, n)?;
    if let Some(vertex) = referenced(tris, n).iter().position(|u| !u) {
        return Err(TutteError::UnreferencedVertex { vertex });
    }
    check_all_finite(pos)?;
    let count = components(tris).count;
    if count > 1 {
        return Err(TutteError::Disconnected { count });
    }
    let loops = boundary_loops(tris)?;
    if loops.len() != 1 {
        return Err(TutteError::NotADisk { loops: loops.len() });
    }
    let boundary = loops.into_iter().next().unwrap_or_default();

    let mut uv = vec![[0.0; 2]; n];
    place_on_circle(pos, &boundary, &mut uv)?;

    // Interior numbering.
    let mut interior = vec![usize::MAX; n];
    let mut is_boundary = vec![false; n];
    for &v in &boundary {
        is_boundary[v] = true;
    }
    let mut m = 0;
    for v in 0..n {
        if !is_boundary[v] {
            interior[v] = m;
            m += 1;
        }
    }
    if m > 0 {
        solve_interior(mesh, weights, (&interior, order), &mut uv, m)?;
    }
    let flipped = tris
        .iter()
        .enumerate()
        .filter(|(_, t)| signed_area_uv(uv[t[0]], uv[t[1]], uv[t[2]]) <= 0.0)
        .map(|(f, _)| f)
        .collect();
    Ok(TutteEmbedding {
        uv,
        boundary,
        flipped,
    })
}

/// Boundary to the unit circle by arc length.
fn place_on_circle(
    pos: &[[f64; 3]],
    boundary: &[usize],
    uv: &mut [[f64; 2]],
) -> Result<(), TutteError> {
    let nb = boundary.len();
    let mut s = Vec::with_capacity(nb);
    let mut total = 0.0;
    for i in 0..nb {
        s.push(total);
        total += norm(sub(pos[boundary[(i + 1) % nb]], pos[boundary[i]]));
    }
    if !(total > 0.0 && total.is_finite()) {
        return Err(TutteError::DegenerateBoundary);
    }
    for (&v, &si) in boundary.iter().zip(&s) {
        let a = std::f64::consts::TAU * si / total;
        uv[v] = [a.cos(), a.sin()];
    }
    Ok(())
}

/// Assemble `L_II u_I = −L_IB u_B` and solve for both coordinates
/// (see [`linear`]); `interior[v]` is v's unknown (`usize::MAX` on the
/// boundary), `order` the vertex order to factorise in, if any (asked for
/// after the assembly).
fn solve_interior<O: AsRef<[usize]>>(
    mesh: &TriMesh,
    weights: TutteWeights,
    (interior, order): (&[usize], impl FnOnce() -> Option<O>),
    uv: &mut [[f64; 2]],
    m: usize,
) -> Result<(), TutteError> {
    let each = |f: usize, out: &mut Vec<weights::Contribution>| {
        weights::triangle_contributions(weights, mesh.triangles[f], &mesh.positions, out)
            .map_err(|edge| TutteError::BadWeight { weights, edge })
    };
    let mut sys = linear::assemble(&mesh.triangles, &each, interior, uv, m)?;
    let solved = if weights.is_symmetric() {
        let perm = match order().and_then(|o| linear::interior_order(o.as_ref(), interior, m)) {
            Some(perm) => perm,
            None => {
                let mut pos = vec![[0.0; 3]; m];
                for (v, &r) in interior.iter().enumerate() {
                    if r != usize::MAX {
                        pos[r] = mesh.positions[v];
                    }
                }
                linear::nested_dissection(&sys.a, &pos)
            }
        };
        // not positive definite (cotangent): use LU
        linear::solve_cholesky(&mut sys, &perm)?
    } else {
        false
    };
    if !solved {
        linear::solve_lu(&mut sys)?;
    }
    let rhs = &sys.rhs;
    for (v, &r) in interior.iter().enumerate() {
        if r != usize::MAX {
            let (x, y) = (rhs[(r, 0)], rhs[(r, 1)]);
            if !(x.is_finite() && y.is_finite()) {
                return Err(TutteError::Solve {
                    message: format!("the solution at vertex {v} is not finite (singular system)"),
                });
            }
            uv[v] = [x, y];
        }
    }
    Ok(())
}
