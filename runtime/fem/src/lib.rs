//! # ecc-fem: FEM assembly and the projected Newton solver
//!
//! Minimises objectives of the form
//!
//!   E(x) = Σ_terms Σ_stencils e_s(x),   e.g.  Σ_q |q| Ψ(F_q(x))
//!
//! over triangle and tetrahedral meshes with projected Newton (Smith, de
//! Goes & Kim 2019, Algorithm 1): per-element PSD-projected Hessians from the
//! eigensystem runtime, sparse Cholesky (faer) or Jacobi-PCG, and a
//! backtracking line search that is inversion-free for barrier energies.
//!
//! ## Pieces
//!
//! * [`Term`]: one additive term, evaluated stencil by stencil (local value,
//!   gradient, filtered Hessian, inversion-free step). [`Elastic`] is the
//!   hyperelastic / distortion term over triangles ([`Tri`]: planar rest
//!   shapes or surface triangles in isometric rest frames) and tets ([`Tet`]),
//!   generic over `E: Energy<D> + ?Sized` (hand-written, generated or
//!   interpreted energies, `Arc<dyn Energy<D>>` included). [`SoftAnchors`] is
//!   a quadratic soft-handle term.
//! * [`DofMap`]: Dirichlet (fixed) DOFs are eliminated; the reduced system
//!   has one unknown per free DOF. Fixed positions are read from `x` at every
//!   solve, so moved handles need no rebuild.
//! * [`Assembler`]: the sparsity pattern, stencil→slot maps and a stencil
//!   colouring are built **once per mesh**; each iteration refills values in
//!   parallel (rayon, colour by colour, no atomics, no allocation).
//! * [`linear`]: faer sparse Cholesky (symbolic analysis once, numeric
//!   factorisation into preallocated storage each step) or Jacobi PCG with an
//!   inexact-Newton forcing term; `Auto` picks from the factor's memory and
//!   flop estimates ([`AutoLimits`]). A small
//!   relative diagonal shift handles the translation null space when nothing
//!   is fixed.
//! * [`NewtonSolver`]: the iteration, with [`NewtonParams`] (tolerances,
//!   filter and [`FilterPolicy`]: fixed, Chen et al. 2024 trust region, or
//!   trust-region Newton; line search constants) and a serde-ready
//!   [`NewtonResult`] (status, best iterate, per-iteration records with the
//!   assembly / factorisation / solve / line-search time split, per-term
//!   timings).
//! * Helpers: [`param`] (surface parameterisation from a Tutte start, unit
//!   area, mean-energy reporting), [`deform`] (tet deformation with fixed and
//!   moved handles), [`quality`] (flipped / inverted element counts).
//!
//! ## Adding a term
//!
//! Implement [`Term`] for a struct holding its stencils (flat vertex list)
//! and data, box it into the solver's term list, and the solver assembles
//! it with the others: gravity is an arity-1 term with zero Hessian, lumped
//! inertia ½ m‖x − x̃‖²/h² an arity-1 quadratic (see [`SoftAnchors`]), a
//! ground barrier an arity-1 barrier term with its own `max_step`. A solver's
//! terms can be reached again with [`NewtonSolver::term_mut`] to update their
//! data (targets, x̃, weights) between solves. Everything is reported per
//! term in [`NewtonResult::terms`].
//!
//! ## Example
//!
//! Bend a tet bar with ARAP: one end fixed, the other end moved.
//!
//! ```
//! use std::sync::Arc;
//! use ecc_fem::{Elastic, NewtonParams, NewtonSolver, Term, Tet};
//! use ecc_runtime::energies::Arap;
//!
//! let mesh = ecc_mesh::bar_tet(1); // [-2, 2] × [-0.5, 0.5]², 96 tets
//! let rest = mesh.positions.clone();
//! let left: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0] < -1.99).collect();
//! let right: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0] > 1.99).collect();
//! let handles: Vec<usize> = left.iter().chain(&right).copied().collect();
//!
//! let elastic = Elastic::<_, Tet>::new(Arc::new(Arap), &rest, &mesh.tets)?;
//! let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(elastic)];
//! let mut solver = NewtonSolver::new(rest.len(), terms, &handles, NewtonParams::default())?;
//!
//! let mut x = rest.clone();
//! for &v in &right {
//!     x[v][1] += 1.0; // move the right handle up; fixed DOFs are read from x
//! }
//! let result = solver.solve(&mut x)?;
//! assert!(result.converged() && result.grad_inf <= 1e-4);
//! assert_eq!(x[right[0]][1], rest[right[0]][1] + 1.0);
//! // result (status, per-iteration records, time split, per-term timings) is serde-serialisable
//! # Ok::<(), ecc_fem::FemError>(())
//! ```

pub mod assembly;
mod colour;
pub mod deform;
pub mod dofs;
pub mod elastic;
pub mod error;
pub mod fibre;
pub mod linear;
pub mod newton;
mod order;
mod parallel;
pub mod param;
pub mod pattern;
pub mod quality;
pub mod roots;
pub mod term;
pub mod terms;

pub use assembly::{Assembler, NonFiniteStencil, TermTiming};
pub use dofs::DofMap;
pub use elastic::{Elastic, Simplex, Tet, Tri};
pub use error::FemError;
pub use fibre::Fibre;
pub use linear::{AutoLimits, LinearSolver};
pub use newton::params::{FilterPolicy, NewtonParams};
pub use newton::record::{IterationRecord, NewtonResult, NewtonStatus, TimeSplit};
pub use newton::solver::{Evaluation, NewtonSolver};
pub use pattern::{Pattern, VertexBlocks};
pub use term::{MAX_STENCIL_DOFS, Term};
pub use terms::SoftAnchors;

pub use ecc_runtime::filter::Filter;
