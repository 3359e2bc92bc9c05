//! `ecc sim` / `ecc demo` end to end: outputs, `.psi` energies, errors.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};

fn ecc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args(args)
        .output()
        .expect("the ecc binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&fs::read(dir.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn demo_writes_frames_pictures_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("demo");
    let o = ecc(&[
        "demo",
        "--frames",
        "2",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("demo: 2 frame(s)"), "{stdout}");
    for f in [
        "frame_0000.obj",
        "frame_0002.vtk",
        "result.png",
        "convergence.png",
        "summary.json",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    let png = fs::read(out.join("result.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let s = summary(&out);
    assert_eq!(s["mode"], "quasi_static");
    assert_eq!(s["terms"].as_array().unwrap().len(), 1);
    assert_eq!(s["counters"]["mass_matrix_builds"], 0);
    assert_eq!(s["converged_frames"], 2);
    // `ecc sim` without a scene is the demo
    let out2 = dir.path().join("sim");
    let o = ecc(&[
        "sim",
        "--frames",
        "1",
        "-q",
        "--no-pictures",
        "-o",
        out2.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(summary(&out2)["scene"], "demo");
    assert!(!out2.join("result.png").exists());
}

#[test]
fn psi_energy_is_interpreted_and_stats_list_terms() {
    let dir = tempfile::tempdir().unwrap();
    let psi = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../energies/psi/arap.psi");
    let scene = dir.path().join("disk.toml");
    fs::write(
        &scene,
        format!(
            "frames = 2\n[mesh]\ngenerate = \"disk\"\nrings = 3\n[energy]\npsi = \"{}\"\n\
             [effects]\ngravity = [0, -0.1]\n[[effects.handles]]\nids = [0]\n\
             [output]\nformats = []\npictures = false\n",
            psi.display()
        ),
    )
    .unwrap();
    let o = ecc(&[
        "sim",
        scene.to_str().unwrap(),
        "--quiet",
        "--stats",
        "--json",
        "-o",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(s["energy"]["name"], "arap");
    let terms: Vec<&str> = s["terms"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    assert_eq!(terms, ["elastic", "gravity"]);
    assert!(stderr(&o).contains("terms evaluated"), "{}", stderr(&o));
}

#[test]
fn scene_errors_name_file_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    fs::write(
        &scene,
        "[mesh]\ngenerate = \"bar\"\n[effects]\ngravty = [0, -9.8, 0]\n[energy]\nname = \"arap\"\n",
    )
    .unwrap();
    let o = ecc(&["sim", scene.to_str().unwrap(), "-q"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("bad.toml:4:1: unknown key `gravty` in [effects]; did you mean `gravity`?"),
        "{e}"
    );

    fs::write(
        &scene,
        "[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"stable_neohooken\"\n",
    )
    .unwrap();
    let o = ecc(&[
        "sim",
        scene.to_str().unwrap(),
        "-q",
        "-o",
        dir.path().join("o").to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        e.contains("bad.toml:5:1: `energy.name`: unknown energy `stable_neohooken`"),
        "{e}"
    );

    fs::write(
        &scene,
        "[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"mips\"\n",
    )
    .unwrap();
    let o = ecc(&[
        "sim",
        scene.to_str().unwrap(),
        "-q",
        "-o",
        dir.path().join("o").to_str().unwrap(),
    ]);
    assert!(
        stderr(&o).contains("`mips` has no 3D version"),
        "{}",
        stderr(&o)
    );

    let blocker = dir.path().join("file");
    fs::write(&blocker, "x").unwrap();
    let o = ecc(&[
        "sim",
        scene.to_str().unwrap(),
        "-q",
        "-o",
        blocker.join("out").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("cannot be written"), "{}", stderr(&o));

    let o = ecc(&["sim", dir.path().join("none.toml").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("cannot read"), "{}", stderr(&o));
}
