//! Shaded renders of tet meshes (their boundary surface).

use ecc_mesh::tet_boundary_faces;

use super::fibres::{self, Fibres};
use super::image::{Orient, Picture, Rgb, hex, scale};
use super::raster::{Camera, Layer, SS, cover, cross, dot, normalize, sub, triangle};
use super::{View, title, title_height};

const BODY: u32 = 0x6f9fd8;
const HANDLE: u32 = 0xee7d3b;

/// Orbit direction (from the target towards the eye) for azimuth/elevation
/// in degrees around `up`; azimuth 0 looks along −h₀, where h₀ is the
/// world axis most perpendicular to `up` (z for y-up).
pub(crate) fn orbit(up: [f64; 3], az: f64, el: f64) -> ([f64; 3], [f64; 3]) {
    let u = normalize(up);
    let axes = [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let h0 = axes
        .iter()
        .copied()
        .min_by(|a, b| dot(*a, u).abs().total_cmp(&dot(*b, u).abs()))
        .unwrap_or([0.0, 0.0, 1.0]);
    let h0 = normalize(sub(h0, u.map(|c| c * dot(h0, u))));
    let side = cross(u, h0);
    let (a, e) = (az.to_radians(), el.to_radians());
    let dir: [f64; 3] =
        std::array::from_fn(|i| e.cos() * (a.cos() * h0[i] + a.sin() * side[i]) + e.sin() * u[i]);
    (normalize(dir), u)
}

/// Centre and radius of the bounding sphere of the boxes of all shots.
fn bounds(shots: &[&[[f64; 3]]]) -> ([f64; 3], f64) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for s in shots {
        for p in s.iter() {
            for c in 0..3 {
                lo[c] = lo[c].min(p[c]);
                hi[c] = hi[c].max(p[c]);
            }
        }
    }
    let c = std::array::from_fn(|i| 0.5 * (lo[i] + hi[i]));
    let r = 0.5 * dot(sub(hi, lo), sub(hi, lo)).sqrt();
    (c, r.max(1e-9))
}

/// Render one body state into the viewport of `pic` with camera `cam`.
pub(crate) struct Scene3<'a> {
    pub faces: &'a [[usize; 3]],
    pub x: &'a [[f64; 3]],
    pub highlight: &'a [bool],
    /// Optional per-vertex texture coordinate and checker size.
    pub checker: Option<(&'a [[f64; 2]], f64)>,
    pub wire: bool,
}

/// Smooth vertex normals (area weighted) of a triangle surface.
fn vertex_normals(faces: &[[usize; 3]], x: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut n = vec![[0.0; 3]; x.len()];
    for f in faces {
        let fn_ = cross(sub(x[f[1]], x[f[0]]), sub(x[f[2]], x[f[0]]));
        for &v in f {
            for c in 0..3 {
                n[v][c] += fn_[c];
            }
        }
    }
    n.into_iter().map(normalize).collect()
}

pub(crate) fn draw_body(layer: &mut Layer, cam: &Camera, s: &Scene3<'_>, up: [f64; 3]) {
    let normals = vertex_normals(s.faces, s.x);
    let fwd = cam.forward();
    let side = normalize(cross(fwd, up));
    let key = normalize(std::array::from_fn(|i| {
        -fwd[i] + 0.9 * up[i] - 0.5 * side[i]
    }));
    let fill = normalize(std::array::from_fn(|i| {
        -fwd[i] + 0.6 * side[i] - 0.2 * up[i]
    }));
    let scr: Vec<[f64; 3]> = s.x.iter().map(|p| cam.project(*p)).collect();
    // wireframe only when triangles are large enough on screen
    let mean_edge = s
        .faces
        .iter()
        .take(2000)
        .map(|f| {
            let (a, b) = (scr[f[0]], scr[f[1]]);
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt()
        })
        .sum::<f64>()
        / s.faces.len().clamp(1, 2000) as f64;
    let wire = s.wire && mean_edge > 9.0 * SS as f64;
    let half_line = 0.55 * SS as f64;
    for f in s.faces {
        let p = [scr[f[0]], scr[f[1]], scr[f[2]]];
        let hl = f
            .iter()
            .any(|&v| s.highlight.get(v).copied().unwrap_or(false));
        let base: Rgb = hex(if hl { HANDLE } else { BODY });
        let nrm = [normals[f[0]], normals[f[1]], normals[f[2]]];
        let tex = s
            .checker
            .map(|(uv, sz)| ([uv[f[0]], uv[f[1]], uv[f[2]]], sz));
        let centroid: [f64; 3] =
            std::array::from_fn(|i| (s.x[f[0]][i] + s.x[f[1]][i] + s.x[f[2]][i]) / 3.0);
        let to_eye = cam.eye_dir(centroid);
        triangle(layer, p, |b, dist| {
            let mut n: [f64; 3] = normalize(std::array::from_fn(|i| {
                b[0] * nrm[0][i] + b[1] * nrm[1][i] + b[2] * nrm[2][i]
            }));
            if dot(n, to_eye) < 0.0 {
                n = n.map(|c| -c);
            }
            let diffuse = 0.28 + 0.62 * dot(n, key).max(0.0) + 0.22 * dot(n, fill).max(0.0);
            let h = normalize(std::array::from_fn(|i| key[i] + to_eye[i]));
            let spec = 0.18 * dot(n, h).max(0.0).powi(24);
            let mut c = base;
            if let Some((uv, sz)) = &tex {
                let u = b[0] * uv[0][0] + b[1] * uv[1][0] + b[2] * uv[2][0];
                let v = b[0] * uv[0][1] + b[1] * uv[1][1] + b[2] * uv[2][1];
                let odd = ((u / sz).floor() as i64 + (v / sz).floor() as i64).rem_euclid(2) == 1;
                c = if odd { hex(0x2b4f81) } else { hex(0xf4f1ea) };
            }
            let mut out = scale(c, diffuse as f32);
            out = out.map(|x| x + spec as f32);
            if wire && dist.iter().fold(f64::INFINITY, |m, d| m.min(*d)) < half_line {
                out = scale(out, 0.72);
            }
            Some((out, 1.0))
        });
    }
}

/// A checker floor on the plane n·x = h around the body.
fn draw_ground(layer: &mut Layer, cam: &Camera, n: [f64; 3], h: f64, centre: [f64; 3], r: f64) {
    let o: [f64; 3] = std::array::from_fn(|i| centre[i] - (dot(centre, n) - h) * n[i]);
    let axes = [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0]];
    let a = axes
        .iter()
        .copied()
        .min_by(|p, q| dot(*p, n).abs().total_cmp(&dot(*q, n).abs()))
        .unwrap_or([1.0, 0.0, 0.0]);
    let e1 = normalize(sub(a, n.map(|c| c * dot(a, n))));
    let e2 = cross(n, e1);
    let ext = 2.2 * r;
    let tile = r / 3.0;
    let corner =
        |s: f64, t: f64| -> [f64; 3] { std::array::from_fn(|i| o[i] + s * e1[i] + t * e2[i]) };
    let q = [
        corner(-ext, -ext),
        corner(ext, -ext),
        corner(ext, ext),
        corner(-ext, ext),
    ];
    let st = [(-ext, -ext), (ext, -ext), (ext, ext), (-ext, ext)];
    let (lw, lh) = layer.size();
    let border = 0.08 * lw.min(lh);
    for tri in [[0, 1, 2], [0, 2, 3]] {
        let p = tri.map(|k| cam.project(q[k]));
        let uv = tri.map(|k| st[k]);
        triangle(layer, p, |b, _| {
            // fade out where the floor meets the edge of the layer
            let (sx, sy) = (
                b[0] * p[0][0] + b[1] * p[1][0] + b[2] * p[2][0],
                b[0] * p[0][1] + b[1] * p[1][1] + b[2] * p[2][1],
            );
            let edge = sx.min(sy).min(lw - sx).min(lh - sy) / border;
            let frame = edge.clamp(0.0, 1.0) as f32;
            let s = b[0] * uv[0].0 + b[1] * uv[1].0 + b[2] * uv[2].0;
            let t = b[0] * uv[0].1 + b[1] * uv[1].1 + b[2] * uv[2].1;
            let odd = ((s / tile).floor() as i64 + (t / tile).floor() as i64).rem_euclid(2) == 1;
            let c = if odd { hex(0xc9ccd1) } else { hex(0xe3e5e8) };
            // fade out into the background towards the edge of the floor
            let d = (s.abs().max(t.abs()) / ext).clamp(0.0, 1.0);
            Some((c, (1.0 - (d * d) as f32) * frame))
        });
    }
}

/// Darken the ground where the body's vertical projection falls (a contact
/// shadow): faces projected along `n` onto n·x = h, drawn into a mask.
fn draw_shadow(
    layer: &mut Layer,
    cam: &Camera,
    faces: &[[usize; 3]],
    x: &[[f64; 3]],
    n: [f64; 3],
    h: f64,
) {
    let mut mask = vec![false; layer.samples()];
    for f in faces {
        let p = f.map(|v| {
            let d = dot(x[v], n) - h;
            let q: [f64; 3] = std::array::from_fn(|i| x[v][i] - d * n[i]);
            let mut s = cam.project(q);
            s[2] *= 1.0 - 1e-4; // just in front of the floor
            s
        });
        cover(layer, p, |k| mask[k] = true);
    }
    layer.darken(&mask, 0.72);
}

/// One shot of the body (with ground and shadow) into a viewport of `pic`,
/// with fibre segments drawn over it when given.
#[allow(clippy::too_many_arguments)]
fn draw_shot(
    pic: &mut Picture,
    vp: (f64, f64, f64, f64),
    fit: &[[f64; 3]],
    faces: &[[usize; 3]],
    x: &[[f64; 3]],
    view: &View<'_>,
    sphere: ([f64; 3], f64),
    wire: bool,
    fibres: Option<(&[fibres::Segment], fibres::StretchScale)>,
) {
    let (centre, r) = sphere;
    let (dir, up) = orbit(view.up, view.camera.0, view.camera.1);
    let mut layer = Layer::new(vp);
    let cam = Camera::fit(centre, dir, up, 6.0 * r, fit, layer.viewport(4.0));
    if let Some((n, gh)) = view.ground {
        draw_ground(&mut layer, &cam, n, gh, centre, r);
        draw_shadow(&mut layer, &cam, faces, x, n, gh);
    }
    let scene = Scene3 {
        faces,
        x,
        highlight: view.highlight,
        checker: None,
        wire,
    };
    draw_body(&mut layer, &cam, &scene, up);
    if let Some((segs, scale)) = fibres {
        fibres::draw(&mut layer, &cam, segs, scale);
    }
    layer.composite(pic);
}

/// The boundary of a tet mesh in each shot; the last shot is the main panel,
/// with a strip of up to six thumbnails below when there are more than two.
pub fn volume(tets: &[[usize; 4]], shots: &[(usize, Vec<[f64; 3]>)], view: &View<'_>) -> Picture {
    volume_with(tets, shots, view, None)
}

/// [`volume`] with each element's deformed fibre direction drawn in the
/// main panel, coloured by stretch, with a legend (see `fibres`).
pub fn volume_fibres(
    tets: &[[usize; 4]],
    shots: &[(usize, Vec<[f64; 3]>)],
    view: &View<'_>,
    fibres: &Fibres<'_, 3>,
) -> Picture {
    volume_with(tets, shots, view, Some(fibres))
}

fn volume_with(
    tets: &[[usize; 4]],
    shots: &[(usize, Vec<[f64; 3]>)],
    view: &View<'_>,
    fibres: Option<&Fibres<'_, 3>>,
) -> Picture {
    let (w, h) = (view.size.0 as f64, view.size.1 as f64);
    let mut pic = Picture::new(view.size.0, view.size.1, [1.0; 3]);
    pic.gradient(hex(0xe9eef5), hex(0xfbfbfb));
    let faces = tet_boundary_faces(tets);
    let all: Vec<&[[f64; 3]]> = shots.iter().map(|(_, x)| x.as_slice()).collect();
    let Some((last_frame, last)) = shots.last() else {
        return pic;
    };
    let sphere = bounds(&all);
    let top = title_height(h);
    let strip = if shots.len() > 2 { 0.26 * h } else { 0.0 };
    let margin = 0.025 * w.min(h) + 4.0;
    let every: Vec<[f64; 3]> = all.iter().flat_map(|s| s.iter().copied()).collect();
    let main_vp = (margin, top, w - 2.0 * margin, h - top - strip - margin);
    // the main panel frames the result (with a ground: the whole motion
    // above it); thumbnails share one framing of all shots
    let main_pts: &[[f64; 3]] = if view.ground.is_some() { &every } else { last };
    let segs = fibres.map(|f| fibres::segments(tets, last, f));
    let overlay = segs.as_deref().map(|s| (s, fibres::StretchScale::of(s)));
    draw_shot(
        &mut pic, main_vp, main_pts, &faces, last, view, sphere, true, overlay,
    );
    title(
        &mut pic,
        view.title,
        &format!(
            "frame {last_frame}, {} tets, {} boundary faces",
            tets.len(),
            faces.len()
        ),
    );
    if let Some((_, scale)) = overlay {
        fibres::legend(&mut pic, scale);
    }
    if strip > 0.0 {
        let k = shots.len().min(6);
        let cell = (w - 2.0 * margin) / k as f64;
        let label = (0.022 * h).clamp(11.0, 18.0);
        let y0 = h - strip - 0.3 * margin;
        for j in 0..k {
            let i = j * (shots.len() - 1) / (k - 1).max(1);
            let card = (
                margin + j as f64 * cell + 0.04 * cell,
                y0 + 1.6 * label,
                0.92 * cell,
                strip - 1.6 * label,
            );
            pic.fill_rect(card.0, card.1, card.2, card.3, hex(0xffffff));
            draw_shot(
                &mut pic,
                card,
                &every,
                &faces,
                &shots[i].1,
                view,
                sphere,
                false,
                None,
            );
            let text = format!("frame {}", shots[i].0);
            pic.text(card.0, y0, &text, label, hex(0x404040), Orient::Across);
        }
    }
    pic
}
