//! Output folders: checked before any work, every file written atomically,
//! the summary lists exactly what was written.

use std::fs;

use ecc_scene::{RunOptions, RuntimeEnergies, SceneError, SceneFile, Silent, Summary, run_scene};

const SCENE: &str = r#"
name = "tiny"
frames = 2
[mesh]
generate = "bar"
resolution = 1
[energy]
name = "arap"
[[effects.handles]]
plane = { point = [-1.9, 0, 0], normal = [-1, 0, 0] }
[[effects.handles]]
plane = { point = [1.9, 0, 0], normal = [1, 0, 0] }
keys = [ { frame = 2, rotate = [60, 0, 0] } ]
[output]
image_size = [320, 240]
"#;

#[test]
fn unwritable_output_folder_fails_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("not-a-folder");
    fs::write(&blocker, "x").unwrap();
    // the mesh file does not exist either: the output folder is checked first
    let text = "[mesh]\nfile = \"missing.obj\"\n[energy]\nname = \"arap\"\n";
    let f = SceneFile::parse(text, "scene.toml", dir.path()).unwrap();
    let opts = RunOptions {
        out_dir: Some(blocker.join("out")),
        ..Default::default()
    };
    let e = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap_err();
    assert!(matches!(e, SceneError::Output { .. }), "{e}");
    assert!(e.to_string().contains("cannot be written"), "{e}");
}

#[test]
fn outputs_are_complete_atomic_and_listed() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let f = SceneFile::parse(SCENE, "tiny.toml", dir.path()).unwrap();
    let opts = RunOptions {
        out_dir: Some(out.clone()),
        ..Default::default()
    };
    let r = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap();
    let mut names: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    let mut expected: Vec<String> = [
        "convergence.png",
        "frame_0000.obj",
        "frame_0000.vtk",
        "frame_0001.obj",
        "frame_0001.vtk",
        "frame_0002.obj",
        "frame_0002.vtk",
        "result.png",
        "summary.json",
    ]
    .map(String::from)
    .to_vec();
    expected.sort();
    assert_eq!(names, expected, "no temporary files may remain");
    let mut listed = r.summary.outputs.clone();
    listed.sort();
    assert_eq!(listed, expected);
    // the summary on disk is the returned one
    let disk: Summary =
        serde_json::from_slice(&fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(disk.scene, "tiny");
    assert_eq!(disk.frames.len(), 3);
    assert_eq!(disk.terms[0].name, "elastic");
    // pictures decode at the requested size
    for png_name in ["result.png", "convergence.png"] {
        let dec = png::Decoder::new(std::io::BufReader::new(
            fs::File::open(out.join(png_name)).unwrap(),
        ));
        let info = dec.read_info().unwrap();
        let i = info.info();
        assert_eq!((i.width, i.height), (320, 240), "{png_name}");
    }
    // frames read back with the mesh readers
    let m = ecc_mesh::read_tet_mesh(out.join("frame_0002.vtk")).unwrap();
    assert_eq!(m.tets.len(), 24);
    // writing again replaces files in place
    let r2 = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap();
    assert_eq!(r2.summary.outputs.len(), expected.len());
    assert_eq!(fs::read_dir(&out).unwrap().count(), expected.len());
}

/// Asks to stop after `after` accepted Newton iterations.
struct StopAfter {
    after: usize,
    seen: usize,
}

impl ecc_scene::Observer for StopAfter {
    fn iteration(
        &mut self,
        _frame: usize,
        _rec: &ecc_fem::IterationRecord,
    ) -> std::ops::ControlFlow<()> {
        self.seen += 1;
        if self.seen >= self.after {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    }
}

#[test]
fn an_observer_can_stop_the_run_and_what_was_computed_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let f = SceneFile::parse(SCENE, "tiny.toml", dir.path()).unwrap();
    let opts = RunOptions {
        out_dir: Some(out.clone()),
        ..Default::default()
    };
    let mut obs = StopAfter { after: 1, seen: 0 };
    let r = run_scene(&f, &RuntimeEnergies, &opts, &mut obs).unwrap();
    assert_eq!(obs.seen, 1, "no iteration after the stop");
    assert_eq!(r.summary.status, ecc_scene::RunStatus::Stopped);
    let why = r.summary.stopped.as_deref().unwrap_or_default();
    assert!(why.contains("interrupted"), "{why}");
    assert!(out.join("summary.json").is_file());
    assert!(out.join("frame_0000.obj").is_file());
}
