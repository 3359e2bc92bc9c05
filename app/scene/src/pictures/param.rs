//! Parameterisation pictures: the surface with a checkerboard mapped
//! through the uv map, and the uv layout coloured by isometric distortion.

use ecc_mesh::TriMesh;

use super::image::{Orient, Picture, Rgb, hex};
use super::planar::{Fit2, boundary_edges, fill_tris};
use super::raster::{Camera, Layer, cross, dot, normalize, sub};
use super::volume::{Scene3, draw_body};
use super::{colour_bar, heat, sv2, title, title_height};

/// max(σ₁, 1/σ₂) of the map from each rest triangle (in its isometric
/// frame) to uv: 1 for an isometry, ∞ for a flipped triangle.
pub(crate) fn isometric_distortion(mesh: &TriMesh, uv: &[[f64; 2]]) -> Vec<f64> {
    mesh.triangles
        .iter()
        .map(|t| {
            let (p0, p1, p2) = (
                mesh.positions[t[0]],
                mesh.positions[t[1]],
                mesh.positions[t[2]],
            );
            let e1 = sub(p1, p0);
            let e2 = sub(p2, p0);
            let l1 = dot(e1, e1).sqrt();
            let c = cross(e1, e2);
            let a2 = dot(c, c).sqrt();
            if l1 == 0.0 || a2 == 0.0 {
                return f64::INFINITY;
            }
            // rest frame: e1 → (l1, 0), e2 → (e1·e2/l1, |e1×e2|/l1)
            let dm = [l1, dot(e1, e2) / l1, 0.0, a2 / l1];
            let (u0, u1, u2) = (uv[t[0]], uv[t[1]], uv[t[2]]);
            let ds = [u1[0] - u0[0], u2[0] - u0[0], u1[1] - u0[1], u2[1] - u0[1]];
            let det_s = ds[0] * ds[3] - ds[1] * ds[2];
            if det_s <= 0.0 {
                return f64::INFINITY;
            }
            let det_m = dm[0] * dm[3];
            let inv = [dm[3] / det_m, -dm[1] / det_m, 0.0, dm[0] / det_m];
            let f = [
                ds[0] * inv[0] + ds[1] * inv[2],
                ds[0] * inv[1] + ds[1] * inv[3],
                ds[2] * inv[0] + ds[3] * inv[2],
                ds[2] * inv[1] + ds[3] * inv[3],
            ];
            let (s1, s2) = sv2(f[0], f[1], f[2], f[3]);
            s1.max(1.0 / s2.max(1e-300))
        })
        .collect()
}

fn distortion_colour(d: f64) -> Rgb {
    if !d.is_finite() {
        return hex(0x5b2a86);
    }
    heat(d.ln() / 4f64.ln())
}

/// The camera direction for an open surface: along the area-weighted mean
/// normal (the side the surface faces), with screen-up along the surface's
/// longest in-plane extent.
fn surface_view(mesh: &TriMesh) -> ([f64; 3], [f64; 3], [f64; 3], f64) {
    let x = &mesh.positions;
    let mut n = [0.0; 3];
    for t in &mesh.triangles {
        let c = cross(sub(x[t[1]], x[t[0]]), sub(x[t[2]], x[t[0]]));
        for i in 0..3 {
            n[i] += c[i];
        }
    }
    let mut n = normalize(n);
    if dot(n, n) == 0.0 {
        n = [0.0, 0.0, 1.0];
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in x {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let centre: [f64; 3] = std::array::from_fn(|i| 0.5 * (lo[i] + hi[i]));
    let r = 0.5 * dot(sub(hi, lo), sub(hi, lo)).sqrt();
    // the world axis with the largest extent, projected into the view plane
    let ext = sub(hi, lo);
    let k = (0..3)
        .max_by(|&a, &b| ext[a].total_cmp(&ext[b]))
        .unwrap_or(1);
    let mut up = [0.0; 3];
    up[k] = 1.0;
    let up = normalize(sub(up, n.map(|c| c * dot(up, n))));
    // tilt the view a little for depth cues
    let dir = normalize(std::array::from_fn(|i| n[i] + 0.25 * up[i]));
    (centre, dir, up, r.max(1e-9))
}

/// Mean of the finite values.
fn finite_mean(v: &[f64]) -> f64 {
    let finite: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    finite.iter().sum::<f64>() / finite.len().max(1) as f64
}

/// The surface with a checkerboard of 24 squares across the uv box.
fn draw_checkered_surface(
    pic: &mut Picture,
    mesh: &TriMesh,
    uv: &[[f64; 2]],
    vp: (f64, f64, f64, f64),
) {
    let (centre, dir, up, r) = surface_view(mesh);
    let mut layer = Layer::new(vp);
    let cam = Camera::fit(
        centre,
        dir,
        up,
        3.5 * r,
        &mesh.positions,
        layer.viewport(2.0),
    );
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in uv {
        lo = [lo[0].min(p[0]), lo[1].min(p[1])];
        hi = [hi[0].max(p[0]), hi[1].max(p[1])];
    }
    let checker = ((hi[0] - lo[0]).max(hi[1] - lo[1]) / 24.0).max(1e-12);
    let none = vec![false; mesh.positions.len()];
    let scene = Scene3 {
        faces: &mesh.triangles,
        x: &mesh.positions,
        highlight: &none,
        checker: Some((uv, checker)),
        wire: false,
    };
    draw_body(&mut layer, &cam, &scene, up);
    layer.composite(pic);
}

/// Left: the surface textured with a checkerboard through `uv`; right: the
/// uv layout coloured by isometric distortion; `start` is the Tutte layout
/// (reported in the subtitle).
pub fn parameterization(
    mesh: &TriMesh,
    start: &[[f64; 2]],
    uv: &[[f64; 2]],
    name: &str,
    size: (usize, usize),
) -> Picture {
    let (w, h) = (size.0 as f64, size.1 as f64);
    let mut pic = Picture::new(size.0, size.1, hex(0xfbfbfb));
    let top = title_height(h);
    let margin = 0.02 * w.min(h) + 4.0;
    let half = 0.5 * w;
    let bar = (0.02 * h).clamp(8.0, 14.0);
    let legend = 3.4 * bar;
    let d = isometric_distortion(mesh, uv);
    let d0 = isometric_distortion(mesh, start);
    let flipped = d.iter().filter(|x| !x.is_finite()).count();
    let panel_h = h - top - margin - legend;

    // left: checkerboard through the map
    draw_checkered_surface(
        &mut pic,
        mesh,
        uv,
        (margin, top, half - 1.5 * margin, panel_h),
    );

    // right: uv layout by distortion, with its boundary
    let fit = Fit2::new(uv, (half + 0.5 * margin, top, half - 1.5 * margin, panel_h));
    let colours: Vec<Rgb> = d.iter().map(|x| distortion_colour(*x)).collect();
    fill_tris(&mut pic, &fit, &mesh.triangles, uv, &colours, true);
    let outline: Vec<_> = boundary_edges(&mesh.triangles)
        .into_iter()
        .map(|(a, b)| (fit.map(uv[a]), fit.map(uv[b])))
        .collect();
    pic.segments(&outline, 1.0, hex(0x303030), 1.0);

    // captions: under the surface, and a colour bar for max(σ₁, 1/σ₂) from 1 to 4
    let by = top + panel_h + 0.7 * bar;
    let size = (1.3 * bar).clamp(11.0, 18.0);
    let caption = "checkerboard mapped through the uv map";
    pic.text(margin, by, caption, size, hex(0x404040), Orient::Across);
    colour_bar(
        &mut pic,
        (half + 0.5 * margin, by, (0.22 * w).min(220.0), bar),
        heat,
        &[("1", 0.0), ("2", 0.5), ("4+", 1.0)],
        "distortion max(σ₁, 1/σ₂)",
    );
    title(
        &mut pic,
        name,
        &format!(
            "{} triangles, {} flipped; mean distortion {:.3} (Tutte start {:.3})",
            mesh.triangles.len(),
            flipped,
            finite_mean(&d),
            finite_mean(&d0)
        ),
    );
    pic
}
