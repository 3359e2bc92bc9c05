//! The fibre term: element derivatives through the Term interface, typed
//! errors, and the anisotropic response of a fibre-reinforced bar.

use std::sync::Arc;

use ecc_fem::{Elastic, FemError, Fibre, Filter, NewtonParams, NewtonSolver, Term, Tet, Tri};
use ecc_runtime::energies::{FibreArap, FibreStvk, StableNeoHookean};
use ecc_runtime::reference::{fd_gradient, fd_hessian};
use nalgebra::SVector;

/// A constant load on some vertices: e = −f · x_v (arity 1, zero Hessian).
struct Load {
    verts: Vec<usize>,
    force: [f64; 3],
}

impl Term<3> for Load {
    fn name(&self) -> &str {
        "load"
    }
    fn arity(&self) -> usize {
        1
    }
    fn stencils(&self) -> &[usize] {
        &self.verts
    }
    fn value(&self, s: usize, x: &[[f64; 3]]) -> f64 {
        let p = x[self.verts[s]];
        -(0..3).map(|i| self.force[i] * p[i]).sum::<f64>()
    }
    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; 3]],
        _f: Filter,
        g: &mut [f64],
        h: Option<&mut [f64]>,
    ) -> f64 {
        for (gi, fi) in g.iter_mut().zip(&self.force) {
            *gi = -fi;
        }
        if let Some(h) = h {
            h[..9].fill(0.0);
        }
        self.value(s, x)
    }
}

/// The tip displacement of a bar (fixed at x = −2, pulled at x = 2 along
/// `pull`) with an isotropic matrix and fibres along `fibre`.
fn tip_displacement(fibre: [f64; 3], pull: [f64; 3]) -> f64 {
    let mesh = ecc_mesh::bar_tet(1);
    let rest = mesh.positions.clone();
    let left: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0] < -1.99).collect();
    let right: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0] > 1.99).collect();
    let dirs = vec![fibre; mesh.tets.len()];
    let matrix =
        Elastic::<_, Tet>::new(Arc::new(StableNeoHookean::new(1.0, 5.0)), &rest, &mesh.tets)
            .unwrap();
    let fibres = Fibre::tets(Arc::new(FibreStvk { mu: 40.0 }), &rest, &mesh.tets, &dirs).unwrap();
    let per = 0.5 / right.len() as f64;
    let load = Load {
        verts: right.clone(),
        force: pull.map(|p| p * per),
    };
    let terms: Vec<Box<dyn Term<3>>> = vec![Box::new(matrix), Box::new(fibres), Box::new(load)];
    let mut solver = NewtonSolver::new(rest.len(), terms, &left, NewtonParams::default()).unwrap();
    let mut x = rest.clone();
    let r = solver.solve(&mut x).unwrap();
    assert!(r.converged(), "{:?}", r.status);
    let d: f64 = right
        .iter()
        .map(|&v| {
            (0..3)
                .map(|i| (x[v][i] - rest[v][i]) * pull[i])
                .sum::<f64>()
        })
        .sum();
    d / right.len() as f64
}

#[test]
fn fibres_make_the_bar_stiffer_along_them() {
    let along = tip_displacement([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
    let across = tip_displacement([0.0, 1.0, 0.0], [1.0, 0.0, 0.0]);
    let none = tip_displacement([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]);
    // Same load: fibres along the pull resist it; fibres across barely do.
    assert!(along > 0.0 && across > 0.0);
    assert!(along * 5.0 < across, "along {along}, across {across}");
    assert!(
        (across - none).abs() < 0.2 * none,
        "across {across}, other transverse {none}"
    );
}

#[test]
fn term_derivatives_match_differences() {
    let mesh = ecc_mesh::bar_tet(1);
    let rest = mesh.positions.clone();
    let dirs: Vec<[f64; 3]> = (0..mesh.tets.len())
        .map(|q| [1.0, 0.3 * (q as f64).sin(), 0.2])
        .collect();
    let term = Fibre::tets(Arc::new(FibreArap { mu: 2.0 }), &rest, &mesh.tets, &dirs).unwrap();
    assert_eq!(term.len(), mesh.tets.len());
    assert!((term.directions()[5].norm() - 1.0).abs() < 1e-15);
    let x: Vec<[f64; 3]> = rest
        .iter()
        .map(|p| [1.3 * p[0], p[1] + 0.1 * p[0], 0.8 * p[2]])
        .collect();
    for s in [0, term.len() / 2, term.len() - 1] {
        let st = &term.stencils()[4 * s..4 * s + 4];
        let flat = SVector::<f64, 12>::from_fn(|k, _| x[st[k / 3]][k % 3]);
        let e = |y: &SVector<f64, 12>| {
            let mut xx = x.clone();
            for k in 0..12 {
                xx[st[k / 3]][k % 3] = y[k];
            }
            term.value(s, &xx)
        };
        let mut g = [0.0; 12];
        let mut h = [0.0; 144];
        let v = term.evaluate(s, &x, Filter::None, &mut g, Some(&mut h));
        assert!((v - e(&flat)).abs() < 1e-14);
        let fg = fd_gradient(e, &flat, 1.0);
        let fh = fd_hessian(e, &flat, 1.0);
        for k in 0..12 {
            assert!(
                (g[k] - fg[k]).abs() < 1e-7 * fg.amax().max(1.0),
                "grad {s} {k}"
            );
            for l in 0..12 {
                assert!(
                    (h[k * 12 + l] - fh[(k, l)]).abs() < 1e-5 * fh.amax().max(1.0),
                    "hess {s}"
                );
            }
        }
    }
}

#[test]
fn bad_directions_and_meshes_are_typed_errors() {
    let rest = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]];
    let tris = [[0, 1, 2], [1, 3, 2]];
    let e = Arc::new(FibreStvk { mu: 1.0 });
    let err = Fibre::planar(e.clone(), &rest, &tris, &[[1.0, 0.0], [0.0, 0.0]])
        .err()
        .unwrap();
    assert!(
        matches!(err, FemError::BadFibre { element: 1, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("element 1"), "{err}");
    let err = Fibre::planar(e.clone(), &rest, &tris, &[[f64::NAN, 0.0], [1.0, 0.0]])
        .err()
        .unwrap();
    assert!(
        matches!(
            err,
            FemError::BadFibre {
                element: 0,
                reason: "not finite",
                ..
            }
        ),
        "{err}"
    );
    let err = Fibre::planar(e.clone(), &rest, &tris, &[[1.0, 0.0]])
        .err()
        .unwrap();
    assert!(
        matches!(
            err,
            FemError::LengthMismatch {
                expected: 2,
                got: 1,
                ..
            }
        ),
        "{err}"
    );
    let err = Fibre::planar(e.clone(), &rest, &[[0, 1, 9]], &[[1.0, 0.0]])
        .err()
        .unwrap();
    assert!(
        matches!(err, FemError::VertexOutOfRange { vertex: 9, .. }),
        "{err}"
    );
    let err = Fibre::planar(e.clone(), &rest, &[[0, 2, 1]], &[[1.0, 0.0]])
        .err()
        .unwrap();
    assert!(
        matches!(err, FemError::DegenerateRest { element: 0, .. }),
        "{err}"
    );
    // A planar fibre term next to an elastic one solves (2D path).
    let ok = Fibre::planar(e, &rest, &tris, &[[2.0, 0.0], [1.0, 1.0]]).unwrap();
    let el =
        Elastic::<_, Tri>::planar(Arc::new(StableNeoHookean::new(1.0, 5.0)), &rest, &tris).unwrap();
    let terms: Vec<Box<dyn Term<2>>> = vec![Box::new(el), Box::new(ok)];
    let mut solver = NewtonSolver::new(4, terms, &[0, 1], NewtonParams::default()).unwrap();
    let mut x = rest.to_vec();
    x[1][0] = 1.5;
    assert!(solver.solve(&mut x).unwrap().converged());
}
