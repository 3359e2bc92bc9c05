//! One scale-invariant rest-shape criterion: ecc-mesh validation and the
//! element library (`ecc_runtime::Rest`, used by every elastic term and the
//! parameterisation) judge each element against its own longest edge, so
//! they accept and refuse the same elements. A disk with a tiny but genuine
//! sliver (area 5.3e-12, quality 9e-6) was refused by validation when its
//! tolerance was relative to the whole mesh's bounding box.

use ecc_mesh::{TriMesh, ValidationError, ValidationOptions, validate_tri};
use ecc_runtime::Rest;

/// The ear fixture ([`ecc_mesh::disk_with_ear`]) as (positions, triangles,
/// the ear's id).
fn disk_with_ear(h: f64) -> (Vec<[f64; 3]>, Vec<[usize; 3]>, usize) {
    let (m, id) = ecc_mesh::disk_with_ear(h);
    (m.positions, m.triangles, id)
}

/// Whether the element library accepts every triangle (planar and as a
/// surface in 3D); the first refused id otherwise.
fn library_refuses(p: &[[f64; 3]], tris: &[[usize; 3]]) -> Option<usize> {
    tris.iter().position(|t| {
        let q = t.map(|v| p[v]);
        let planar = Rest::<2>::new(q.map(|x| [x[0], x[1]])).is_err();
        let surface = Rest::<2>::from_3d(q).is_err();
        assert_eq!(planar, surface, "planar and surface rules agree");
        planar
    })
}

#[test]
fn the_two_rules_are_one() {
    assert_eq!(
        ecc_mesh::DEGENERATE_REL_TOL,
        ecc_runtime::element::DEGENERATE_REL_TOL
    );
}

#[test]
fn a_tiny_genuine_sliver_is_accepted_with_a_warning_naming_it() {
    let (p, tris, ear) = disk_with_ear(1.4e-8);
    assert_eq!(library_refuses(&p, &tris), None);
    let bbox = TriMesh::new(p.clone(), tris.clone()).bbox_diagonal();
    let area = TriMesh::new(p.clone(), tris.clone()).area(ear).unwrap();
    assert!(
        area < 1e-12 * bbox * bbox,
        "below the old whole-mesh tolerance: {area:e}"
    );
    for planar in [true, false] {
        let m = TriMesh::new(p.clone(), tris.clone());
        let v = validate_tri(m, planar, &ValidationOptions::default()).unwrap();
        assert_eq!(v.warnings.len(), 1, "{:?}", v.warnings);
        let w = &v.warnings[0];
        assert!(
            w.starts_with("1 sliver element (rest area ÷ longest edge² below 1e-5): "),
            "{w}"
        );
        assert!(
            w.contains(&format!("the worst is element {ear} (9.")),
            "{w}"
        );
    }
    // a minimum quality turns it into an error naming it
    let strict = ValidationOptions {
        min_quality: 1e-5,
        ..Default::default()
    };
    let e = validate_tri(TriMesh::new(p, tris), true, &strict).unwrap_err();
    assert!(
        matches!(&e, ValidationError::LowQualityElements { count: 1, worst, first, .. }
            if *worst == ear && first == &vec![ear]),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .contains(&format!("elements {ear}; the worst is element {ear}")),
        "{e}"
    );
}

#[test]
fn a_degenerate_ear_is_refused_by_both_naming_it() {
    let (p, tris, ear) = disk_with_ear(0.0);
    assert_eq!(library_refuses(&p, &tris), Some(ear));
    for planar in [true, false] {
        let m = TriMesh::new(p.clone(), tris.clone());
        let e = validate_tri(m, planar, &ValidationOptions::default()).unwrap_err();
        assert!(
            matches!(e, ValidationError::DegenerateElement { element, .. } if element == ear),
            "{e:?}"
        );
        assert!(
            e.to_string()
                .starts_with(&format!("element {ear} is degenerate")),
            "{e}"
        );
    }
}

#[test]
fn a_scaled_mesh_gives_the_same_verdicts() {
    // scale invariance: the verdicts do not depend on the units
    for s in [1e-6, 1e6] {
        let (p, tris, _) = disk_with_ear(1.4e-8);
        let p: Vec<[f64; 3]> = p.iter().map(|x| x.map(|c| c * s)).collect();
        assert_eq!(library_refuses(&p, &tris), None);
        let v = validate_tri(TriMesh::new(p, tris), true, &ValidationOptions::default());
        assert_eq!(v.map(|v| v.warnings.len()).ok(), Some(1));
    }
}
