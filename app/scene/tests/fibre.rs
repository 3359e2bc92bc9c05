//! `[fibers]`: the shipped fibre_bar scene runs, and the fibre term makes a
//! cantilever stiffer along its fibres than across them (same load).

use ecc_scene::sim::FinalState;
use ecc_scene::{RunOptions, RunReport, RuntimeEnergies, SceneError, SceneFile, Silent, run_scene};

fn run(text: &str) -> Result<RunReport, SceneError> {
    let f = SceneFile::parse(text, "scene.toml", ".")?;
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    run_scene(&f, &RuntimeEnergies, &opts, &mut Silent)
}

/// A bar cantilevered at x = −2 under gravity, fibres `fibres`: the mean
/// downward tip displacement.
fn sag(fibres: &str) -> f64 {
    let r = run(&format!(
        r#"
frames = 1
[mesh]
generate = "bar"
resolution = 2
[energy]
name = "snh"
params = {{ mu = 1.0, lambda = 10.0 }}
[fibers]
params = {{ mu = 50.0 }}
{fibres}
[effects]
gravity = [0, -0.05, 0]
[[effects.handles]]
plane = {{ point = [-1.99, 0, 0], normal = [-1, 0, 0] }}
"#
    ))
    .unwrap();
    assert_eq!(r.summary.converged_frames, 1);
    let names: Vec<&str> = r.summary.terms.iter().map(|t| t.name.as_str()).collect();
    assert_eq!(names, ["elastic", "fibre", "gravity"]);
    let FinalState::Volume { rest, x, .. } = &r.state else {
        panic!("a tet body")
    };
    let tip: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0] > 1.99).collect();
    tip.iter().map(|&v| rest[v][1] - x[v][1]).sum::<f64>() / tip.len() as f64
}

#[test]
fn a_cantilever_is_stiffer_along_its_fibres() {
    let along = sag("direction = [1, 0, 0]");
    let across = sag("direction = [0, 0, 1]");
    let helix = sag("around = { point = [0, 0, 0], axis = [1, 0, 0], angle = 60 }");
    assert!(along > 0.0 && across > 0.0, "{along} {across}");
    assert!(along * 3.0 < across, "along {along}, across {across}");
    // helical fibres (60° from the circumference towards the axis) carry
    // bending with their axial component and resist the section's shear with
    // their circumferential one: far stiffer than fibres across
    assert!(
        helix * 3.0 < across,
        "along {along}, helix {helix}, across {across}"
    );
}

#[test]
fn the_shipped_fibre_bar_scene_runs() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/fibre_bar.toml");
    let f = SceneFile::read(path).unwrap();
    assert!(f.scene.fibers.is_some());
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    let r = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap();
    assert_eq!(r.summary.converged_frames, 12);
}

#[test]
fn bad_fibre_keys_are_located_errors() {
    let base = "[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"arap\"\n[fibers]\n";
    let cases = [
        ("direction = [0, 0, 0]", "zero or not finite"),
        ("direction = [1, 0]", "expected 3 finite numbers"),
        ("direction = [1, 0, 0]\nfield = \"fiber\"", "exactly one of"),
        (
            "energy = \"nope\"\ndirection = [1, 0, 0]",
            "unknown fibre energy `nope`",
        ),
        (
            "energy = \"muscle.psi\"\ndirection = [1, 0, 0]",
            "not supported by scenes yet",
        ),
        ("params = { k9 = 1.0 }\ndirection = [1, 0, 0]", "k9"),
        ("field = \"fiber\"", "needs `mesh.file`"),
        ("around = { point = [0, 0, 0] }", "needs an axis in 3D"),
        ("colour = 1", "colour"),
    ];
    for (extra, want) in cases {
        let err = run(&format!("{base}{extra}\n"))
            .err()
            .unwrap_or_else(|| panic!("{extra} accepted"));
        assert!(err.to_string().contains(want), "{extra}: {err}");
    }
}
