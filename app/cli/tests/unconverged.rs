//! A run whose frames did not converge is not a success: `ecc sim` writes
//! every file, says what to change and exits 3 (`summary.json` has
//! `"status": "unconverged"`), unless `--allow-unconverged` (exit 0, with
//! the warning). Before, it only warned and exited 0.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};

fn ecc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args(args)
        .output()
        .expect("the ecc binary runs")
}

/// A bar twisted by 90° per frame with one Newton step per solve: it
/// cannot converge.
const SCENE: &str = r#"frames = 2

[mesh]
generate = "bar"
resolution = 1

[energy]
name = "arap"

[[effects.handles]]
plane = { point = [-1.9, 0, 0], normal = [-1, 0, 0] }

[[effects.handles]]
plane = { point = [1.9, 0, 0], normal = [1, 0, 0] }
keys = [ { frame = 2, rotate = [180, 0, 0] } ]

[solver]
max_iters = 1
"#;

fn run(dir: &Path, extra: &[&str]) -> Output {
    fs::write(dir.join("scene.toml"), SCENE).unwrap();
    let scene = dir.join("scene.toml");
    let out = dir.join("out");
    let mut args = vec![
        "sim",
        scene.to_str().unwrap(),
        "-q",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    ecc(&args)
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&fs::read(dir.join("out/summary.json")).unwrap()).unwrap()
}

fn all_files_written(dir: &Path) {
    for f in [
        "frame_0000.obj",
        "frame_0002.obj",
        "frame_0002.vtk",
        "result.png",
        "convergence.png",
        "summary.json",
    ] {
        assert!(dir.join("out").join(f).is_file(), "{f} missing");
    }
}

#[test]
fn an_unconverged_run_exits_3_and_says_what_to_change() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(dir.path(), &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(3), "{err}");
    assert!(err.contains("frame(s) did not converge"), "{err}");
    assert!(err.contains("MaxIterations"), "{err}");
    assert!(
        err.contains("error: 2 of 2 frame(s) did not converge"),
        "{err}"
    );
    assert!(err.contains("raise `[solver] max_iters`"), "{err}");
    assert!(err.contains("--allow-unconverged"), "{err}");
    all_files_written(dir.path());
    let s = summary(dir.path());
    assert_eq!(s["status"], "unconverged");
    assert_eq!(s["converged_frames"], 0);
    assert!(s["stopped"].is_null());
}

#[test]
fn allow_unconverged_exits_0_with_the_warning() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(dir.path(), &["--allow-unconverged"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(0), "{err}");
    assert!(
        err.contains("warning: 2 frame(s) did not converge"),
        "{err}"
    );
    all_files_written(dir.path());
    assert_eq!(summary(dir.path())["status"], "unconverged");
}

#[test]
fn a_converged_run_says_so() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("scene.toml"),
        SCENE.replace("max_iters = 1", "max_iters = 500"),
    )
    .unwrap();
    let scene = dir.path().join("scene.toml");
    let out = dir.path().join("out");
    let o = ecc(&[
        "sim",
        scene.to_str().unwrap(),
        "-q",
        "--no-pictures",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(summary(dir.path())["status"], "converged");
}
