//! One scale-invariant rest-shape criterion: ecc-mesh validation and the
//! element library (`ecc_runtime::Rest`, used by every elastic term and the
//! parameterisation) judge each element against its own longest edge, so
//! they accept and refuse the same elements. A disk with a tiny but genuine
//! sliver (area 5.3e-12, quality 9e-6) was refused by validation when its
//! tolerance was relative to the whole mesh's bounding box.

use ecc_mesh::{TriMesh, ValidationError, ValidationOptions, validate_tri};
use ecc_runtime::Rest;

/// `disk_tri(rings, 1)` with a tiny ear on its boundary: boundary edge
/// (a, b) of triangle T is split at m = a + ε(b − a) (T becomes (a, m, c)
/// and (m, b, c)) and the ear (a, p, m) is added outside, p at height `h`
/// over the middle of am. With |am| ≈ 7.7e-4 and h = 1.4e-8 the ear has
/// area ≈ 5.3e-12 (below 1e-12 × the bounding-box diagonal² ≈ 8e-12, the
/// old whole-mesh tolerance) and quality area ÷ longest edge² ≈ 9e-6: a
/// genuine sliver. `h = 0` puts p on am: a degenerate ear. Returns
/// (positions, triangles, the ear's id).
fn disk_with_ear(h: f64) -> (Vec<[f64; 3]>, Vec<[usize; 3]>, usize) {
    let mut m = ecc_mesh::disk_tri(6, 1.0);
    let lp = ecc_mesh::boundary_loops(&m.triangles).unwrap();
    let (a, b) = (lp[0][0], lp[0][1]);
    let t = m
        .triangles
        .iter()
        .position(|t| t.contains(&a) && t.contains(&b))
        .unwrap();
    let (pa, pb) = (m.positions[a], m.positions[b]);
    let ab = ((pb[0] - pa[0]).powi(2) + (pb[1] - pa[1]).powi(2)).sqrt();
    let eps = 7.7e-4 / ab;
    let pm = [
        pa[0] + eps * (pb[0] - pa[0]),
        pa[1] + eps * (pb[1] - pa[1]),
        0.0,
    ];
    let mid = [(pa[0] + pm[0]) / 2.0, (pa[1] + pm[1]) / 2.0];
    let r = (mid[0] * mid[0] + mid[1] * mid[1]).sqrt();
    let pp = [mid[0] + h * mid[0] / r, mid[1] + h * mid[1] / r, 0.0];
    let (im, ip) = (m.positions.len(), m.positions.len() + 1);
    m.positions.push(pm);
    m.positions.push(pp);
    let tri = m.triangles[t];
    m.triangles[t] = tri.map(|v| if v == b { im } else { v });
    m.triangles.push(tri.map(|v| if v == a { im } else { v }));
    let signed = |t: [usize; 3]| {
        let (p, q, s) = (m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
        (q[0] - p[0]) * (s[1] - p[1]) - (q[1] - p[1]) * (s[0] - p[0])
    };
    let ear = if signed([a, ip, im]) >= 0.0 {
        [a, ip, im]
    } else {
        [a, im, ip]
    };
    m.triangles.push(ear);
    let id = m.triangles.len() - 1;
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
