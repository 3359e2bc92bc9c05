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
            "no .psi interpreter for fibre energies",
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

/// `result.png` of a small fibre scene with and without `draw_fibers`.
fn fibre_pictures(draw: bool) -> (Vec<u8>, (u32, u32), Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let text = format!(
        r#"
name = "fibre-picture"
frames = 1
[mesh]
generate = "bar"
resolution = 2
[energy]
name = "snh"
params = {{ mu = 1.0, lambda = 10.0 }}
[fibers]
params = {{ mu = 20.0 }}
around = {{ point = [0, 0, 0], axis = [1, 0, 0], angle = 45 }}
[[effects.handles]]
plane = {{ point = [-1.99, 0, 0], normal = [-1, 0, 0] }}
[[effects.handles]]
plane = {{ point = [1.99, 0, 0], normal = [1, 0, 0] }}
keys = [ {{ frame = 1, translate = [0.4, 0, 0] }} ]
[output]
formats = []
image_size = [480, 360]
draw_fibers = {draw}
"#
    );
    let f = SceneFile::parse(&text, "scene.toml", dir.path()).unwrap();
    let opts = RunOptions {
        out_dir: Some(out.clone()),
        ..Default::default()
    };
    let r = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap();
    assert_eq!(r.summary.converged_frames, 1);
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    let dec = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(out.join("result.png")).unwrap(),
    ));
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    assert_eq!(info.color_type, png::ColorType::Rgb, "8-bit RGB pictures");
    (buf, (info.width, info.height), names)
}

/// The fibres are drawn (on the body, plus the legend) when the scene has
/// `[fibers]`, `draw_fibers = false` turns them off, and the picture is
/// written like the others (complete, listed, no temporary file left).
#[test]
fn the_picture_draws_the_fibres_on_the_body() {
    let (on, size, names) = fibre_pictures(true);
    let (off, size_off, names_off) = fibre_pictures(false);
    assert_eq!(size, (480, 360));
    assert_eq!(size, size_off);
    let want = ["convergence.png", "result.png", "summary.json"];
    assert_eq!(names, want, "no temporary files may remain");
    assert_eq!(names_off, want);
    let (w, h) = (size.0 as usize, size.1 as usize);
    let px = |b: &[u8], x: usize, y: usize| -> [f32; 3] {
        let i = 3 * (y * w + x);
        [b[i], b[i + 1], b[i + 2]].map(|c| c as f32 / 255.0)
    };
    // body pixels of the plain picture: anything darker than the pale
    // background gradient (#e9eef5 → #fbfbfb)
    let body = |c: [f32; 3]| c.iter().any(|v| *v < 0.85);
    // the legend sits in the top-right quarter, under the title
    let legend = |x: usize, y: usize| x > w / 2 && y < h / 4;
    let (mut changed, mut on_body) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let (a, b) = (px(&on, x, y), px(&off, x, y));
            let d = (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f32::max);
            if d > 0.1 && !legend(x, y) {
                changed += 1;
                // on the body or within 3 px of it (segment ends and halos
                // at the silhouette)
                let near = (y.saturating_sub(3)..(y + 4).min(h)).any(|yy| {
                    (x.saturating_sub(3)..(x + 4).min(w)).any(|xx| body(px(&off, xx, yy)))
                });
                on_body += usize::from(near);
            }
        }
    }
    assert!(changed > 300, "only {changed} pixels changed");
    assert!(
        on_body as f64 > 0.97 * changed as f64,
        "{on_body} of {changed} changed pixels on the body"
    );
    let legend_changed = (0..h / 4)
        .flat_map(|y| (w / 2..w).map(move |x| (x, y)))
        .filter(|&(x, y)| px(&on, x, y) != px(&off, x, y))
        .count();
    assert!(legend_changed > 200, "no legend ({legend_changed} pixels)");
}
