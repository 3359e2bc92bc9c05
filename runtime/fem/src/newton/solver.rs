//! The projected Newton loop (Smith et al. 2019, Algorithm 1).

use std::ops::ControlFlow;
use std::time::Instant;

use ecc_runtime::filter::Filter;

use super::iteration::SolveState;
use super::params::NewtonParams;
use super::record::{IterationRecord, NewtonResult, NewtonStatus};
use crate::assembly::{Assembler, NonFiniteStencil};
use crate::dofs::DofMap;
use crate::error::FemError;
use crate::linear::ordering::Coordinates;
use crate::linear::{LinearSolver, LinearSystem};
use crate::pattern::Pattern;
use crate::term::Term;

/// Energy, reduced gradient and (optionally) reduced Hessian values at a point.
#[derive(Clone, Debug)]
pub struct Evaluation {
    /// Scaled energy.
    pub energy: f64,
    /// Scaled gradient per vertex DOF (index v·D + c), zero on fixed DOFs.
    pub gradient: Vec<f64>,
    /// Upper-CSC values of the scaled, filtered reduced Hessian over the
    /// unknowns (see [`NewtonSolver::pattern`] and [`NewtonSolver::dofs`]).
    pub hessian: Option<Vec<f64>>,
}

/// A projected Newton solver for Σ terms over a fixed mesh and fixed set.
///
/// Built once per (terms' stencils, fixed DOFs): pattern, slot maps,
/// colourings and the symbolic factorisation. `solve` can then be called
/// any number of times (moved handles, changed term data, new start).
pub struct NewtonSolver<const D: usize> {
    pub(super) terms: Vec<Box<dyn Term<D>>>,
    pub(super) assembler: Assembler<D>,
    pub(super) linear: LinearSystem,
    /// (symbolic analyses, numeric factorisations) of the linear backends
    /// replaced by [`NewtonSolver::set_linear_solver`].
    earlier: (usize, usize),
    /// Parameters (may be changed between solves; `linear_solver` and
    /// `auto_limits` only take effect through [`NewtonSolver::set_linear_solver`]).
    pub params: NewtonParams,
    /// ∇E over the unknowns.
    pub(super) g: Vec<f64>,
    /// Upper-CSC values of the (shifted) Hessian.
    pub(super) values: Vec<f64>,
    pub(super) rhs: Vec<f64>,
    /// Newton direction over the unknowns.
    pub(super) d: Vec<f64>,
    /// d per vertex (zero on fixed DOFs).
    pub(super) dx: Vec<[f64; D]>,
    /// Trial positions x + αd.
    pub(super) xt: Vec<[f64; D]>,
    pub(super) partials: Vec<f64>,
    /// Position of every unknown, for the `geometric` ordering.
    coords: Option<Coordinates>,
}

/// Vertex positions and, when computed already, a nested dissection of
/// the vertices ([`NewtonSolver::with_dissected_geometry`]).
type Geometry<'a> = (&'a [[f64; 3]], Option<&'a [usize]>);

/// The [`Coordinates`] of the unknowns of `dofs` (the assembler's
/// renumbered order) at the vertex `positions`, with the vertex
/// `dissection` as the first unknown of each of its vertices that has one.
fn coordinates<const D: usize>(
    dofs: &DofMap,
    positions: &[[f64; 3]],
    dissection: Option<&[usize]>,
) -> Coordinates {
    let n = dofs.n_unknowns();
    let vertex = |u: usize| dofs.dof(u) / D;
    let at: Vec<[f64; 3]> = (0..n).map(|u| positions[vertex(u)]).collect();
    let dissection = dissection.map(|order| {
        let mut first = vec![usize::MAX; positions.len()];
        for u in (0..n).rev() {
            first[vertex(u)] = u;
        }
        order
            .iter()
            .filter_map(|&v| first.get(v).copied().filter(|&u| u != usize::MAX))
            .collect()
    });
    Coordinates {
        at: at.into(),
        dissection,
    }
}

impl<const D: usize> NewtonSolver<D> {
    /// Solver with whole vertices fixed (`fixed` may be empty).
    pub fn new(
        n_vertices: usize,
        terms: Vec<Box<dyn Term<D>>>,
        fixed: &[usize],
        params: NewtonParams,
    ) -> Result<Self, FemError> {
        let dofs = DofMap::from_fixed_vertices(n_vertices, D, fixed)?;
        Self::with_dofs(terms, dofs, params)
    }

    /// Solver with an explicit DOF map (per-coordinate constraints).
    pub fn with_dofs(
        terms: Vec<Box<dyn Term<D>>>,
        dofs: DofMap,
        params: NewtonParams,
    ) -> Result<Self, FemError> {
        Self::build(terms, dofs, params, None)
    }

    /// [`NewtonSolver::with_dofs`] knowing where the vertices are
    /// (`positions[v]`, e.g. the rest shape; 2D positions with z = 0), so
    /// the Cholesky factor can use the `geometric` ordering
    /// ([`crate::linear::ordering::FillOrdering::Geometric`]) when asked
    /// for. Errors when `positions` is not one per vertex.
    pub fn with_geometry(
        terms: Vec<Box<dyn Term<D>>>,
        dofs: DofMap,
        params: NewtonParams,
        positions: &[[f64; 3]],
    ) -> Result<Self, FemError> {
        Self::positioned(terms, dofs, params, (positions, None))
    }

    /// [`NewtonSolver::with_geometry`] with a nested dissection of the
    /// vertex graph at `positions` computed already (`dissection[new] =
    /// vertex`, e.g. `ecc_mesh::dissection::mesh_dissection`, shared with the
    /// Tutte start), which the `geometric` ordering then takes instead of
    /// dissecting the same graph again
    /// ([`crate::linear::ordering::Coordinates::dissection`]). Only the fill
    /// depends on it: a dissection that is not one of the solver's vertex
    /// groups is not used.
    pub fn with_dissected_geometry(
        terms: Vec<Box<dyn Term<D>>>,
        dofs: DofMap,
        params: NewtonParams,
        positions: &[[f64; 3]],
        dissection: &[usize],
    ) -> Result<Self, FemError> {
        Self::positioned(terms, dofs, params, (positions, Some(dissection)))
    }

    /// [`NewtonSolver::build`] with `geometry`, whose positions must be one
    /// per vertex.
    fn positioned(
        terms: Vec<Box<dyn Term<D>>>,
        dofs: DofMap,
        params: NewtonParams,
        geometry: Geometry<'_>,
    ) -> Result<Self, FemError> {
        FemError::check_len(
            "vertex positions for the ordering",
            dofs.n_vertices(),
            geometry.0.len(),
        )?;
        Self::build(terms, dofs, params, Some(geometry))
    }

    fn build(
        terms: Vec<Box<dyn Term<D>>>,
        dofs: DofMap,
        params: NewtonParams,
        geometry: Option<Geometry<'_>>,
    ) -> Result<Self, FemError> {
        let nv = dofs.n_vertices();
        let assembler = Assembler::new(&terms, dofs)?;
        let pattern = assembler.pattern();
        let coords = geometry.map(|(p, d)| coordinates::<D>(assembler.dofs(), p, d));
        let linear = LinearSystem::with_geometry(
            pattern,
            params.linear_solver,
            params.auto_limits,
            D,
            params.cholesky,
            coords.clone(),
        )?;
        let n = pattern.n();
        let nnz = pattern.nnz();
        Ok(NewtonSolver {
            terms,
            linear,
            earlier: (0, 0),
            params,
            g: vec![0.0; n],
            values: vec![0.0; nnz],
            rhs: vec![0.0; n],
            d: vec![0.0; n],
            dx: vec![[0.0; D]; nv],
            xt: vec![[0.0; D]; nv],
            partials: Vec::new(),
            assembler,
            coords,
        })
    }

    /// Rebuild the linear backend (e.g. switch Cholesky ↔ PCG).
    pub fn set_linear_solver(&mut self, choice: LinearSolver) -> Result<(), FemError> {
        self.params.linear_solver = choice;
        let limits = self.params.auto_limits;
        let pattern = self.assembler.pattern();
        let new = LinearSystem::with_geometry(
            pattern,
            choice,
            limits,
            D,
            self.params.cholesky,
            self.coords.clone(),
        )?;
        let old = std::mem::replace(&mut self.linear, new);
        self.earlier.0 += old.symbolic_analyses();
        self.earlier.1 += old.cholesky().map_or(0, |c| c.numeric_factorizations());
        Ok(())
    }

    /// The linear solver in use (`Cholesky` or `Pcg`).
    pub fn linear_solver(&self) -> LinearSolver {
        self.linear.kind()
    }

    /// The linear system (factor size, counters).
    pub fn linear_system(&self) -> &LinearSystem {
        &self.linear
    }

    /// The DOF map.
    pub fn dofs(&self) -> &DofMap {
        self.assembler.dofs()
    }

    /// The reduced Hessian's pattern.
    pub fn pattern(&self) -> &Pattern {
        self.assembler.pattern()
    }

    /// Number of vertices.
    pub fn n_vertices(&self) -> usize {
        self.dx.len()
    }

    /// The terms.
    pub fn terms(&self) -> &[Box<dyn Term<D>>] {
        &self.terms
    }

    /// Term `i` as its concrete type, to change its data between solves
    /// (its stencils must not change).
    pub fn term_mut<T: Term<D>>(&mut self, i: usize) -> Option<&mut T> {
        let t: &mut dyn std::any::Any = self.terms.get_mut(i)?.as_mut();
        t.downcast_mut::<T>()
    }

    fn check_positions(&self, x: &[[f64; D]]) -> Result<(), FemError> {
        FemError::check_len("positions", self.dx.len(), x.len())?;
        if let Some(v) = x.iter().position(|p| p.iter().any(|c| !c.is_finite())) {
            return Err(FemError::NonFinitePosition {
                what: "positions",
                vertex: v,
            });
        }
        Ok(())
    }

    /// Scaled energy at `x` (`+∞` outside the domain).
    pub fn energy(&mut self, x: &[[f64; D]]) -> Result<f64, FemError> {
        self.check_positions(x)?;
        Ok(self
            .assembler
            .energy(&self.terms, x, self.params.energy_scale))
    }

    /// Scaled energy, gradient and optionally the filtered Hessian at `x`.
    pub fn evaluate(
        &mut self,
        x: &[[f64; D]],
        hessian: Option<Filter>,
    ) -> Result<Result<Evaluation, NonFiniteStencil>, FemError> {
        self.check_positions(x)?;
        let mut reduced = vec![0.0; self.g.len()];
        let mut values = hessian.map(|_| vec![0.0; self.values.len()]);
        let h = hessian.zip(values.as_deref_mut());
        let assembled =
            self.assembler
                .assemble(&self.terms, x, self.params.energy_scale, &mut reduced, h);
        Ok(assembled.map(|energy| {
            let mut gradient = vec![0.0; x.len() * D];
            self.assembler.dofs().scatter(&reduced, &mut gradient);
            Evaluation {
                energy,
                gradient,
                hessian: values,
            }
        }))
    }

    /// Minimise from `x` (fixed vertices keep their values in `x`).
    pub fn solve(&mut self, x: &mut [[f64; D]]) -> Result<NewtonResult, FemError> {
        self.solve_with(x, |_, _| ControlFlow::Continue(()))
    }

    /// [`NewtonSolver::solve`] with a callback after every accepted step
    /// (record, new positions); `ControlFlow::Break` stops with `Interrupted`.
    pub fn solve_with(
        &mut self,
        x: &mut [[f64; D]],
        mut callback: impl FnMut(&IterationRecord, &[[f64; D]]) -> ControlFlow<()>,
    ) -> Result<NewtonResult, FemError> {
        self.check_positions(x)?;
        let t_start = Instant::now();
        self.assembler.reset_timings();
        let mut state = SolveState::new(self.params.clone(), self.dofs().n_fixed());
        self.linear.forget_factor();
        let status = loop {
            if let Err(status) = self.iteration(x, &mut state, &mut callback) {
                break status;
            }
        };
        // The reported energy is that of the returned positions as
        // [`NewtonSolver::energy`] computes it: the assembly pass that set
        // `last` sums the same element energies in another grouping (with the
        // gradient), so its total can differ in the last bits.
        if state.last.0.is_finite() {
            state.last.0 = self
                .assembler
                .energy(&self.terms, x, self.params.energy_scale);
        }
        state.times.total = t_start.elapsed().as_secs_f64();
        Ok(self.result(status, state))
    }

    /// The solve's report; the counters cover this solver's whole life
    /// (every linear backend it has had).
    fn result(&self, status: NewtonStatus, s: SolveState) -> NewtonResult {
        let (initial_energy, initial_grad_inf) = s.initial.unwrap_or(s.last);
        let factorizations = self
            .linear
            .cholesky()
            .map_or(0, |c| c.numeric_factorizations());
        NewtonResult {
            status,
            iterations: s.iter,
            initial_energy,
            energy: s.last.0,
            initial_grad_inf,
            grad_inf: s.last.1,
            unknowns: self.g.len(),
            linear_solver: self.linear.kind(),
            symbolic_analyses: self.earlier.0 + self.linear.symbolic_analyses(),
            numeric_factorizations: self.earlier.1 + factorizations,
            times: s.times,
            terms: self.assembler.timings().to_vec(),
            records: s.records,
        }
    }
}
