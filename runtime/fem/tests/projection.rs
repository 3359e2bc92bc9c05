//! The elastic term's `Projection`: F-space = `element_eval`'s Hessian,
//! `Element` = the numeric projection of the raw element Hessian, `Hybrid`
//! = `Element` exactly on the elements with cond(M) above the threshold.

use std::sync::Arc;

use ecc_fem::elastic::{HYBRID_MIN_COND, Projection};
use ecc_fem::{Elastic, Filter, Term, Tri};
use ecc_runtime::energies::Arap;
use ecc_runtime::reference::project_psd_numeric;
use nalgebra::SMatrix;

/// One near-equilateral and one needle triangle, compressed and sheared so
/// that ARAP's Hessian is indefinite on both.
/// Rest positions, triangles, deformed positions.
type Problem = (Vec<[f64; 2]>, Vec<[usize; 3]>, Vec<[f64; 2]>);

fn problem() -> Problem {
    let rest = vec![[0.0, 0.0], [1.0, 0.0], [0.5, 0.85], [3.0, 0.1]];
    let tris = vec![[0, 1, 2], [1, 3, 2]];
    let x = rest
        .iter()
        .map(|p| [0.2 * p[0] + 0.5 * p[1], -0.3 * p[0] + 0.1 * p[1]])
        .collect();
    (rest, tris, x)
}

fn hessian(
    term: &Elastic<Arap, Tri>,
    s: usize,
    x: &[[f64; 2]],
    filter: Filter,
) -> SMatrix<f64, 6, 6> {
    let mut g = [0.0; 6];
    let mut h = [0.0; 36];
    term.evaluate(s, x, filter, &mut g, Some(&mut h));
    SMatrix::from_column_slice(&h)
}

#[test]
fn projections_of_the_elastic_term() {
    let (rest, tris, x) = problem();
    let make = |p| {
        Elastic::<Arap, Tri>::planar(Arc::new(Arap), &rest, &tris)
            .unwrap()
            .with_projection(p)
    };
    let (fspace, element) = (make(Projection::FSpace), make(Projection::Element));
    let hybrid = make(Projection::hybrid());
    assert_eq!(Projection::default(), Projection::FSpace);
    let conds: Vec<f64> = fspace
        .rest()
        .iter()
        .map(|r| r.congruence().cond())
        .collect();
    assert!(
        conds[0] < HYBRID_MIN_COND && conds[1] > HYBRID_MIN_COND,
        "{conds:?}"
    );
    for (s, &cond) in conds.iter().enumerate() {
        let raw = hessian(&fspace, s, &x, Filter::None);
        let f = hessian(&fspace, s, &x, Filter::Clamp);
        let e = hessian(&element, s, &x, Filter::Clamp);
        let h = hessian(&hybrid, s, &x, Filter::Clamp);
        assert_ne!(raw, f, "element {s} must be indefinite");
        let want = project_psd_numeric(&raw, Filter::Clamp);
        let scale = raw.amax();
        assert!(
            (e - want).amax() < 1e-10 * scale,
            "element {s}: exact projection"
        );
        assert_eq!(h, if cond > HYBRID_MIN_COND { e } else { f }, "hybrid {s}");
        // the raw Hessian is the same whatever the projection
        assert_eq!(hessian(&element, s, &x, Filter::None), raw);
    }
    // On the needle the F-space projection is not the exact one.
    let f1 = hessian(&fspace, 1, &x, Filter::Clamp);
    let e1 = hessian(&element, 1, &x, Filter::Clamp);
    assert!((f1 - e1).amax() > 1e-6 * e1.amax());
}
