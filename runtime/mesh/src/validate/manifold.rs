//! Manifoldness and orientation of triangle meshes, and face manifoldness
//! of tet meshes.

use crate::error::ValidationError;
use crate::topology::{Side, TET_FACES, VertexTriangles, sort_by_vertex};

/// Edges with more than two triangles, and (when `oriented`) interior
/// edges traversed twice in the same direction.
pub(crate) fn check_edges(
    sides: &[Side],
    manifold: bool,
    oriented: bool,
) -> Result<(), ValidationError> {
    for group in sides.chunk_by(|a, b| a.key == b.key) {
        if manifold && group.len() > 2 {
            return Err(ValidationError::NonManifoldEdge {
                edge: group[0].key,
                faces: group.iter().map(|s| s.face).collect(),
            });
        }
        if oriented {
            for (i, a) in group.iter().enumerate() {
                if let Some(b) = group[i + 1..].iter().find(|b| b.from == a.from) {
                    return Err(ValidationError::InconsistentOrientation {
                        edge: [a.from, a.to],
                        faces: [a.face, b.face],
                    });
                }
            }
        }
    }
    Ok(())
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Every vertex's triangles form a single fan: the link edges `{a, b}` of
/// the triangles `(v, a, b)` around `v` form one connected graph. (With
/// manifold edges this also rules out boundary vertices with more than
/// two boundary edges.)
pub(crate) fn check_fans(tris: &[[usize; 3]], vertex_count: usize) -> Result<(), ValidationError> {
    let incident = VertexTriangles::of(tris, vertex_count)?;
    let mut nbrs: Vec<usize> = Vec::new();
    let mut parent: Vec<usize> = Vec::new();
    for v in 0..vertex_count {
        let faces = incident.around(v);
        if faces.len() < 2 {
            continue;
        }
        let link = |f: usize| {
            let t = tris[f];
            let k = t.iter().position(|&x| x == v).unwrap_or(0);
            (t[(k + 1) % 3], t[(k + 2) % 3])
        };
        nbrs.clear();
        for &f in faces {
            let (a, b) = link(f);
            nbrs.push(a);
            nbrs.push(b);
        }
        nbrs.sort_unstable();
        nbrs.dedup();
        parent.clear();
        parent.extend(0..nbrs.len());
        let local = |x: usize| nbrs.binary_search(&x).unwrap_or(0);
        for &f in faces {
            let (a, b) = link(f);
            let (ra, rb) = (find(&mut parent, local(a)), find(&mut parent, local(b)));
            parent[ra.max(rb)] = ra.min(rb);
        }
        let fans = (0..nbrs.len())
            .filter(|&i| find(&mut parent, i) == i)
            .count();
        if fans > 1 {
            return Err(ValidationError::NonManifoldVertex {
                vertex: v,
                reason: format!(
                    "its {} triangles form {fans} separate fans (pinched vertex)",
                    faces.len()
                ),
            });
        }
    }
    Ok(())
}

/// No triangular face shared by more than two tets.
pub(crate) fn check_tet_faces(tets: &[[usize; 4]]) -> Result<(), ValidationError> {
    let mut faces: Vec<([usize; 3], usize)> = Vec::with_capacity(tets.len() * 4);
    for (t, tet) in tets.iter().enumerate() {
        for f in TET_FACES {
            let mut key = f.map(|k| tet[k]);
            key.sort_unstable();
            faces.push((key, t));
        }
    }
    sort_by_vertex(&mut faces, |f| f.0[0], |f| (f.0[1], f.0[2], f.1));
    for group in faces.chunk_by(|a, b| a.0 == b.0) {
        if group.len() > 2 {
            return Err(ValidationError::NonManifoldFace {
                face: group[0].0,
                tets: group.iter().map(|g| g.1).collect(),
            });
        }
    }
    Ok(())
}
