//! Surface parameterisation: minimise Σ_q |q| Ψ(J_q) over uv for a
//! disk-topology triangle mesh, from a Tutte start.
//!
//! 1. **Rest frames.** Each triangle is expressed in its own isometric 2D
//!    frame (`Rest::<2>::from_3d`), so J_q = Ds(uv) Dm⁻¹ is the Jacobian of the
//!    map from the surface to the plane.
//! 2. **Normalisation** (`normalize_area`, default on): the 3D positions are
//!    scaled by 1/√A so the total rest area Σ|q| is 1. Energies such as
//!    symmetric Dirichlet ½(‖J‖² + ‖J⁻¹‖²) are not scale invariant, so this is
//!    what makes numbers comparable across meshes and with peer libraries.
//! 3. **Mean energy** (`mean_energy`, default on): the solver minimises and
//!    reports Ē = Σ|q|Ψ / Σ|q| (the area-weighted mean; an isometry gives SD
//!    = 2) and tests ‖∇Ē‖∞ ≤ `tol_abs`. With unit area, Ē = Σ|q|Ψ.
//! 4. **Start.** Tutte embedding (ecc-mesh; bijective for uniform and
//!    mean-value weights, boundary on a circle), rescaled so the uv area equals
//!    the rest area (a mismatched scale costs barrier energies many steps).
//! 5. **Solve.** Projected Newton with no fixed vertex: the translation null
//!    space is handled by the solver's diagonal shift.
//!
//! Setup runs the Tutte solve (sequential sparse Cholesky, ecc-mesh) on its
//! own thread while this thread builds the solver (rest frames, pattern,
//! colouring, symbolic analysis): the two are independent, so the result is
//! bit-identical to running them one after the other, and on two cores the
//! setup costs about the longer of the two instead of their sum (issue #11:
//! on the 1M-triangle disk the Tutte solve was ≈ 1/3 of the setup). Both
//! use one geometric nested dissection of the mesh's vertex graph
//! (`ecc_mesh::dissection::mesh_dissection`, on rayon's threads) instead of
//! each dissecting its own graph of the same vertices (stop 32): this
//! thread computes it first, while the Tutte thread checks the mesh and
//! assembles its system, and hands it over when the Tutte solve asks
//! (stop 33); only for uniform and cotangent weights, whose Tutte solve
//! needs a dissection anyway.

use std::ops::ControlFlow;
use std::sync::Arc;
use std::time::Instant;

use ecc_mesh::dissection::mesh_dissection;
use ecc_mesh::{TriMesh, TutteWeights, tutte_embedding, tutte_embedding_in_order};
use ecc_runtime::Energy;
use serde::{Deserialize, Serialize};

use crate::dofs::DofMap;
use crate::elastic::{Elastic, Projection, Tri};
use crate::error::FemError;
use crate::newton::params::{FilterPolicy, NewtonParams};
use crate::newton::record::{IterationRecord, NewtonResult, NewtonStatus, TimeSplit};
use crate::newton::solver::NewtonSolver;
use crate::quality::{count_flipped, tri_signed_area};
use crate::term::Term;

/// Options of [`parameterize`].
#[derive(Clone, Debug)]
pub struct ParamOptions {
    /// Scale the mesh to unit total area first.
    pub normalize_area: bool,
    /// Minimise / report the area-weighted mean energy (sets `energy_scale`).
    pub mean_energy: bool,
    /// Weights of the Tutte start.
    pub tutte: TutteWeights,
    /// Newton parameters (`energy_scale` is overwritten when `mean_energy`).
    /// Default: [`NewtonParams::default`] with the filter policy
    /// [`FilterPolicy::TrustRegionNewton`] (the configured filter while the
    /// quadratic model is not trusted, the raw Hessian once it is; fewer
    /// iterations on every measured parameterisation,
    /// `docs/benchmarks/projection.md`) and `extrapolate` on (the same or
    /// fewer iterations on every measured parameterisation, same
    /// document, "Line-search extrapolation").
    pub newton: NewtonParams,
    /// How the element Hessians are projected (see [`Projection`]).
    pub projection: Projection,
}

impl Default for ParamOptions {
    fn default() -> Self {
        ParamOptions {
            normalize_area: true,
            mean_energy: true,
            tutte: TutteWeights::Uniform,
            newton: NewtonParams {
                filter_policy: FilterPolicy::TrustRegionNewton,
                extrapolate: true,
                ..NewtonParams::default()
            },
            projection: Projection::default(),
        }
    }
}

/// A computed parameterisation.
#[derive(Clone, Debug)]
pub struct Parameterization {
    /// One uv per vertex (in the normalised units if `normalize_area`).
    pub uv: Vec<[f64; 2]>,
    /// The Newton solve.
    pub result: NewtonResult,
    /// Triangles with signed uv area ≤ 0 at the end.
    pub flipped: usize,
    /// Factor applied to the 3D positions (1 without normalisation).
    pub position_scale: f64,
    /// Σ|q| of the (scaled) rest triangles.
    pub rest_area: f64,
    /// Seconds spent in the Tutte start.
    pub tutte_seconds: f64,
    /// Seconds spent building the solver (the shared vertex dissection,
    /// rest frames, pattern, colouring, symbolic analysis).
    pub setup_seconds: f64,
}

/// Machine-readable one-line summary of a parameterisation run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ParamSummary {
    pub mesh: String,
    pub energy: String,
    pub vertices: usize,
    pub triangles: usize,
    pub status: NewtonStatus,
    pub iterations: usize,
    /// Mean (or total, without `mean_energy`) energy at the Tutte start and at the end.
    pub initial_energy: f64,
    pub final_energy: f64,
    pub grad_inf: f64,
    pub flipped: usize,
    pub tutte_seconds: f64,
    pub setup_seconds: f64,
    /// Newton time split (assembly / factor / solve / line search / total).
    pub newton: TimeSplit,
}

impl Parameterization {
    /// Summary for reports (`mesh` and `energy` are labels).
    pub fn summary(&self, mesh: &str, energy: &str, triangles: usize) -> ParamSummary {
        ParamSummary {
            mesh: mesh.to_string(),
            energy: energy.to_string(),
            vertices: self.uv.len(),
            triangles,
            status: self.result.status.clone(),
            iterations: self.result.iterations,
            initial_energy: self.result.initial_energy,
            final_energy: self.result.energy,
            grad_inf: self.result.grad_inf,
            flipped: self.flipped,
            tutte_seconds: self.tutte_seconds,
            setup_seconds: self.setup_seconds,
            newton: self.result.times,
        }
    }
}

/// A parameterisation ready to solve: the solver over the (scaled) surface
/// and the Tutte start (steps 1–4 of the module docs).
pub struct ParamProblem {
    /// Projected Newton over the single elastic term `elastic`.
    pub solver: NewtonSolver<2>,
    /// The Tutte start, rescaled to the rest area.
    pub start: Vec<[f64; 2]>,
    /// The triangles.
    pub triangles: Vec<[usize; 3]>,
    /// Factor applied to the 3D positions (1 without normalisation).
    pub position_scale: f64,
    /// Σ|q| of the (scaled) rest triangles.
    pub rest_area: f64,
    /// Σ|q| of the triangles as given (before normalisation).
    pub input_area: f64,
    /// Seconds spent in the Tutte start.
    pub tutte_seconds: f64,
    /// Seconds spent building the solver (the shared vertex dissection,
    /// rest frames, pattern, colouring, symbolic analysis).
    pub setup_seconds: f64,
}

/// Build the solver and the Tutte start for `mesh` with energy `E`.
///
/// Errors: an empty mesh, a degenerate rest triangle, a mesh that is not a
/// disk ([`FemError::Tutte`]), or a Tutte start whose total signed area is
/// not positive ([`FemError::TutteArea`]: the start must be a bijection).
pub fn prepare<E: Energy<2> + ?Sized + 'static>(
    mesh: &TriMesh,
    energy: Arc<E>,
    opts: &ParamOptions,
) -> Result<ParamProblem, FemError> {
    if mesh.triangles.is_empty() {
        return Err(FemError::EmptyMesh);
    }
    let weights = opts.tutte;
    let (built, tutte) = std::thread::scope(|scope| {
        // the shared dissection reaches the Tutte thread once computed here,
        // while it checks the mesh and assembles its system; only for
        // symmetric weights, whose Tutte solve dissects anyway (with
        // mean-value weights, LU, the solver dissects its own groups if its
        // ordering is the geometric one)
        let (send, receive) = std::sync::mpsc::sync_channel::<Option<Arc<[usize]>>>(1);
        let tutte = scope.spawn(move || {
            let t1 = Instant::now();
            let uv = if weights.is_symmetric() {
                // a sender gone without sending (a panic) dissects here
                tutte_embedding_in_order(mesh, weights, || receive.recv().ok().flatten())
            } else {
                tutte_embedding(mesh, weights)
            };
            (uv, t1.elapsed().as_secs_f64())
        });
        let t0 = Instant::now();
        let order: Option<Arc<[usize]>> = weights
            .is_symmetric()
            .then(|| mesh_dissection(&mesh.positions, &mesh.triangles))
            .flatten()
            .map(Arc::from);
        // fails only if the Tutte thread has stopped already (a mesh it
        // rejects): nothing then waits for the order
        let _ = send.send(order.clone());
        let dissection_seconds = t0.elapsed().as_secs_f64();
        let built = build_solver(mesh, energy, opts, order.as_deref());
        let built = built.map(|(solver, scales, s)| (solver, scales, s + dissection_seconds));
        (built, tutte.join())
    });
    let (solver, scales, setup_seconds) = built?;
    let (uv, tutte_seconds) = match tutte {
        Ok(r) => r,
        // the Tutte thread panicked: hand the panic on unchanged
        Err(panic) => std::panic::resume_unwind(panic),
    };
    let t2 = Instant::now();
    let start = tutte_start(mesh, uv?, scales.rest_area)?;
    Ok(ParamProblem {
        solver,
        start,
        triangles: mesh.triangles.clone(),
        position_scale: scales.position_scale,
        rest_area: scales.rest_area,
        input_area: scales.input_area,
        tutte_seconds: tutte_seconds + t2.elapsed().as_secs_f64(),
        setup_seconds,
    })
}

/// The scale factors of [`ParamProblem`].
struct Scales {
    position_scale: f64,
    rest_area: f64,
    input_area: f64,
}

/// Steps 1–3 of the module docs: the elastic term over the (scaled)
/// surface and the Newton solver over it, with the seconds they took.
fn build_solver<E: Energy<2> + ?Sized + 'static>(
    mesh: &TriMesh,
    energy: Arc<E>,
    opts: &ParamOptions,
    dissection: Option<&[usize]>,
) -> Result<(NewtonSolver<2>, Scales, f64), FemError> {
    let t0 = Instant::now();
    let input = Elastic::<E, Tri>::surface(energy, &mesh.positions, &mesh.triangles)?;
    let input_area = input.total_measure();
    let position_scale = if opts.normalize_area {
        1.0 / input_area.sqrt()
    } else {
        1.0
    };
    // every rest frame was built, so each area is positive and finite with
    // finite squares (≤ ≈ 1e154): the total neither overflows nor vanishes
    // and the scale is finite and positive
    debug_assert!(position_scale.is_finite() && position_scale > 0.0);
    let elastic = if opts.normalize_area {
        input.scaled(position_scale)
    } else {
        input
    }
    .with_projection(opts.projection.resolve_for(2, opts.newton.filter_policy));
    let rest_area = elastic.total_measure();
    let mut newton = opts.newton.clone();
    if opts.mean_energy {
        newton.energy_scale = 1.0 / rest_area;
    }
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(elastic)];
    let dofs = DofMap::all_free(mesh.positions.len(), 2)?;
    let solver = match dissection {
        Some(d) => NewtonSolver::with_dissected_geometry(terms, dofs, newton, &mesh.positions, d),
        None => NewtonSolver::with_geometry(terms, dofs, newton, &mesh.positions),
    }?;
    let scales = Scales {
        position_scale,
        rest_area,
        input_area,
    };
    Ok((solver, scales, t0.elapsed().as_secs_f64()))
}

/// The Tutte embedding `uv` scaled so its signed area equals `rest_area`.
fn tutte_start(
    mesh: &TriMesh,
    mut uv: Vec<[f64; 2]>,
    rest_area: f64,
) -> Result<Vec<[f64; 2]>, FemError> {
    let uv_area: f64 = mesh
        .triangles
        .iter()
        .map(|&t| tri_signed_area(&uv, t))
        .sum();
    if !(uv_area.is_finite() && uv_area > 0.0) {
        return Err(FemError::TutteArea(uv_area));
    }
    let s = (rest_area / uv_area).sqrt();
    for p in &mut uv {
        *p = [p[0] * s, p[1] * s];
    }
    Ok(uv)
}

impl ParamProblem {
    /// Minimise from the Tutte start; `on_iteration` sees every accepted
    /// Newton step (record, current uv) and may stop the solve
    /// (`ControlFlow::Break`, status `Interrupted`). The problem stays
    /// usable afterwards (e.g. to evaluate its term at the result).
    pub fn solve_with(
        &mut self,
        on_iteration: impl FnMut(&IterationRecord, &[[f64; 2]]) -> ControlFlow<()>,
    ) -> Result<Parameterization, FemError> {
        let mut uv = self.start.clone();
        let result = self.solver.solve_with(&mut uv, on_iteration)?;
        let flipped = count_flipped(&uv, &self.triangles);
        Ok(Parameterization {
            uv,
            result,
            flipped,
            position_scale: self.position_scale,
            rest_area: self.rest_area,
            tutte_seconds: self.tutte_seconds,
            setup_seconds: self.setup_seconds,
        })
    }
}

/// Parameterise a disk-topology mesh with energy `E` (see the module docs):
/// [`prepare`], then [`ParamProblem::solve_with`] without a callback.
pub fn parameterize<E: Energy<2> + ?Sized + 'static>(
    mesh: &TriMesh,
    energy: Arc<E>,
    opts: &ParamOptions,
) -> Result<Parameterization, FemError> {
    prepare(mesh, energy, opts)?.solve_with(|_, _| ControlFlow::Continue(()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use ecc_runtime::energies::SymmetricDirichlet;

    fn prepare_sd(positions: Vec<[f64; 3]>, triangles: Vec<[usize; 3]>) -> Result<(), FemError> {
        let mesh = TriMesh::new(positions, triangles);
        prepare(
            &mesh,
            Arc::new(SymmetricDirichlet),
            &ParamOptions::default(),
        )
        .map(|_| ())
    }

    /// The Tutte solve runs beside the solver build: its errors and the
    /// build's keep their order (rest shape first, then the topology).
    #[test]
    fn errors_keep_their_order_with_the_concurrent_tutte_solve() {
        let tet = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let closed = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]];
        // a closed surface: no Tutte embedding
        let e = prepare_sd(tet.clone(), closed.clone()).unwrap_err();
        assert!(matches!(e, FemError::Tutte(_)), "{e}");
        // also a degenerate triangle: the rest-shape error wins, as before
        let mut p = tet;
        p.push([2.0, 0.0, 0.0]);
        let mut t = closed;
        t.push([0, 1, 4]);
        let e = prepare_sd(p, t).unwrap_err();
        assert!(
            matches!(e, FemError::DegenerateRest { element: 4, .. }),
            "{e}"
        );
        assert!(matches!(
            prepare_sd(Vec::new(), Vec::new()),
            Err(FemError::EmptyMesh)
        ));
    }

    /// The concurrent setup gives the start and problem of the sequential
    /// one: the Tutte embedding in the shared vertex dissection rescaled to
    /// the rest area, which is the one in the interior's own dissection to
    /// rounding.
    #[test]
    fn the_start_is_the_rescaled_tutte_embedding() {
        let mut mesh = ecc_mesh::disk_tri(4, 2.0);
        for p in &mut mesh.positions {
            p[2] = 0.1 * p[0] * p[1];
        }
        let opts = ParamOptions::default();
        let prob = prepare(&mesh, Arc::new(SymmetricDirichlet), &opts).unwrap();
        let order = mesh_dissection(&mesh.positions, &mesh.triangles).unwrap();
        let uv = tutte_embedding_in_order(&mesh, opts.tutte, || Some(order)).unwrap();
        let want = tutte_start(&mesh, uv, prob.rest_area).unwrap();
        assert_eq!(prob.start, want);
        let own = tutte_embedding(&mesh, opts.tutte).unwrap();
        let own = tutte_start(&mesh, own, prob.rest_area).unwrap();
        for (a, b) in own.iter().zip(&prob.start) {
            assert!((a[0] - b[0]).abs() < 1e-13 && (a[1] - b[1]).abs() < 1e-13);
        }
        assert!((prob.rest_area - 1.0).abs() < 1e-12);
        assert!(prob.tutte_seconds >= 0.0 && prob.setup_seconds >= 0.0);
    }
}
