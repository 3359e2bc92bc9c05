//! `Elastic` overrides `Term::curvature` with `element_curvature` (the raw
//! dxᵀ H dx from the element's eigensystem, no element Hessian). Here
//! `Assembler::raw_curvature` with the override equals the generic default
//! (local Hessian with `Filter::None`, then dlᵀ H dl), reached through a
//! wrapper term that forwards everything except `curvature`, per stencil and
//! in total, for the `FSpace` and `Element` projections, in 2D and 3D,
//! with fixed vertices and (barrier) an inverted element.

use std::sync::Arc;

use ecc_fem::elastic::Projection;
use ecc_fem::{Assembler, DofMap, Elastic, Filter, Term, Tet, Tri};
use ecc_runtime::Energy;
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};

/// Forwards everything to `inner` but keeps the default `Term::curvature`.
struct Generic<const D: usize>(Box<dyn Term<D>>);

impl<const D: usize> Term<D> for Generic<D> {
    fn name(&self) -> &str {
        self.0.name()
    }
    fn arity(&self) -> usize {
        self.0.arity()
    }
    fn stencils(&self) -> &[usize] {
        self.0.stencils()
    }
    fn is_barrier(&self) -> bool {
        self.0.is_barrier()
    }
    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        self.0.value(s, x)
    }
    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        filter: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        self.0.evaluate(s, x, filter, grad, hess)
    }
}

/// ‖H_s‖max ‖dl_s‖² of stencil s (raw Hessian): the scale of its rounding.
fn stencil_scale<const D: usize>(t: &dyn Term<D>, s: usize, x: &[[f64; D]], d: &[[f64; D]]) -> f64 {
    let k = t.arity() * D;
    let (mut g, mut h) = (vec![0.0; k], vec![0.0; k * k]);
    t.evaluate(s, x, Filter::None, &mut g, Some(&mut h));
    let st = &t.stencils()[s * t.arity()..(s + 1) * t.arity()];
    let dl2: f64 = st.iter().flat_map(|&v| d[v]).map(|c| c * c).sum();
    h.iter().fold(0.0f64, |m, v| m.max(v.abs())) * dl2
}

/// dlᵀ H dl of stencil s with its local Hessian filtered by `filter`.
fn local_form<const D: usize>(
    t: &dyn Term<D>,
    s: usize,
    x: &[[f64; D]],
    d: &[[f64; D]],
    filter: Filter,
) -> f64 {
    let k = t.arity() * D;
    let (mut g, mut h) = (vec![0.0; k], vec![0.0; k * k]);
    t.evaluate(s, x, filter, &mut g, Some(&mut h));
    let st = &t.stencils()[s * t.arity()..(s + 1) * t.arity()];
    let dl: Vec<f64> = st.iter().flat_map(|&v| d[v]).collect();
    (0..k)
        .map(|a| dl[a] * (0..k).map(|b| h[a * k + b] * dl[b]).sum::<f64>())
        .sum()
}

/// What [`compare`] measured.
struct Outcome {
    /// `raw_curvature` with the override (scale 1).
    total: f64,
    /// Σ_s dlᵀ H_s dl with Clamp-filtered local Hessians (finite stencils).
    clamped: f64,
    /// Stencils whose curvature is not finite.
    infinite: usize,
}

/// The override against the default, per stencil (to 1e-12 of
/// ‖H_s‖max‖dl_s‖²) and through `Assembler::raw_curvature` (to 1e-12 of the
/// sum of those); `make` builds the same term twice.
fn compare<const D: usize>(
    make: impl Fn() -> Box<dyn Term<D>>,
    x: &[[f64; D]],
    d: &[[f64; D]],
    fixed: &[usize],
) -> Outcome {
    let fast: Vec<Box<dyn Term<D>>> = vec![make()];
    let slow: Vec<Box<dyn Term<D>>> = vec![Box::new(Generic(make()))];
    let (mut total_scale, mut infinite, mut clamped) = (0.0, 0, 0.0);
    for s in 0..fast[0].n_stencils() {
        let got = fast[0].curvature(s, x, d);
        let want = slow[0].curvature(s, x, d);
        if !want.is_finite() {
            assert_eq!((got, want), (f64::INFINITY, f64::INFINITY), "stencil {s}");
            infinite += 1;
            continue;
        }
        let scale = stencil_scale(&*slow[0], s, x, d);
        assert!(
            (got - want).abs() <= 1e-12 * scale,
            "stencil {s}: {got} vs {want} (scale {scale})"
        );
        total_scale += scale;
        clamped += local_form(&*slow[0], s, x, d, Filter::Clamp);
    }
    let dofs = || DofMap::from_fixed_vertices(x.len(), D, fixed).unwrap();
    let by_override = Assembler::new(&fast, dofs())
        .unwrap()
        .raw_curvature(&fast, x, d, 0.5);
    let by_default = Assembler::new(&slow, dofs())
        .unwrap()
        .raw_curvature(&slow, x, d, 0.5);
    if infinite == 0 {
        assert!(
            (by_override - by_default).abs() <= 0.5e-12 * total_scale,
            "{by_override} vs {by_default}"
        );
    } else {
        assert_eq!((by_override, by_default), (f64::INFINITY, f64::INFINITY));
    }
    Outcome {
        total: 2.0 * by_override,
        clamped,
        infinite,
    }
}

/// A direction that is zero on the fixed vertices.
fn direction<const D: usize>(n: usize, fixed: &[usize]) -> Vec<[f64; D]> {
    (0..n)
        .map(|v| {
            if fixed.contains(&v) {
                [0.0; D]
            } else {
                std::array::from_fn(|i| (0.9 * (v * D + i) as f64).sin())
            }
        })
        .collect()
}

const PROJECTIONS: [Projection; 2] = [Projection::FSpace, Projection::Element];

/// The elastic term of `energy` over the surface triangles, projected by
/// `projection`.
fn surface<E: Energy<2> + 'static>(
    energy: E,
    rest: &[[f64; 3]],
    tris: &[[usize; 3]],
    projection: Projection,
) -> Box<dyn Term<2>> {
    Box::new(
        Elastic::<_, Tri>::surface(Arc::new(energy), rest, tris)
            .unwrap()
            .with_projection(projection),
    )
}

#[test]
fn triangles_override_equals_the_default_for_both_projections() {
    let mesh = ecc_mesh::disk_tri(6, 1.0);
    let rest = mesh.positions.clone();
    let tris = mesh.triangles.clone();
    // stretched, sheared, slightly twisted: far from rest, indefinite elements
    let x: Vec<[f64; 2]> = rest
        .iter()
        .map(|p| {
            let (u, v) = (p[0], p[1]);
            [
                1.6 * u + 0.4 * v + 0.2 * (3.0 * v).sin(),
                0.7 * v - 0.1 * u * u,
            ]
        })
        .collect();
    let fixed = [0usize, 1];
    let d = direction::<2>(x.len(), &fixed);
    for projection in PROJECTIONS {
        let sd = || surface(SymmetricDirichlet, &rest, &tris, projection);
        let arap = || surface(Arap, &rest, &tris, projection);
        for (name, make) in [
            ("sd", &sd as &dyn Fn() -> Box<dyn Term<2>>),
            ("arap", &arap),
        ] {
            let out = compare(make, &x, &d, &fixed);
            assert_eq!(out.infinite, 0, "{name} {projection:?}");
            // SD's Hessians are indefinite here (ARAP's are not: σ1 + σ2 > 2),
            // so the comparison sees the raw Hessian, not a projected one
            if name == "sd" {
                assert!(
                    (out.clamped - out.total).abs() > 1e-6 * out.total.abs(),
                    "{projection:?}: the clamp changed nothing along d"
                );
            }
        }
    }
}

#[test]
fn an_inverted_barrier_element_is_infinite_both_ways() {
    let mesh = ecc_mesh::disk_tri(2, 1.0);
    let rest = mesh.positions.clone();
    let tris = mesh.triangles.clone();
    // mirror the centre vertex far across: its fan inverts
    let mut x: Vec<[f64; 2]> = rest.iter().map(|p| [p[0], p[1]]).collect();
    x[0] = [3.0, 0.2];
    let d = direction::<2>(x.len(), &[]);
    for projection in PROJECTIONS {
        let sd = || surface(SymmetricDirichlet, &rest, &tris, projection);
        let out = compare(sd, &x, &d, &[]);
        assert!(out.infinite > 0, "{projection:?}: nothing inverted");
        assert_eq!(out.total, f64::INFINITY);
    }
}

#[test]
fn tetrahedra_override_equals_the_default_for_both_projections() {
    let mesh = ecc_mesh::box_tet(2, 2, 2, [1.0, 1.0, 1.0]);
    let rest = mesh.positions.clone();
    let tets = mesh.tets.clone();
    let x: Vec<[f64; 3]> = rest
        .iter()
        .map(|p| {
            [
                1.4 * p[0] + 0.3 * p[1] + 0.1 * (2.0 * p[2]).sin(),
                0.8 * p[1] - 0.2 * p[0] * p[2],
                0.6 * p[2] + 0.25 * p[0],
            ]
        })
        .collect();
    let fixed = [0usize];
    let d = direction::<3>(x.len(), &fixed);
    for projection in PROJECTIONS {
        let snh = || -> Box<dyn Term<3>> {
            let e = Arc::new(StableNeoHookean::new(1.0, 10.0));
            Box::new(
                Elastic::<_, Tet>::new(e, &rest, &tets)
                    .unwrap()
                    .with_projection(projection),
            )
        };
        let out = compare(snh, &x, &d, &fixed);
        assert_eq!(out.infinite, 0, "{projection:?}");
        assert!(out.total.is_finite() && out.total != 0.0);
    }
}
