//! A scene accepts a disk whose smallest triangle is a tiny but genuine
//! sliver (area 5.3e-12, quality 9e-6: refused before, when the tolerance
//! was relative to the mesh's bounding box), warns naming it, refuses it
//! with `[mesh] min_quality`, and refuses a degenerate one naming its id —
//! the same verdicts as the element library (runtime/fem/tests/mesh_quality.rs).

use ecc_scene::{RunOptions, RuntimeEnergies, SceneError, SceneFile, Silent, run_scene};

/// The ear fixture ([`ecc_mesh::disk_with_ear`]) as (positions, triangles,
/// the ear's id).
fn disk_with_ear(h: f64) -> (Vec<[f64; 3]>, Vec<[usize; 3]>, usize) {
    let (m, id) = ecc_mesh::disk_with_ear(h);
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
