//! Hostile scenes end to end: a solve that cannot succeed stops the run
//! with a report — exit status 1, `the run stopped early: <why> at frame
//! <n>` on stderr, the per-frame statuses in `summary.json` — and every
//! file written is complete and free of NaN/∞ (the frames before the stop
//! and the best iterate of the failed frame).

use std::fs;
use std::path::Path;
use std::process::Command;

fn sim(dir: &Path, scene: &str) -> (i32, String) {
    fs::write(dir.join("scene.toml"), scene).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args(["sim", "scene.toml", "-q", "--no-pictures", "-o", "out"])
        .current_dir(dir)
        .output()
        .expect("the ecc binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        !stderr.contains("panicked") && !stderr.contains("internal error"),
        "{stderr}"
    );
    (out.status.code().unwrap_or(-1), stderr)
}

/// Every output file parses and holds no NaN or infinity.
fn outputs_are_clean(dir: &Path) -> serde_json::Value {
    let out = dir.join("out");
    let mut frames = 0;
    for e in fs::read_dir(&out).unwrap().flatten() {
        let p = e.path();
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".obj") || name.ends_with(".vtk") {
            frames += 1;
            let mesh = ecc_mesh_read(&p);
            assert!(mesh, "{name} does not read back as a finite mesh");
        }
    }
    assert!(
        frames >= 2,
        "at least the initial frame and the stopped one"
    );
    let text = fs::read_to_string(out.join("summary.json")).unwrap();
    let s: serde_json::Value = serde_json::from_str(&text).expect("valid JSON");
    assert!(
        !text.contains("NaN") && !text.contains("Infinity"),
        "{text}"
    );
    s
}

/// The OBJ/VTK text has only finite numbers (the writers refuse NaN/∞, and
/// Rust prints them as `NaN` / `inf`).
fn ecc_mesh_read(p: &Path) -> bool {
    let text = fs::read_to_string(p).unwrap();
    !text.contains("NaN") && !text.split_whitespace().any(|w| w == "inf" || w == "-inf")
}

#[test]
fn an_energy_unbounded_below_stops_the_run_with_a_report() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("neg.psi"), "psi = -I2\n").unwrap();
    let (code, e) = sim(
        dir.path(),
        "frames = 2\n[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\npsi = \"neg.psi\"\n\
         [[effects.handles]]\nids = [0, 1, 2, 3]\n",
    );
    assert_eq!(code, 1, "{e}");
    assert!(
        e.contains("the run stopped early") && e.contains("at frame 1"),
        "{e}"
    );
    let s = outputs_are_clean(dir.path());
    assert!(
        s["stopped"].as_str().is_some_and(|w| w.contains("frame 1")),
        "{s}"
    );
    assert_eq!(s["converged_frames"], 0);
    let status = &s["solves"][0]["status"];
    assert!(status.is_string() && status != "Converged", "{status}");
}

#[test]
fn handles_that_force_an_inversion_of_a_barrier_energy_stop_the_run() {
    let dir = tempfile::tempdir().unwrap();
    // push the right end of an SD bar (a barrier) past its left end: no
    // uninverted configuration exists, the frame cannot be reached
    let (code, e) = sim(
        dir.path(),
        "frames = 1\n[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"sd\"\n\
         [[effects.handles]]\nbox = { min = [-2.1, -1, -1], max = [-1.9, 1, 1] }\n\
         [[effects.handles]]\nbox = { min = [1.9, -1, -1], max = [2.1, 1, 1] }\n\
         keys = [ { frame = 1, translate = [-4.5, 0, 0] } ]\n",
    );
    assert_eq!(code, 1, "{e}");
    assert!(
        e.contains("the run stopped early: frame 1: moving the handles inverts elements"),
        "{e}"
    );
    let s = outputs_are_clean(dir.path());
    assert!(s["stopped"].is_string(), "{s}");
    for f in s["frames"].as_array().unwrap() {
        assert_eq!(f["inverted"], 0, "no written frame is inverted: {f}");
    }
}

#[test]
fn a_time_step_too_small_for_f64_is_reported_with_its_term() {
    let dir = tempfile::tempdir().unwrap();
    let (code, e) = sim(
        dir.path(),
        "frames = 1\n[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"snh\"\n\
         [effects]\ninertia = { dt = 1e-300 }\ngravity = [0, -9.8, 0]\n",
    );
    assert_eq!(code, 1, "{e}");
    assert!(e.contains("non-finite energy in term `inertia`"), "{e}");
    let s = outputs_are_clean(dir.path());
    assert_eq!(s["solves"][0]["status"], "NonFinite", "{s}");
}
