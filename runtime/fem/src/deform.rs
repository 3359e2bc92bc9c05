//! Tet-mesh deformation with handles: some vertices fixed, some moved.
//!
//! Handle vertices are Dirichlet DOFs (eliminated); the rest minimise
//! Σ_q |q| Ψ(F_q). Moving the handles only rewrites their positions — the
//! pattern, colouring and symbolic factorisation are reused. Large handle
//! motions can be split into `substeps` linear increments (each a full
//! Newton solve warm-started from the previous one), which keeps elements
//! next to the handles from inverting in one jump: needed for barrier
//! energies, helpful for convergence of the others.

use std::ops::ControlFlow;
use std::sync::Arc;

use ecc_mesh::TetMesh;
use ecc_runtime::Energy;
use serde::{Deserialize, Serialize};

use crate::elastic::{Elastic, Tet};
use crate::error::FemError;
use crate::newton::params::NewtonParams;
use crate::newton::record::{IterationRecord, NewtonResult};
use crate::newton::solver::NewtonSolver;
use crate::quality::count_inverted;
use crate::term::Term;

/// Indices of the vertices whose position satisfies `pred`.
pub fn vertices_where(positions: &[[f64; 3]], pred: impl Fn(&[f64; 3]) -> bool) -> Vec<usize> {
    positions
        .iter()
        .enumerate()
        .filter(|(_, p)| pred(p))
        .map(|(i, _)| i)
        .collect()
}

/// Outcome of moving the handles.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct DeformResult {
    /// One Newton result per substep.
    pub substeps: Vec<NewtonResult>,
    /// Inverted tets in the final positions.
    pub inverted: usize,
}

impl DeformResult {
    /// Whether every substep converged.
    pub fn converged(&self) -> bool {
        self.substeps.iter().all(|r| r.converged())
    }

    /// Newton iterations over all substeps.
    pub fn iterations(&self) -> usize {
        self.substeps.iter().map(|r| r.iterations).sum()
    }
}

/// A tet mesh with handle vertices, ready to be deformed repeatedly.
pub struct HandleDeformation {
    solver: NewtonSolver<3>,
    tets: Vec<[usize; 4]>,
    handles: Vec<usize>,
    x: Vec<[f64; 3]>,
}

impl HandleDeformation {
    /// Rest shape = the mesh positions; `handles` are fixed (and may later be moved).
    pub fn new<E: Energy<3> + ?Sized + 'static>(
        mesh: &TetMesh,
        energy: Arc<E>,
        handles: &[usize],
        params: NewtonParams,
    ) -> Result<Self, FemError> {
        let elastic = Elastic::<E, Tet>::new(energy, &mesh.positions, &mesh.tets)?;
        let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(elastic)];
        let solver = NewtonSolver::new(mesh.positions.len(), terms, handles, params)?;
        Ok(HandleDeformation {
            solver,
            tets: mesh.tets.clone(),
            handles: handles.to_vec(),
            x: mesh.positions.clone(),
        })
    }

    /// The handle vertices, in the order targets are given.
    pub fn handles(&self) -> &[usize] {
        &self.handles
    }

    /// Current positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.x
    }

    /// Overwrite the current positions (e.g. a new start).
    pub fn set_positions(&mut self, x: &[[f64; 3]]) -> Result<(), FemError> {
        if x.len() != self.x.len() {
            return Err(FemError::LengthMismatch {
                what: "positions",
                expected: self.x.len(),
                got: x.len(),
            });
        }
        self.x.copy_from_slice(x);
        Ok(())
    }

    /// The underlying solver (parameters, counters).
    pub fn solver_mut(&mut self) -> &mut NewtonSolver<3> {
        &mut self.solver
    }

    /// Move handle `i` to `targets[i]` in `substeps` ≥ 1 equal increments,
    /// solving after each. Stops early (and reports it) if a substep fails.
    pub fn solve(
        &mut self,
        targets: &[[f64; 3]],
        substeps: usize,
    ) -> Result<DeformResult, FemError> {
        self.solve_with(targets, substeps, |_, _| ControlFlow::Continue(()))
    }

    /// [`solve`](Self::solve) with `on_iteration` called after every Newton
    /// step of every substep (the record and the current positions);
    /// returning `Break` stops the solve (status `Interrupted`) and no
    /// further substep runs.
    pub fn solve_with(
        &mut self,
        targets: &[[f64; 3]],
        substeps: usize,
        mut on_iteration: impl FnMut(&IterationRecord, &[[f64; 3]]) -> ControlFlow<()>,
    ) -> Result<DeformResult, FemError> {
        if targets.len() != self.handles.len() {
            return Err(FemError::LengthMismatch {
                what: "handle targets",
                expected: self.handles.len(),
                got: targets.len(),
            });
        }
        if let Some(i) = targets
            .iter()
            .position(|t| t.iter().any(|c| !c.is_finite()))
        {
            return Err(FemError::NonFinitePosition {
                what: "handle targets",
                vertex: self.handles[i],
            });
        }
        let start: Vec<[f64; 3]> = self.handles.iter().map(|&h| self.x[h]).collect();
        let n = substeps.max(1);
        let mut results = Vec::with_capacity(n);
        for k in 1..=n {
            let t = k as f64 / n as f64;
            for ((&h, s), e) in self.handles.iter().zip(&start).zip(targets) {
                // the last substep lands exactly on the target
                self.x[h] = if k == n {
                    *e
                } else {
                    std::array::from_fn(|c| s[c] + t * (e[c] - s[c]))
                };
            }
            let r = self.solver.solve_with(&mut self.x, &mut on_iteration)?;
            let ok = r.converged();
            results.push(r);
            if !ok {
                break;
            }
        }
        Ok(DeformResult {
            substeps: results,
            inverted: count_inverted(&self.x, &self.tets),
        })
    }
}
