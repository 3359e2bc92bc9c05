//! The shipped 2D fibre scene (scenes/fibre_sheet.toml, issue #16): it runs,
//! its picture is written with the fibres drawn, and the same sheet is
//! stiffer along its fibres than across them under the same body force.

use ecc_scene::sim::FinalState;
use ecc_scene::{RunOptions, RuntimeEnergies, SceneFile, Silent, run_scene};

const SCENE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/fibre_sheet.toml");

/// The shipped scene, with the picture size `size` and no mesh files.
fn shipped(size: [usize; 2]) -> SceneFile {
    let mut f = SceneFile::read(SCENE).unwrap();
    f.scene.output.formats = Some(Vec::new());
    f.scene.output.image_size = Some(size.to_vec());
    f
}

/// The shipped sheet with its clamp only, fibres along `fibres`, under the
/// body force `g` (density 1): the mean displacement of the free edge.
fn free_edge(fibres: [f64; 2], g: [f64; 2]) -> [f64; 2] {
    let mut f = shipped([320, 240]);
    f.scene.frames = Some(1);
    f.scene.effects.handles.retain(|h| h.keys.is_empty());
    assert_eq!(f.scene.effects.handles.len(), 1, "the clamp");
    f.scene.effects.gravity = Some(g.to_vec());
    f.scene.fibers.as_mut().unwrap().direction = Some(fibres.to_vec());
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    let r = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap();
    assert_eq!(r.summary.converged_frames, 1);
    let names: Vec<&str> = r.summary.terms.iter().map(|t| t.name.as_str()).collect();
    assert_eq!(names, ["elastic", "fibre", "gravity"]);
    let FinalState::Planar { rest, x, .. } = &r.state else {
        panic!("a planar body")
    };
    let tip: Vec<usize> = (0..rest.len()).filter(|&v| rest[v][0] > 3.99).collect();
    assert!(tip.len() > 2);
    let mean = |k: usize| tip.iter().map(|&v| x[v][k] - rest[v][k]).sum::<f64>() / tip.len() as f64;
    [mean(0), mean(1)]
}

/// Stretched along x by a body force, the sheet with fibres along x gives
/// a fraction of the extension of the sheet with fibres across; sagging
/// under a body force across (shear and bending), likewise.
#[test]
fn the_sheet_is_stiffer_along_its_fibres_than_across() {
    let (along, across) = ([1.0, 0.0], [0.0, 1.0]);
    let pull = [0.05, 0.0];
    let (a, c) = (free_edge(along, pull)[0], free_edge(across, pull)[0]);
    assert!(a > 0.0 && c > 0.0, "{a} {c}");
    eprintln!("pulled along x: free edge moves {a:.4e} (fibres along), {c:.4e} (across)");
    assert!(5.0 * a < c, "pulled: along {a}, across {c}");
    let sag = [0.0, -0.01];
    let (a, c) = (-free_edge(along, sag)[1], -free_edge(across, sag)[1]);
    assert!(a > 0.0 && c > 0.0, "{a} {c}");
    eprintln!("sagging: free edge drops {a:.4e} (fibres along), {c:.4e} (across)");
    assert!(2.5 * a < c, "sagging: along {a}, across {c}");
}

/// Pixels of `result.png` of the shipped scene run into a temporary folder
/// (with or without fibres), its size and the files written.
fn picture(draw: bool) -> (Vec<u8>, (usize, usize), Vec<String>) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("run");
    let mut f = shipped([640, 480]);
    f.scene.output.draw_fibers = Some(draw);
    let opts = RunOptions {
        out_dir: Some(out.clone()),
        ..Default::default()
    };
    let r = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap();
    assert_eq!(r.summary.converged_frames, 8);
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
    assert_eq!(info.color_type, png::ColorType::Rgb);
    (buf, (info.width as usize, info.height as usize), names)
}

/// The fibre cores are magenta (stretched; the distortion ramp of the body
/// has no blue) and sit on the body, the legend is drawn, and without
/// `draw_fibers` neither is.
#[test]
fn the_picture_is_written_with_the_fibres_on_the_sheet() {
    let (on, (w, h), names) = picture(true);
    let (off, size_off, _) = picture(false);
    assert_eq!((w, h), (640, 480));
    assert_eq!(size_off, (w, h));
    assert_eq!(names, ["convergence.png", "result.png", "summary.json"]);
    let px = |b: &[u8], x: usize, y: usize| {
        let i = 3 * (y * w + x);
        [b[i], b[i + 1], b[i + 2]].map(i32::from)
    };
    // a stretched fibre's core: red and blue well above green
    let magenta = |c: [i32; 3]| c[0] > c[1] + 60 && c[2] > c[1] + 30;
    let count = |b: &[u8], rows: std::ops::Range<usize>| {
        rows.flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| magenta(px(b, x, y)))
            .count()
    };
    // main panel (under the legend row), legend row, and the picture
    // without fibres
    let (panel, legend) = (count(&on, h / 5..h / 2), count(&on, 0..h / 6));
    assert!(panel > 400, "{panel} fibre pixels in the main panel");
    assert!(legend > 50, "{legend} legend pixels");
    assert_eq!(count(&off, 0..h), 0, "no fibres without draw_fibers");
}
