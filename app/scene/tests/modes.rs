//! Each kind of scene runs and does the physically right thing (small sizes).

use ecc_scene::{FinalState, RunOptions, RunReport, RuntimeEnergies, SceneFile, Silent, run_scene};

fn run(text: &str) -> RunReport {
    let f = SceneFile::parse(text, "scene.toml", ".").unwrap();
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap()
}

#[test]
fn parameterizing_a_flat_disk_with_sd_reaches_the_isometry() {
    let r = run(r#"
[mesh]
generate = "disk"
rings = 4
[energy]
name = "sd"
[effects.parameterize]
tutte = "uniform"
[solver]
tol = 1e-8
"#);
    assert_eq!(r.summary.mode, "parameterization");
    let f = &r.summary.frames;
    assert!(f[1].converged);
    // SD ≥ 2 with equality for isometries; a flat disk can be laid out isometrically
    assert!(f[0].elastic_energy > f[1].elastic_energy);
    assert!(
        (r.summary.final_energy - 2.0).abs() < 1e-6,
        "{}",
        r.summary.final_energy
    );
    assert_eq!(f[1].inverted, 0);
    assert!(matches!(r.state, FinalState::Param { .. }));
}

#[test]
fn interpolation_reaches_the_second_rest_shape_at_t_1() {
    let r = run(r#"
[mesh]
generate = "bar"
resolution = 1
[energy]
name = "arap"
[effects.interpolate]
twist = 90
bend = 30
steps = 4
[solver]
tol = 1e-9
"#);
    assert_eq!(r.summary.mode, "interpolation");
    let ts: Vec<f64> = r.summary.frames.iter().map(|f| f.t.unwrap()).collect();
    assert_eq!(ts, [0.0, 0.25, 0.5, 0.75, 1.0]);
    let last = r.summary.frames.last().unwrap();
    assert!(last.converged, "{:?}", last.statuses);
    // E_1 = E_2 = 0 are reached at t = 0 and t = 1 (up to a rigid motion)
    assert!(last.elastic_energy < 1e-12, "{}", last.elastic_energy);
    // in between, the blend cannot be zero: the two shapes differ
    assert!(r.summary.frames[2].elastic_energy > 1e-3);
}

#[test]
fn planar_handles_are_reached_exactly_and_nothing_inverts() {
    let r = run(r#"
frames = 3
[mesh]
generate = "grid"
cells = [8, 2]
size = [4, 1]
[energy]
name = "sd"
[[effects.handles]]
box = { min = [-0.01, -0.01], max = [0.01, 1.01] }
[[effects.handles]]
box = { min = [3.99, -0.01], max = [4.01, 1.01] }
keys = [ { frame = 3, translate = [-1.0, 0.5], rotate = [45] } ]
"#);
    for f in &r.summary.frames {
        assert_eq!(f.handle_error, Some(0.0));
        assert_eq!(f.inverted, 0, "frame {}", f.frame);
    }
    assert_eq!(r.summary.converged_frames, 3);
    let FinalState::Planar { x, rest, .. } = &r.state else {
        panic!("planar")
    };
    // the moved end went where its key says
    // (4, 0) turns by 45° about the end's centre (4, 0.5), then moves by (−1, 0.5)
    let v = rest
        .iter()
        .position(|p| p[0] == 4.0 && p[1] == 0.0)
        .unwrap();
    let h = 0.5 * std::f64::consts::FRAC_1_SQRT_2;
    assert!(
        (x[v][0] - (3.0 + h)).abs() < 1e-12 && (x[v][1] - (1.0 - h)).abs() < 1e-12,
        "{:?}",
        x[v]
    );
}

/// A 2D cantilever released under gravity: total energy per frame.
fn swing(integrator: &str) -> Vec<f64> {
    let r = run(&format!(
        r#"
frames = 30
[mesh]
generate = "grid"
cells = [6, 1]
size = [3, 0.5]
[energy]
name = "snh"
params = {{ mu = 20.0, lambda = 50.0 }}
[effects]
gravity = [0.0, -1.0]
inertia = {{ dt = 0.05, integrator = "{integrator}" }}
[[effects.handles]]
box = {{ min = [-0.01, -0.01], max = [0.01, 0.51] }}
[solver]
tol = 1e-10
"#
    ));
    assert_eq!(r.summary.converged_frames, 30);
    r.summary.frames.iter().map(|f| f.total_energy).collect()
}

#[test]
fn implicit_euler_dissipates_and_bdf2_keeps_more_energy() {
    let euler = swing("euler");
    let bdf2 = swing("bdf2");
    let scale = euler.iter().map(|e| e.abs()).fold(0.0, f64::max);
    for w in euler.windows(2) {
        assert!(
            w[1] <= w[0] + 1e-9 * scale,
            "implicit Euler gained energy: {w:?}"
        );
    }
    // the swing converts potential into motion and both integrators lose
    // some of it; BDF2 (second order) loses less
    let (e_loss, b_loss) = (euler[0] - euler[30], bdf2[0] - bdf2[30]);
    assert!(e_loss > 0.0, "Euler should dissipate: {euler:?}");
    assert!(
        b_loss < e_loss,
        "BDF2 loss {b_loss} should be below Euler's {e_loss}"
    );
}
