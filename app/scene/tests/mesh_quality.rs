//! A scene accepts a disk whose smallest triangle is a tiny but genuine
//! sliver (area 5.3e-12, quality 9e-6: refused before, when the tolerance
//! was relative to the mesh's bounding box), warns naming it, refuses it
//! with `[mesh] min_quality`, and refuses a degenerate one naming its id —
//! the same verdicts as the element library (runtime/fem/tests/mesh_quality.rs).

use ecc_scene::{RunOptions, RuntimeEnergies, SceneError, SceneFile, Silent, run_scene};

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

fn obj(p: &[[f64; 3]], tris: &[[usize; 3]]) -> String {
    let mut s = String::new();
    for x in p {
        s += &format!("v {:e} {:e} {:e}\n", x[0], x[1], x[2]);
    }
    for t in tris {
        s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

/// Dry-run a planar deformation of the disk (`h`: the ear's height) with
/// `extra` lines in [mesh], or a parameterisation of it as a surface.
fn run(h: f64, extra: &str, param: bool) -> (Result<ecc_scene::RunReport, SceneError>, usize) {
    let dir = tempfile::tempdir().unwrap();
    let (p, tris, ear) = disk_with_ear(h);
    std::fs::write(dir.path().join("disk.obj"), obj(&p, &tris)).unwrap();
    let effects = if param {
        "[effects.parameterize]\n"
    } else {
        "[[effects.handles]]\nids = [0, 1]\n"
    };
    let text = format!(
        "[mesh]\nfile = \"disk.obj\"\n{extra}\n[energy]\nname = \"{}\"\n\n{effects}",
        if param { "sd" } else { "arap" }
    );
    let f = SceneFile::parse(&text, "scene.toml", dir.path()).unwrap();
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    (run_scene(&f, &RuntimeEnergies, &opts, &mut Silent), ear)
}

#[test]
fn a_tiny_genuine_sliver_is_accepted_with_a_warning_naming_it() {
    for param in [false, true] {
        let (r, ear) = run(1.4e-8, "", param);
        let report = r.unwrap_or_else(|e| panic!("param {param}: {e}"));
        let w = &report.summary.warnings;
        assert!(
            w.iter().any(|w| w.contains("1 sliver element")
                && w.contains(&format!("the worst is element {ear} (9."))),
            "{w:?}"
        );
    }
}

#[test]
fn min_quality_refuses_it_naming_it() {
    let (r, ear) = run(1.4e-8, "min_quality = 1e-5", false);
    let e = r.expect_err("refused");
    assert_eq!(e.key(), Some("mesh.file"));
    let m = e.to_string();
    assert!(
        m.contains(&format!("below the minimum 1e-5: elements {ear}")),
        "{m}"
    );
    assert!(m.contains("lower or remove `min_quality` in [mesh]"), "{m}");
    for bad in ["-1", "nan", "inf"] {
        let (r, _) = run(1.4e-8, &format!("min_quality = {bad}"), false);
        let e = r.expect_err("refused");
        assert_eq!(e.key(), Some("mesh.min_quality"), "{e}");
    }
}

#[test]
fn a_degenerate_ear_is_refused_naming_it() {
    for param in [false, true] {
        let (r, ear) = run(0.0, "", param);
        let m = r.expect_err("refused").to_string();
        assert!(m.contains(&format!("element {ear} is degenerate")), "{m}");
    }
}
