//! Degrees of freedom and their elimination.
//!
//! Positions are stored vertex-major, `x[v][c]`, so the flat DOF index of
//! coordinate `c` of vertex `v` is `v·D + c`. Dirichlet (fixed) DOFs are
//! *eliminated*: the linear system only has one unknown per free DOF, numbered
//! in increasing DOF order (so unknowns of one vertex are consecutive and the
//! unknown order follows the vertex order, which keeps the pattern build
//! simple). Fixed DOFs keep whatever value the caller puts in `x`, so moving a
//! handle between solves is just writing new positions.

use crate::error::FemError;

/// Marks a DOF without an unknown.
const FIXED: u32 = u32::MAX;

/// The map between vertex DOFs and the unknowns of the reduced system.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DofMap {
    n_vertices: usize,
    dim: usize,
    /// DOF → unknown, or `FIXED`.
    to_unknown: Vec<u32>,
    /// unknown → DOF.
    to_dof: Vec<u32>,
}

impl DofMap {
    /// Every DOF free.
    pub fn all_free(n_vertices: usize, dim: usize) -> Result<Self, FemError> {
        Self::from_dof_mask(n_vertices, dim, &vec![false; n_vertices * dim])
    }

    /// Whole vertices fixed (every coordinate). Repeated indices are fine.
    pub fn from_fixed_vertices(
        n_vertices: usize,
        dim: usize,
        fixed: &[usize],
    ) -> Result<Self, FemError> {
        let mut mask = vec![false; n_vertices * dim];
        for &v in fixed {
            if v >= n_vertices {
                return Err(FemError::FixedOutOfRange {
                    vertex: v,
                    n_vertices,
                });
            }
            mask[v * dim..(v + 1) * dim].fill(true);
        }
        Self::from_dof_mask(n_vertices, dim, &mask)
    }

    /// Per-DOF mask: `fixed[v·D + c]` fixes coordinate `c` of vertex `v`.
    pub fn from_dof_mask(n_vertices: usize, dim: usize, fixed: &[bool]) -> Result<Self, FemError> {
        let n_dofs = n_vertices * dim;
        FemError::check_len("fixed-DOF mask", n_dofs, fixed.len())?;
        if n_dofs >= FIXED as usize {
            return Err(FemError::TooLarge {
                what: "DOF",
                count: n_dofs,
                max: FIXED as usize - 1,
            });
        }
        let mut to_unknown = vec![FIXED; n_dofs];
        let mut to_dof = Vec::with_capacity(n_dofs);
        for (d, &f) in fixed.iter().enumerate() {
            if !f {
                to_unknown[d] = to_dof.len() as u32;
                to_dof.push(d as u32);
            }
        }
        Ok(DofMap {
            n_vertices,
            dim,
            to_unknown,
            to_dof,
        })
    }

    /// The same fixed set with unknowns renumbered vertex by vertex in
    /// `vertex_order` (a permutation of the vertices; components ascending).
    /// The solver uses this for memory locality (see `order`).
    pub fn renumbered(&self, vertex_order: &[usize]) -> DofMap {
        let mut to_unknown = vec![FIXED; self.to_unknown.len()];
        let mut to_dof = Vec::with_capacity(self.to_dof.len());
        for &v in vertex_order {
            for c in 0..self.dim {
                let d = v * self.dim + c;
                if self.to_unknown[d] != FIXED {
                    to_unknown[d] = to_dof.len() as u32;
                    to_dof.push(d as u32);
                }
            }
        }
        DofMap {
            n_vertices: self.n_vertices,
            dim: self.dim,
            to_unknown,
            to_dof,
        }
    }

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.n_vertices
    }

    /// Coordinates per vertex.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of unknowns (free DOFs).
    pub fn n_unknowns(&self) -> usize {
        self.to_dof.len()
    }

    /// Number of fixed DOFs.
    pub fn n_fixed(&self) -> usize {
        self.to_unknown.len() - self.to_dof.len()
    }

    /// The unknown of DOF `dof`, or `None` when it is fixed.
    #[inline]
    pub fn unknown(&self, dof: usize) -> Option<usize> {
        let u = self.to_unknown[dof];
        (u != FIXED).then_some(u as usize)
    }

    /// Raw DOF → unknown table (`u32::MAX` = fixed), for hot loops.
    #[inline]
    pub(crate) fn unknown_table(&self) -> &[u32] {
        &self.to_unknown
    }

    /// The DOF of unknown `u`.
    #[inline]
    pub fn dof(&self, u: usize) -> usize {
        self.to_dof[u] as usize
    }

    /// Whether coordinate `c` of vertex `v` is fixed.
    pub fn is_fixed(&self, v: usize, c: usize) -> bool {
        self.to_unknown[v * self.dim + c] == FIXED
    }

    /// Whether vertex `v` has at least one free coordinate.
    pub fn vertex_has_free(&self, v: usize) -> bool {
        (0..self.dim).any(|c| !self.is_fixed(v, c))
    }

    /// `reduced[u] = full[dof(u)]`.
    pub fn gather(&self, full: &[f64], reduced: &mut [f64]) {
        for (r, &d) in reduced.iter_mut().zip(&self.to_dof) {
            *r = full[d as usize];
        }
    }

    /// `full[dof(u)] = reduced[u]`; fixed entries untouched.
    pub fn scatter(&self, reduced: &[f64], full: &mut [f64]) {
        for (r, &d) in reduced.iter().zip(&self.to_dof) {
            full[d as usize] = *r;
        }
    }

    /// `full[dof(u)] += a·reduced[u]`; fixed entries untouched.
    pub fn scatter_axpy(&self, a: f64, reduced: &[f64], full: &mut [f64]) {
        for (r, &d) in reduced.iter().zip(&self.to_dof) {
            full[d as usize] += a * *r;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbering_follows_dofs_and_skips_fixed() {
        let m = DofMap::from_fixed_vertices(3, 2, &[1, 1]).unwrap();
        assert_eq!(m.n_unknowns(), 4);
        assert_eq!(m.n_fixed(), 2);
        assert_eq!(m.unknown(0), Some(0));
        assert_eq!(m.unknown(2), None);
        assert_eq!(m.unknown(4), Some(2));
        assert_eq!(m.dof(3), 5);
        assert!(!m.vertex_has_free(1));
        let full = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let mut red = [0.0; 4];
        m.gather(&full, &mut red);
        assert_eq!(red, [1.0, 2.0, 5.0, 6.0]);
        let mut back = [0.0; 6];
        m.scatter(&red, &mut back);
        assert_eq!(back, [1.0, 2.0, 0.0, 0.0, 5.0, 6.0]);
        m.scatter_axpy(2.0, &red, &mut back);
        assert_eq!(back, [3.0, 6.0, 0.0, 0.0, 15.0, 18.0]);
    }

    #[test]
    fn renumbering_keeps_the_fixed_set() {
        let m = DofMap::from_fixed_vertices(3, 2, &[1])
            .unwrap()
            .renumbered(&[2, 1, 0]);
        assert_eq!(m.n_unknowns(), 4);
        assert_eq!(m.unknown(4), Some(0)); // vertex 2 first
        assert_eq!(m.unknown(5), Some(1));
        assert_eq!(m.unknown(2), None);
        assert_eq!(m.unknown(0), Some(2));
        let full = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let mut red = [0.0; 4];
        m.gather(&full, &mut red);
        assert_eq!(red, [5.0, 6.0, 1.0, 2.0]);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(matches!(
            DofMap::from_fixed_vertices(3, 2, &[3]),
            Err(FemError::FixedOutOfRange {
                vertex: 3,
                n_vertices: 3
            })
        ));
        assert!(matches!(
            DofMap::from_dof_mask(2, 2, &[false; 3]),
            Err(FemError::LengthMismatch { .. })
        ));
    }
}
