//! Trust-region Newton's ratio ρ needs dᵀ H d with the raw Hessian at x.
//! When the step was solved with the raw Hessian (`Filter::None`) the
//! solver reads it off the assembled matrix, `Pattern::quadratic_form`
//! minus the diagonal shift, instead of a second pass over the elements
//! (`Assembler::raw_curvature`). This checks that identity on an indefinite
//! symmetric Dirichlet Hessian with fixed vertices.

use std::sync::Arc;

use ecc_fem::{Assembler, DofMap, Elastic, Filter, Term, Tri};
use ecc_runtime::energies::SymmetricDirichlet;

#[test]
fn the_assembled_raw_hessian_gives_the_elements_raw_curvature() {
    let mesh = ecc_mesh::disk_tri(6, 1.0);
    let rest: Vec<[f64; 3]> = mesh.positions.clone();
    let term =
        Elastic::<_, Tri>::surface(Arc::new(SymmetricDirichlet), &rest, &mesh.triangles).unwrap();
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(term)];
    let n = mesh.positions.len();
    // a stretched, sheared, slightly twisted uv: far from rest, so some
    // element Hessians are indefinite
    let x: Vec<[f64; 2]> = mesh
        .positions
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
    let dofs = DofMap::from_fixed_vertices(n, 2, &fixed).unwrap();
    let mut asm = Assembler::new(&terms, dofs).unwrap();
    let m = asm.dofs().n_unknowns();
    let scale = 0.37;
    let mut g = vec![0.0; m];
    let mut values = vec![0.0; asm.pattern().nnz()];
    asm.assemble(&terms, &x, scale, &mut g, Some((Filter::None, &mut values)))
        .unwrap();
    let d: Vec<f64> = (0..m).map(|i| (0.9 * i as f64).sin()).collect();
    let mut full = vec![0.0; 2 * n];
    asm.dofs().scatter(&d, &mut full);
    let dx: Vec<[f64; 2]> = full.chunks(2).map(|c| [c[0], c[1]]).collect();
    let slow = asm.raw_curvature(&terms, &x, &dx, scale);
    let fast = asm.pattern().quadratic_form(&values, &d, &mut Vec::new());
    let mut clamped = vec![0.0; values.len()];
    asm.assemble(
        &terms,
        &x,
        scale,
        &mut g,
        Some((Filter::Clamp, &mut clamped)),
    )
    .unwrap();
    let projected = asm.pattern().quadratic_form(&clamped, &d, &mut Vec::new());
    assert!(
        (fast - slow).abs() <= 1e-12 * slow.abs().max(1.0),
        "assembled {fast} vs element pass {slow}"
    );
    // the check can tell the raw Hessian from a projected one
    assert!(
        (projected - slow).abs() > 1e-6 * slow.abs(),
        "the clamp changed nothing along d: pick a harder x"
    );
}
