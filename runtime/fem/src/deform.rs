//! Deformation with handles: some vertices fixed, some moved.
//!
//! Handle vertices are Dirichlet DOFs (eliminated); the rest minimise the
//! solver's objective (Σ_q |q| Ψ(F_q) for [`HandleDeformation`], any sum of
//! terms for [`move_handles`]). Moving the handles only rewrites their
//! positions — the pattern, colouring and symbolic factorisation are reused.
//!
//! A move is split into [`Substeps::count`] equal increments, each a full
//! Newton solve warm-started from the previous one, which keeps elements next
//! to the handles from inverting in one jump. An increment whose start is
//! infeasible (objective +∞ or not finite: an element of a barrier energy
//! inverted by the handle jump) is halved, at most
//! [`Substeps::max_halvings`] times, and grows back (doubling, up to a full
//! increment) after every solve. With n increments of 2^h ticks each
//! (h = `max_halvings`), the handles are placed at fractions
//!
//! f = k / (n 2^h),  k ∈ ℕ,  f ≤ 1,                                   (1)
//!
//! so f lands exactly on 1 (the targets) and, without halving, on i/n.

use std::ops::ControlFlow;
use std::sync::Arc;

use ecc_mesh::TetMesh;
use ecc_runtime::Energy;
use serde::{Deserialize, Serialize};

use crate::dofs::DofMap;
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

/// How a move is split into solves (see the module docs, eq. 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Substeps {
    /// Equal increments (0 is taken as 1).
    pub count: usize,
    /// How often an infeasible increment may be halved (10: down to 1/1024).
    pub max_halvings: u32,
}

impl Substeps {
    /// `count` increments, each halved down to 1/1024 when infeasible.
    pub fn new(count: usize) -> Self {
        Substeps {
            count,
            max_halvings: 10,
        }
    }
}

/// What drives a move: where the handles are at a fraction of it and what
/// happens around each Newton solve.
pub trait HandleMove<const D: usize> {
    /// Write the handles' positions (and any state that follows the move,
    /// e.g. an interpolation parameter held by a term) at fraction
    /// `f` ∈ (0, 1] of the move into `x`.
    fn place(&mut self, f: f64, solver: &mut NewtonSolver<D>, x: &mut [[f64; D]]);

    /// Just before a solve starts from a feasible placement.
    fn before_solve(&mut self) {}

    /// After every Newton step (record, current positions); `Break` stops
    /// the solve (status `Interrupted`).
    fn iteration(&mut self, _rec: &IterationRecord, _x: &[[f64; D]]) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }

    /// After every solve; `Break` ends the move (no further increment).
    fn solved(&mut self, result: &NewtonResult) -> ControlFlow<()>;
}

/// How a move ended.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum MoveEnd {
    /// The handles reached their targets (f = 1) and every solve was let through.
    Done,
    /// [`HandleMove::solved`] returned `Break`.
    Stopped,
    /// Even the smallest increment after fraction `reached` was infeasible;
    /// the positions are back at the start of the move.
    Infeasible {
        /// The fraction of the move solved before.
        reached: f64,
    },
}

/// The solves of a move and how it ended.
#[derive(Clone, Debug)]
pub struct MoveOutcome {
    /// One Newton result per solve, in order.
    pub solves: Vec<NewtonResult>,
    /// How the move ended.
    pub end: MoveEnd,
}

/// Whether the objective is finite at `x` (a placement a solve can start from).
pub fn feasible<const D: usize>(solver: &mut NewtonSolver<D>, x: &[[f64; D]]) -> bool {
    solver.energy(x).is_ok_and(|e| e.is_finite())
}

/// Move the handles along `mv` from the current positions `x`: the one
/// substep loop of the workspace (module docs, eq. 1). Errors are the
/// solver's (positions it rejects).
pub fn move_handles<const D: usize>(
    solver: &mut NewtonSolver<D>,
    x: &mut [[f64; D]],
    substeps: Substeps,
    mv: &mut impl HandleMove<D>,
) -> Result<MoveOutcome, FemError> {
    let per = 1u64 << substeps.max_halvings.min(40);
    let total = per * substeps.count.max(1) as u64;
    let start = x.to_vec();
    let (mut done, mut step) = (0u64, per);
    let mut solves = Vec::new();
    while done < total {
        let to = (done + step).min(total);
        mv.place(to as f64 / total as f64, solver, x);
        if !feasible(solver, x) {
            // retry a shorter increment from the last solved positions (an
            // increment cut by the end of the move may need several halvings)
            while step > 1 && (done + step).min(total) >= to {
                step /= 2;
            }
            if (done + step).min(total) >= to {
                x.copy_from_slice(&start);
                let reached = done as f64 / total as f64;
                let end = MoveEnd::Infeasible { reached };
                return Ok(MoveOutcome { solves, end });
            }
            continue;
        }
        mv.before_solve();
        let r = solver.solve_with(x, |rec, x| mv.iteration(rec, x))?;
        done = to;
        step = (step * 2).min(per);
        let flow = mv.solved(&r);
        solves.push(r);
        if flow.is_break() {
            let end = MoveEnd::Stopped;
            return Ok(MoveOutcome { solves, end });
        }
    }
    let end = MoveEnd::Done;
    Ok(MoveOutcome { solves, end })
}

/// Outcome of moving the handles.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct DeformResult {
    /// One Newton result per substep.
    pub substeps: Vec<NewtonResult>,
    /// Inverted tets in the final positions.
    pub inverted: usize,
    /// Even the smallest increment was infeasible (the positions are back
    /// at the start of the move).
    #[serde(default)]
    pub infeasible: bool,
}

impl DeformResult {
    /// Whether the handles reached their targets and every substep converged.
    pub fn converged(&self) -> bool {
        !self.infeasible && self.substeps.iter().all(|r| r.converged())
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

/// Handles moved on straight lines from `start` to `targets`; the move
/// stops after the first solve that does not converge.
struct Linear<'a, C> {
    handles: &'a [usize],
    start: Vec<[f64; 3]>,
    targets: &'a [[f64; 3]],
    on_iteration: C,
}

impl<C> HandleMove<3> for Linear<'_, C>
where
    C: FnMut(&IterationRecord, &[[f64; 3]]) -> ControlFlow<()>,
{
    fn place(&mut self, f: f64, _: &mut NewtonSolver<3>, x: &mut [[f64; 3]]) {
        for ((&h, s), e) in self.handles.iter().zip(&self.start).zip(self.targets) {
            // the last increment lands exactly on the target
            x[h] = if f == 1.0 {
                *e
            } else {
                std::array::from_fn(|c| s[c] + f * (e[c] - s[c]))
            };
        }
    }

    fn iteration(&mut self, rec: &IterationRecord, x: &[[f64; 3]]) -> ControlFlow<()> {
        (self.on_iteration)(rec, x)
    }

    fn solved(&mut self, result: &NewtonResult) -> ControlFlow<()> {
        if result.converged() {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    }
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
        let dofs = DofMap::from_fixed_vertices(mesh.positions.len(), 3, handles)?;
        let solver = NewtonSolver::with_geometry(terms, dofs, params, &mesh.positions)?;
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
        FemError::check_len("positions", self.x.len(), x.len())?;
        self.x.copy_from_slice(x);
        Ok(())
    }

    /// The underlying solver (parameters, counters).
    pub fn solver_mut(&mut self) -> &mut NewtonSolver<3> {
        &mut self.solver
    }

    /// Move handle `i` to `targets[i]` in `substeps` ≥ 1 equal increments
    /// (halved when infeasible, see the module docs), solving after each.
    /// Stops early (and reports it) if a substep fails.
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
        on_iteration: impl FnMut(&IterationRecord, &[[f64; 3]]) -> ControlFlow<()>,
    ) -> Result<DeformResult, FemError> {
        self.check_targets(targets)?;
        let mut linear = Linear {
            handles: &self.handles,
            start: self.handles.iter().map(|&h| self.x[h]).collect(),
            targets,
            on_iteration,
        };
        let m = move_handles(
            &mut self.solver,
            &mut self.x,
            Substeps::new(substeps),
            &mut linear,
        )?;
        Ok(DeformResult {
            substeps: m.solves,
            inverted: count_inverted(&self.x, &self.tets),
            infeasible: matches!(m.end, MoveEnd::Infeasible { .. }),
        })
    }

    fn check_targets(&self, targets: &[[f64; 3]]) -> Result<(), FemError> {
        FemError::check_len("handle targets", self.handles.len(), targets.len())?;
        match targets
            .iter()
            .position(|t| t.iter().any(|c| !c.is_finite()))
        {
            Some(i) => Err(FemError::NonFinitePosition {
                what: "handle targets",
                vertex: self.handles[i],
            }),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use ecc_mesh::box_tet;
    use ecc_runtime::energies::SymmetricDirichlet;

    use super::*;

    /// The x = 1 face of the unit cube pushed to x = `to` (the x = 0 face
    /// held), recording every placement.
    struct Squeeze {
        right: Vec<usize>,
        to: f64,
        placed: Vec<f64>,
    }

    impl HandleMove<3> for Squeeze {
        fn place(&mut self, f: f64, _: &mut NewtonSolver<3>, x: &mut [[f64; 3]]) {
            self.placed.push(f);
            for &v in &self.right {
                x[v][0] = 1.0 + f * (self.to - 1.0);
            }
        }

        fn solved(&mut self, _: &NewtonResult) -> ControlFlow<()> {
            ControlFlow::Continue(())
        }
    }

    fn squeeze(to: f64) -> (MoveOutcome, Squeeze, Vec<[f64; 3]>, Vec<[f64; 3]>) {
        let mesh = box_tet(2, 2, 2, [1.0; 3]);
        let rest = mesh.positions.clone();
        let left = vertices_where(&rest, |p| p[0] == 0.0);
        let right = vertices_where(&rest, |p| p[0] == 1.0);
        let handles: Vec<usize> = left.iter().chain(&right).copied().collect();
        let sd = Arc::new(SymmetricDirichlet);
        let elastic = Elastic::<SymmetricDirichlet, Tet>::new(sd, &rest, &mesh.tets).unwrap();
        let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(elastic)];
        let params = NewtonParams::default();
        let mut solver = NewtonSolver::new(rest.len(), terms, &handles, params).unwrap();
        let mut mv = Squeeze {
            right,
            to,
            placed: Vec::new(),
        };
        let mut x = rest.clone();
        let out = move_handles(&mut solver, &mut x, Substeps::new(1), &mut mv).unwrap();
        (out, mv, x, rest)
    }

    #[test]
    fn an_infeasible_increment_is_halved_and_grows_back() {
        // the face jumps past the middle layer (x = 0.5) in one increment:
        // inverted, so halved; from the solved half-way state the rest is feasible
        let (out, mv, x, _) = squeeze(0.2);
        assert_eq!(out.end, MoveEnd::Done);
        let placed = &mv.placed;
        assert_eq!(&placed[..2], &[1.0, 0.5], "{placed:?}");
        assert_eq!(*placed.last().unwrap(), 1.0);
        assert!(out.solves.len() >= 2 && out.solves.len() < placed.len());
        // no placement is tried twice in a row
        assert!(placed.windows(2).all(|w| w[0] != w[1]), "{placed:?}");
        assert!(out.solves.iter().all(|r| r.converged()));
        for &v in &mv.right {
            assert!((x[v][0] - 0.2).abs() < 1e-15);
        }
    }

    #[test]
    fn a_move_that_must_invert_ends_infeasible_at_its_start() {
        // the x = 1 face behind the x = 0 face inverts every column
        let (out, mv, x, rest) = squeeze(-0.5);
        let MoveEnd::Infeasible { reached } = out.end else {
            panic!("{:?}", out.end);
        };
        assert!(reached < 1.0);
        // the smallest increment is 1/1024 of the move
        let ticks: Vec<f64> = mv.placed.iter().map(|f| f * 1024.0).collect();
        assert!(ticks.iter().all(|t| t.fract() == 0.0), "{ticks:?}");
        assert_eq!(x, rest, "positions are back at the start of the move");
    }
}
