//! Greedy colouring of stencils for race-free parallel scatter.
//!
//! Two stencils *conflict* when they share a vertex that has a free DOF (only
//! free DOFs are written to the reduced gradient and Hessian; a shared fully
//! fixed vertex writes nothing). Stencils of one colour are pairwise
//! conflict-free, so within a colour every stencil writes its own gradient
//! entries and Hessian slots and the colour can be processed in parallel
//! without atomics. The colouring is computed once per mesh.
//!
//! Greedy first-fit in stencil order: stencil s takes the smallest colour not
//! used by an already-coloured stencil sharing an active vertex with it. The
//! colour count is at most 1 + max over stencils of the number of conflicting
//! stencils (≈ arity × vertex valence), typically 8–16 for triangle meshes and
//! 20–40 for tet meshes.

/// Stencils grouped by colour: colour `c` is `order[ptr[c]..ptr[c+1]]`
/// (stencil indices in increasing order within a colour).
#[derive(Clone, Debug, Default)]
pub(crate) struct Colouring {
    pub ptr: Vec<usize>,
    pub order: Vec<u32>,
}

impl Colouring {
    /// Number of colours.
    pub fn n_colours(&self) -> usize {
        self.ptr.len().saturating_sub(1)
    }

    /// The stencils of colour `c`.
    #[cfg(test)]
    pub fn colour(&self, c: usize) -> &[u32] {
        &self.order[self.ptr[c]..self.ptr[c + 1]]
    }
}

/// Colour `stencils` (flat, `arity` vertices each, indices < `n_vertices`,
/// already validated) so that no two stencils of a colour share an active vertex.
pub(crate) fn colour_stencils(
    n_vertices: usize,
    arity: usize,
    stencils: &[usize],
    active: &[bool],
) -> Colouring {
    let n = stencils.len() / arity;
    // vertex → incident stencils (CSR), active vertices only
    let mut vptr = vec![0usize; n_vertices + 1];
    for &v in stencils {
        if active[v] {
            vptr[v + 1] += 1;
        }
    }
    for v in 0..n_vertices {
        vptr[v + 1] += vptr[v];
    }
    let mut fill = vptr.clone();
    let mut inc = vec![0u32; vptr[n_vertices]];
    for (s, st) in stencils.chunks_exact(arity).enumerate() {
        for &v in st {
            if active[v] {
                inc[fill[v]] = s as u32;
                fill[v] += 1;
            }
        }
    }
    drop(fill);

    const NONE: u32 = u32::MAX;
    let mut colour = vec![NONE; n];
    // forbidden[c] == s+1 ⇔ colour c is used by a neighbour of stencil s
    let mut forbidden: Vec<usize> = Vec::new();
    let mut n_colours = 0usize;
    for (s, st) in stencils.chunks_exact(arity).enumerate() {
        for &v in st {
            if !active[v] {
                continue;
            }
            for &t in &inc[vptr[v]..vptr[v + 1]] {
                let c = colour[t as usize];
                if c != NONE {
                    forbidden[c as usize] = s + 1;
                }
            }
        }
        let c = (0..n_colours)
            .find(|&c| forbidden[c] != s + 1)
            .unwrap_or_else(|| {
                n_colours += 1;
                forbidden.push(0);
                n_colours - 1
            });
        colour[s] = c as u32;
    }

    let mut ptr = vec![0usize; n_colours + 1];
    for &c in &colour {
        ptr[c as usize + 1] += 1;
    }
    for c in 0..n_colours {
        ptr[c + 1] += ptr[c];
    }
    let mut fill = ptr.clone();
    let mut order = vec![0u32; n];
    for (s, &c) in colour.iter().enumerate() {
        order[fill[c as usize]] = s as u32;
        fill[c as usize] += 1;
    }
    Colouring { ptr, order }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(n_vertices: usize, arity: usize, stencils: &[usize], active: &[bool]) -> Colouring {
        let col = colour_stencils(n_vertices, arity, stencils, active);
        assert_eq!(col.order.len(), stencils.len() / arity);
        let mut seen = vec![false; stencils.len() / arity];
        for c in 0..col.n_colours() {
            let mut owner = vec![usize::MAX; n_vertices];
            for &s in col.colour(c) {
                assert!(!seen[s as usize]);
                seen[s as usize] = true;
                for &v in &stencils[s as usize * arity..(s as usize + 1) * arity] {
                    if active[v] {
                        assert_eq!(owner[v], usize::MAX, "colour {c} shares vertex {v}");
                        owner[v] = s as usize;
                    }
                }
            }
        }
        assert!(seen.iter().all(|&b| b));
        col
    }

    #[test]
    fn grid_triangles_get_a_valid_small_colouring() {
        // 10×10 quads split in two triangles
        let m = 11;
        let mut tris = Vec::new();
        for i in 0..10 {
            for j in 0..10 {
                let a = i * m + j;
                tris.extend_from_slice(&[a, a + 1, a + m + 1, a, a + m + 1, a + m]);
            }
        }
        let active = vec![true; m * m];
        let col = check(m * m, 3, &tris, &active);
        assert!(col.n_colours() <= 13, "{} colours", col.n_colours());
    }

    #[test]
    fn fixed_vertices_do_not_conflict() {
        // a fan of 5 triangles around vertex 0: all conflict unless 0 is fixed
        let tris = [0, 1, 2, 0, 3, 4, 0, 5, 6, 0, 7, 8, 0, 9, 10];
        let mut active = vec![true; 11];
        assert_eq!(check(11, 3, &tris, &active).n_colours(), 5);
        active[0] = false;
        assert_eq!(check(11, 3, &tris, &active).n_colours(), 1);
    }
}
