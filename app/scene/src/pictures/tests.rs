//! Whole pictures: the right size, not blank, legible text in the title bar,
//! anti-aliased edges (intermediate shades), and the PNG round trip.

use ecc_mesh::{box_tet, grid_tri};

use super::*;
use crate::summary::{SolveLog, SolvePoint};

/// With `ECC_PICTURES_DUMP=DIR`, write the picture to DIR/`name` (to look at).
fn dump(name: &str, p: &Picture) {
    if let Some(dir) = std::env::var_os("ECC_PICTURES_DUMP") {
        let path = std::path::Path::new(&dir).join(name);
        if let Err(e) = std::fs::write(&path, p.to_png()) {
            panic!("cannot write {}: {e}", path.display());
        }
    }
}

/// Pixels whose colour differs from `bg` by more than 24 in some channel.
fn ink(p: &Picture, (x0, y0, x1, y1): (usize, usize, usize, usize), bg: [u8; 3]) -> usize {
    (y0..y1.min(p.height()))
        .flat_map(|y| (x0..x1.min(p.width())).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            let c = p.rgb(x, y);
            (0..3).any(|i| c[i].abs_diff(bg[i]) > 24)
        })
        .count()
}

/// Distinct colours (a flat, aliased drawing has few).
fn colours(p: &Picture) -> usize {
    let mut all: Vec<[u8; 3]> = (0..p.height())
        .flat_map(|y| (0..p.width()).map(move |x| (x, y)))
        .map(|(x, y)| p.rgb(x, y))
        .collect();
    all.sort_unstable();
    all.dedup();
    all.len()
}

/// Title text: dark pixels in the title bar.
fn title_ink(p: &Picture) -> usize {
    let h = title_height(p.height() as f64) as usize;
    (0..h)
        .flat_map(|y| (0..p.width() / 3).map(move |x| (x, y)))
        .filter(|&(x, y)| p.rgb(x, y).iter().all(|c| *c < 100))
        .count()
}

fn view<'a>(highlight: &'a [bool], size: (usize, usize)) -> View<'a> {
    View {
        title: "gravity",
        size,
        camera: (30.0, 20.0),
        highlight,
        ground: None,
        up: [0.0, 1.0, 0.0],
    }
}

#[test]
fn singular_values_of_2x2() {
    let (s1, s2) = sv2(3.0, 0.0, 0.0, -2.0);
    assert!((s1 - 3.0).abs() < 1e-12 && (s2 - 2.0).abs() < 1e-12);
    let (s1, s2) = sv2(1.0, 1.0, 0.0, 1.0);
    // golden ratio pair
    assert!((s1 * s2 - 1.0).abs() < 1e-12 && (s1 - 1.618_033_988_749_895).abs() < 1e-12);
}

#[test]
fn volume_picture_has_size_body_title_and_smooth_silhouettes() {
    let m = box_tet(4, 2, 2, [2.0, 0.5, 0.5]);
    let shots: Vec<(usize, Vec<[f64; 3]>)> = (0..4)
        .map(|k| {
            let x = m
                .positions
                .iter()
                .map(|p| [p[0], p[1] + 0.1 * k as f64 * p[0] * p[0], p[2]])
                .collect();
            (k, x)
        })
        .collect();
    let hl: Vec<bool> = m.positions.iter().map(|p| p[0] == 0.0).collect();
    let mut v = view(&hl, (320, 240));
    v.ground = Some(([0.0, 1.0, 0.0], -0.2));
    let p = volume(&m.tets, &shots, &v);
    dump("volume.png", &p);
    assert_eq!((p.width(), p.height()), (320, 240));
    assert!(title_ink(&p) > 30, "title: {} dark pixels", title_ink(&p));
    // the body fills a good part of the main panel, thumbnails show too
    assert!(ink(&p, (0, 30, 320, 170), [240, 243, 248]) > 3000);
    assert!(ink(&p, (0, 190, 320, 240), [255, 255, 255]) > 200);
    assert!(colours(&p) > 500, "{} colours", colours(&p));
}

#[test]
fn planar_picture_draws_the_mesh_outline_handles_and_legend() {
    let m = grid_tri(6, 3, 2.0, 1.0);
    let rest: Vec<[f64; 2]> = m.positions.iter().map(|p| [p[0], p[1]]).collect();
    let bent: Vec<[f64; 2]> = rest
        .iter()
        .map(|p| [p[0], p[1] + 0.2 * p[0] * p[0]])
        .collect();
    let hl: Vec<bool> = rest.iter().map(|p| p[0] == 2.0).collect();
    let shots = vec![(0, rest.clone()), (1, bent.clone()), (2, bent)];
    let mut v = view(&hl, (400, 300));
    v.ground = Some(([0.0, 1.0, 0.0], -0.1));
    let p = planar(&m.triangles, &rest, &shots, &v);
    dump("planar.png", &p);
    assert_eq!((p.width(), p.height()), (400, 300));
    assert!(title_ink(&p) > 30);
    assert!(ink(&p, (0, 40, 400, 200), [251, 251, 251]) > 4000);
    // handles in orange
    let orange = (0..p.height())
        .flat_map(|y| (0..p.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| p.rgb(x, y) == [0xee, 0x7d, 0x3b])
        .count();
    assert!(orange > 10, "{orange} orange pixels");
    assert!(colours(&p) > 300, "{} colours", colours(&p));
    assert_eq!(&p.to_png()[1..4], b"PNG");
}

#[test]
fn parameterisation_picture_shows_surface_and_layout() {
    let m = grid_tri(6, 6, 1.0, 1.0);
    let mut mesh = m.clone();
    for p in &mut mesh.positions {
        p[2] = 0.3 * (p[0] * 3.0).sin();
    }
    let uv: Vec<[f64; 2]> = m.positions.iter().map(|p| [p[0], p[1]]).collect();
    let p = parameterization(&mesh, &uv, &uv, "camel", (480, 300));
    dump("param.png", &p);
    assert_eq!((p.width(), p.height()), (480, 300));
    assert!(title_ink(&p) > 30);
    // left half (surface) and right half (layout) both drawn
    assert!(ink(&p, (0, 40, 240, 240), [251, 251, 251]) > 3000);
    assert!(ink(&p, (240, 40, 480, 240), [251, 251, 251]) > 3000);
}

#[test]
fn convergence_plot_has_curves_labels_and_tolerance() {
    let solve = |frame: usize, n: usize| SolveLog {
        frame,
        status: "converged".into(),
        iterations: n,
        points: (0..=n)
            .map(|i| SolvePoint {
                grad_inf: 10f64.powf(2.0 - i as f64),
                energy: 1.0,
                seconds: 0.01 * (frame * 10 + i) as f64,
            })
            .collect(),
        times: Default::default(),
        linear: Default::default(),
    };
    let solves: Vec<SolveLog> = (1..=3).map(|f| solve(f, 6 + f)).collect();
    let p = convergence(&solves, 1e-6, "demo", (640, 360));
    dump("convergence.png", &p);
    assert_eq!((p.width(), p.height()), (640, 360));
    assert!(title_ink(&p) > 30);
    // tick labels and axis titles below each panel
    assert!(ink(&p, (0, 300, 320, 360), [255, 255, 255]) > 150);
    assert!(ink(&p, (320, 300, 640, 360), [255, 255, 255]) > 150);
    // the dashed tolerance line (green) is drawn
    let green = (0..p.height())
        .flat_map(|y| (0..p.width()).map(move |x| (x, y)))
        .filter(|&(x, y)| p.rgb(x, y) == [0x2e, 0x8b, 0x57])
        .count();
    assert!(green > 100, "{green} green pixels");
    assert!(colours(&p) > 200, "{} colours", colours(&p));
}

#[test]
fn chart_with_log_axes_and_legend_outside() {
    let chart = Chart {
        title: "Time per Newton iteration".into(),
        xlabel: "elements".into(),
        ylabel: "seconds per iteration".into(),
        log_x: true,
        log_y: true,
        series: vec![Series {
            label: "tri (SD) Cholesky".into(),
            points: vec![(1e4, 0.01), (1e5, 0.1), (1e6, 1.5)],
            dots: true,
            colour: None,
        }],
        ..Chart::default()
    };
    let p = chart.picture(600, 320);
    dump("chart.png", &p);
    assert_eq!((p.width(), p.height()), (600, 320));
    // the legend sits to the right of the plot: text there
    assert!(ink(&p, (430, 20, 600, 80), [255, 255, 255]) > 80);
    // an empty chart still draws its axes without panicking
    let empty = Chart::default().picture(300, 200);
    assert!(ink(&empty, (0, 0, 300, 200), [255, 255, 255]) > 100);
}

/// A layout of sub-pixel triangles (splatted) covers the same pixels in the
/// same colour as the same square in large triangles (anti-aliased paths):
/// interior pixels exactly the fill colour, the background untouched, the
/// covered area equal to within the one-pixel anti-aliased border.
#[test]
fn sub_pixel_triangles_are_splatted_like_the_filled_square() {
    use super::planar::{Fit2, fill_tris};
    let draw = |n: usize| {
        let m = grid_tri(n, n, 1.0, 1.0);
        let uv: Vec<[f64; 2]> = m.positions.iter().map(|p| [p[0], p[1]]).collect();
        let mut pic = Picture::new(120, 120, hex(0xffffff));
        let fit = Fit2::new(&uv, (20.0, 20.0, 80.0, 80.0));
        let colours = vec![hex(0x3060c0); m.triangles.len()];
        fill_tris(&mut pic, &fit, &m.triangles, &uv, &colours, false);
        pic
    };
    // 400×400 cells on 80 px: edges 0.2–0.28 px, every triangle splatted
    let (fine, coarse) = (draw(400), draw(2));
    let fill = [0x30, 0x60, 0xc0];
    for (x, y) in [(30, 30), (60, 60), (95, 25)] {
        // the tent filter's sampling noise, and the paths' anti-aliased
        // seams: within 2 of 255 levels
        for got in [fine.rgb(x, y), coarse.rgb(x, y)] {
            assert!(
                (0..3).all(|k| got[k].abs_diff(fill[k]) <= 2),
                "({x}, {y}): {got:?}"
            );
        }
    }
    for (x, y) in [(5, 5), (110, 60), (60, 115)] {
        assert_eq!(fine.rgb(x, y), [255; 3], "({x}, {y})");
    }
    let (a, b) = (
        ink(&fine, (0, 0, 120, 120), [255; 3]),
        ink(&coarse, (0, 0, 120, 120), [255; 3]),
    );
    assert!(a.abs_diff(b) <= 4 * 82, "{a} vs {b} inked pixels");
    assert!(a >= 80 * 80, "{a}");
}
