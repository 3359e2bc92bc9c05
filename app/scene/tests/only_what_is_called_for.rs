//! The objective holds exactly the terms the scene names: a quasi-static
//! scene never builds a mass matrix, a scene without a ground never runs
//! contact code, and each named effect shows up in the summary's terms.

use ecc_scene::{RunOptions, RunReport, RuntimeEnergies, SceneFile, Silent, run_scene};

fn run(text: &str) -> RunReport {
    let f = SceneFile::parse(text, "scene.toml", ".").unwrap();
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap()
}

fn term_names(r: &RunReport) -> Vec<String> {
    r.summary.terms.iter().map(|t| t.name.clone()).collect()
}

#[test]
fn quasi_static_scene_builds_no_mass_matrix_and_runs_no_contact() {
    let r = run(r#"
frames = 2
[mesh]
generate = "bar"
resolution = 1
[energy]
name = "arap"
[effects]
gravity = [0, -0.5, 0]
[[effects.handles]]
plane = { point = [-1.9, 0, 0], normal = [-1, 0, 0] }
"#);
    assert_eq!(term_names(&r), ["elastic", "gravity"]);
    let c = r.summary.counters;
    assert_eq!(c.mass_matrix_builds, 0);
    assert_eq!(c.inertia_passes, 0);
    assert_eq!(c.contact_passes, 0);
    assert!(c.gravity_passes > 0);
    assert_eq!(r.summary.mode, "quasi_static");
    // every frame converged and the bar sagged under gravity
    assert_eq!(r.summary.converged_frames, 2);
    let last = r.summary.frames.last().unwrap();
    assert!(last.gravity_potential.unwrap() < r.summary.frames[0].gravity_potential.unwrap());
    assert!(last.kinetic_energy.is_none() && last.contact_energy.is_none());
}

#[test]
fn nothing_named_means_only_the_elastic_term() {
    let r = run("[mesh]\ngenerate = \"disk\"\nrings = 3\n[energy]\nname = \"arap\"\n");
    assert_eq!(term_names(&r), ["elastic"]);
    assert_eq!(r.summary.counters, Default::default());
}

#[test]
fn dynamics_with_ground_and_damping_builds_each_term_once() {
    let r = run(r#"
frames = 3
[mesh]
generate = "bar"
resolution = 1
[energy]
name = "snh"
params = { mu = 20.0, lambda = 100.0 }
[effects]
gravity = [0, -9.81, 0]
inertia = { dt = 0.02, integrator = "bdf2", mass = "consistent" }
damping = { alpha = 0.1, beta = 0.01 }
ground = { height = -0.6 }
"#);
    assert_eq!(
        term_names(&r),
        [
            "elastic",
            "gravity",
            "inertia",
            "damping_mass",
            "damping_stiffness",
            "ground"
        ]
    );
    let c = r.summary.counters;
    assert_eq!(c.mass_matrix_builds, 1);
    assert_eq!(c.stiffness_snapshots, 3);
    assert!(c.contact_passes > 0 && c.inertia_passes > 0 && c.damping_passes > 0);
    assert_eq!(r.summary.mode, "dynamic");
    for t in &r.summary.terms {
        assert!(t.assembly_passes > 0, "{} never assembled", t.name);
    }
}
