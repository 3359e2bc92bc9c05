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
    assert_eq!(Projection::default(), Projection::Auto);
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

/// `Auto` resolves by dimension and filter policy: `Element` on triangles
/// unless the policy is trust-region Newton, `FSpace` otherwise; explicit
/// choices are kept under every policy.
#[test]
fn auto_projection_follows_the_dimension_and_the_filter_policy() {
    use ecc_fem::FilterPolicy;
    let policies = [
        FilterPolicy::Fixed,
        FilterPolicy::TrustRegion,
        FilterPolicy::TrustRegionNewton,
    ];
    for policy in policies {
        let tri = if policy == FilterPolicy::TrustRegionNewton {
            Projection::FSpace
        } else {
            Projection::Element
        };
        assert_eq!(Projection::Auto.resolve_for(2, policy), tri, "{policy:?}");
        assert_eq!(Projection::Auto.resolve_for(3, policy), Projection::FSpace);
        for p in [
            Projection::FSpace,
            Projection::Element,
            Projection::hybrid(),
        ] {
            for d in [2, 3] {
                assert_eq!(p.resolve_for(d, policy), p);
            }
        }
    }
}

/// `Auto` is `Element` on triangles and `FSpace` on tetrahedra, bit for bit
/// (the fixed policy an `Elastic` term assumes).
#[test]
fn auto_projection_is_element_for_triangles_and_f_space_for_tets() {
    assert_eq!(Projection::Auto.resolve(2), Projection::Element);
    assert_eq!(Projection::Auto.resolve(3), Projection::FSpace);
    assert_eq!(Projection::Auto.name(), "auto");
    let (rest, tris, x) = problem();
    let make = |p| {
        Elastic::<Arap, Tri>::planar(Arc::new(Arap), &rest, &tris)
            .unwrap()
            .with_projection(p)
    };
    let (auto, element) = (make(Projection::Auto), make(Projection::Element));
    let fspace = make(Projection::FSpace);
    for s in 0..tris.len() {
        let a = hessian(&auto, s, &x, Filter::Clamp);
        assert_eq!(a, hessian(&element, s, &x, Filter::Clamp), "triangle {s}");
        assert_ne!(a, hessian(&fspace, s, &x, Filter::Clamp), "triangle {s}");
    }
    // A skewed tet compressed and sheared (ARAP indefinite): Auto = F-space.
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.1, 0.0],
        [0.2, 0.8, 0.1],
        [0.3, 0.1, 1.4],
    ];
    let f = [[0.45, 0.35, 0.1], [-0.2, 0.5, 0.3], [0.1, -0.3, 0.6]];
    let y: Vec<[f64; 3]> = p
        .iter()
        .map(|q| std::array::from_fn(|i| (0..3).map(|j| f[i][j] * q[j]).sum()))
        .collect();
    let tet = |proj| {
        Elastic::<Arap, ecc_fem::Tet>::new(Arc::new(Arap), &p, &[[0, 1, 2, 3]])
            .unwrap()
            .with_projection(proj)
    };
    let h = |t: &Elastic<Arap, ecc_fem::Tet>, filter| {
        let mut g = [0.0; 12];
        let mut h = [0.0; 144];
        t.evaluate(0, &y, filter, &mut g, Some(&mut h));
        h
    };
    let (auto, fspace) = (tet(Projection::Auto), tet(Projection::FSpace));
    assert_ne!(
        h(&fspace, Filter::None),
        h(&fspace, Filter::Clamp),
        "indefinite"
    );
    assert_eq!(h(&auto, Filter::Clamp), h(&fspace, Filter::Clamp));
    assert_ne!(
        h(&tet(Projection::Element), Filter::Clamp),
        h(&fspace, Filter::Clamp)
    );
}
