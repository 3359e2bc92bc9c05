//! `[solver] projection`: parsed with did-you-mean, applied to both the
//! parameterisation and frame scenes, reported in the summary.

use ecc_scene::{RunOptions, RunReport, RuntimeEnergies, SceneFile, Silent, run_scene};

fn run(text: &str) -> RunReport {
    let f = SceneFile::parse(text, "scene.toml", ".").unwrap();
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap()
}

fn disk(projection: Option<&str>) -> String {
    let key = projection.map_or(String::new(), |p| format!("projection = \"{p}\"\n"));
    format!(
        "[mesh]\ngenerate = \"disk\"\nrings = 4\n[energy]\nname = \"sd\"\n\
         [effects.parameterize]\ntutte = \"uniform\"\n[solver]\ntol = 1e-8\n{key}"
    )
}

#[test]
fn unknown_projection_suggests_the_closest() {
    let e = SceneFile::parse(&disk(Some("elemnt")), "scene.toml", ".")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("scene.toml:10:"), "{e}");
    assert!(
        e.contains("unknown value `elemnt`") && e.contains("did you mean `element`?"),
        "{e}"
    );
    assert!(e.contains("`f-space`") && e.contains("`hybrid`"), "{e}");
}

#[test]
fn every_projection_parameterizes_to_the_same_minimum() {
    let default = run(&disk(None));
    assert_eq!(default.summary.projection, "auto");
    for name in ["f-space", "element", "hybrid", "auto"] {
        let r = run(&disk(Some(name)));
        assert_eq!(r.summary.projection, name);
        assert!(r.summary.frames[1].converged, "{name}");
        let e = r.summary.final_energy;
        assert!(
            (e - default.summary.final_energy).abs() < 1e-9,
            "{name}: {e}"
        );
    }
}

#[test]
fn frame_scenes_report_and_use_the_projection() {
    let scene = |p: &str| {
        format!(
            "frames = 1\n[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"snh\"\n\
             [[effects.handles]]\nplane = {{ point = [-1.9, 0, 0], normal = [-1, 0, 0] }}\n\
             [[effects.handles]]\nplane = {{ point = [1.9, 0, 0], normal = [1, 0, 0] }}\n\
             keys = [ {{ frame = 1, rotate = [60, 0, 0] }} ]\n\
             [solver]\ntol = 1e-8\nprojection = \"{p}\"\n"
        )
    };
    let reference = run(&scene("f-space"));
    assert_eq!(reference.summary.projection, "f-space");
    // On tets `auto` is `f-space`: the same iterations and energy, bit for bit.
    let auto = run(&scene("auto"));
    assert_eq!(auto.summary.projection, "auto");
    assert_eq!(
        auto.summary.final_energy.to_bits(),
        reference.summary.final_energy.to_bits()
    );
    for name in ["element", "hybrid"] {
        let r = run(&scene(name));
        assert_eq!(r.summary.projection, name);
        assert_eq!(r.summary.converged_frames, 1, "{name}");
        let (a, b) = (r.summary.final_energy, reference.summary.final_energy);
        assert!(
            (a - b).abs() < 1e-9 * b.abs().max(1.0),
            "{name}: {a} vs {b}"
        );
    }
}
