//! Flat drawings of planar triangle meshes (deformations and uv layouts).

use ecc_mesh::geometry::signed_area_uv;

use super::fibres::{self, Fibres, Segment, StretchScale};
use super::image::{Orient, Picture, Rgb, hex};
use super::{View, colour_bar, heat, sv2, title, title_height};

/// A 2D → screen map fitted to a box (y up on screen).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fit2 {
    s: f64,
    ox: f64,
    oy: f64,
}

impl Fit2 {
    /// Fit the points into the viewport `(x, y, w, h)`.
    pub(crate) fn new(points: &[[f64; 2]], vp: (f64, f64, f64, f64)) -> Self {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points {
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
        if !(hi[0] >= lo[0]) {
            lo = [0.0; 2];
            hi = [1.0; 2];
        }
        let s = (vp.2 / (hi[0] - lo[0]).max(1e-12)).min(vp.3 / (hi[1] - lo[1]).max(1e-12));
        let (cx, cy) = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]));
        Fit2 {
            s,
            ox: vp.0 + 0.5 * vp.2 - s * cx,
            oy: vp.1 + 0.5 * vp.3 + s * cy,
        }
    }

    /// Screen position.
    pub(crate) fn map(&self, p: [f64; 2]) -> (f64, f64) {
        (self.ox + self.s * p[0], self.oy - self.s * p[1])
    }
}

/// Longest screen edge (pixels) of a triangle drawn by [`Picture::splat`].
const SPLAT_MAX_EDGE: f64 = 1.0;

/// Fill triangles with per-triangle colours (anti-aliased, later triangles
/// on top: inverted ones may overlap; sub-pixel triangles are composited
/// together after the others) and, when `edges` and the triangles are large
/// enough on screen, a faint wireframe.
pub(crate) fn fill_tris(
    pic: &mut Picture,
    fit: &Fit2,
    tris: &[[usize; 3]],
    x: &[[f64; 2]],
    colour: &[Rgb],
    edges: bool,
) {
    let scr: Vec<(f64, f64)> = x.iter().map(|p| fit.map(*p)).collect();
    let mean_edge = tris
        .iter()
        .take(2000)
        .map(|t| {
            let (a, b) = (scr[t[0]], scr[t[1]]);
            ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt()
        })
        .sum::<f64>()
        / tris.len().clamp(1, 2000) as f64;
    // triangles below a pixel are splatted (tent filter), the others filled
    // as anti-aliased paths: a 1M-triangle layout took 1.4 s as paths
    let mut pieces = Vec::new();
    for (t, c) in tris.iter().zip(colour) {
        let p = t.map(|v| scr[v]);
        let d2 = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2);
        let longest = d2(p[0], p[1]).max(d2(p[1], p[2])).max(d2(p[2], p[0]));
        if longest < SPLAT_MAX_EDGE * SPLAT_MAX_EDGE {
            let centre = (
                (p[0].0 + p[1].0 + p[2].0) / 3.0,
                (p[0].1 + p[1].1 + p[2].1) / 3.0,
            );
            let area = signed_area_uv(p[0].into(), p[1].into(), p[2].into()).abs();
            pieces.push((centre, area, *c));
        } else {
            pic.tile(&p, *c, 0.6);
        }
    }
    pic.splat(&pieces);
    if edges && mean_edge > 7.0 {
        let segs: Vec<_> = all_edges(tris)
            .into_iter()
            .map(|(a, b)| (scr[a], scr[b]))
            .collect();
        pic.segments(&segs, 0.7, hex(0x000000), 0.28);
    }
}

/// Every edge once.
fn all_edges(tris: &[[usize; 3]]) -> Vec<(usize, usize)> {
    let mut e: Vec<(usize, usize)> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    e.sort_unstable();
    e.dedup();
    e
}

/// Boundary edges (edges used by one triangle).
pub(crate) fn boundary_edges(tris: &[[usize; 3]]) -> Vec<(usize, usize)> {
    let mut e: Vec<(usize, usize)> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    e.sort_unstable();
    let mut out = Vec::new();
    let mut i = 0;
    while i < e.len() {
        let mut j = i + 1;
        while j < e.len() && e[j] == e[i] {
            j += 1;
        }
        if j - i == 1 {
            out.push(e[i]);
        }
        i = j;
    }
    out
}

/// Per-triangle conformal distortion σ₁/σ₂ of the map rest → x, as a colour.
fn distortion_colours(tris: &[[usize; 3]], rest: &[[f64; 2]], x: &[[f64; 2]]) -> Vec<Rgb> {
    tris.iter()
        .map(|t| {
            let (r0, r1, r2) = (rest[t[0]], rest[t[1]], rest[t[2]]);
            let (x0, x1, x2) = (x[t[0]], x[t[1]], x[t[2]]);
            let dm = [r1[0] - r0[0], r2[0] - r0[0], r1[1] - r0[1], r2[1] - r0[1]];
            let ds = [x1[0] - x0[0], x2[0] - x0[0], x1[1] - x0[1], x2[1] - x0[1]];
            let det_m = dm[0] * dm[3] - dm[1] * dm[2];
            let det_s = ds[0] * ds[3] - ds[1] * ds[2];
            if det_s * det_m <= 0.0 {
                return hex(0x5b2a86);
            }
            let inv = [dm[3] / det_m, -dm[1] / det_m, -dm[2] / det_m, dm[0] / det_m];
            let f = [
                ds[0] * inv[0] + ds[1] * inv[2],
                ds[0] * inv[1] + ds[1] * inv[3],
                ds[2] * inv[0] + ds[3] * inv[2],
                ds[2] * inv[1] + ds[3] * inv[3],
            ];
            let (s1, s2) = sv2(f[0], f[1], f[2], f[3]);
            heat((s1 / s2.max(1e-300)).ln() / 3f64.ln())
        })
        .collect()
}

/// The part of the rectangle `(x, y, w, h)` where `f < 0` (f affine).
fn clip_half((x, y, w, h): (f64, f64, f64, f64), f: impl Fn((f64, f64)) -> f64) -> Vec<(f64, f64)> {
    let rect = [(x, y), (x + w, y), (x + w, y + h), (x, y + h)];
    let mut out = Vec::new();
    for i in 0..4 {
        let (a, b) = (rect[i], rect[(i + 1) % 4]);
        let (fa, fb) = (f(a), f(b));
        if fa < 0.0 {
            out.push(a);
        }
        if (fa < 0.0) != (fb < 0.0) {
            let t = fa / (fa - fb);
            out.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
        }
    }
    out
}

/// How one state is drawn: its frame (clip box of the ground), whether in
/// detail (main panel: rest outline, wireframe, bigger handles) and the
/// fibres drawn over it.
struct Panel<'a> {
    frame: (f64, f64, f64, f64),
    detail: bool,
    fibres: Option<(&'a [Segment], StretchScale)>,
}

fn draw_state(
    pic: &mut Picture,
    fit: &Fit2,
    tris: &[[usize; 3]],
    rest: &[[f64; 2]],
    x: &[[f64; 2]],
    view: &View<'_>,
    panel: &Panel<'_>,
) {
    let (frame, detail) = (panel.frame, panel.detail);
    if let Some((n, h)) = view.ground {
        // the half-plane n·p < h, hatched
        let world = |(sx, sy): (f64, f64)| {
            let p = [(sx - fit.ox) / fit.s, (fit.oy - sy) / fit.s];
            n[0] * p[0] + n[1] * p[1] - h
        };
        let poly = clip_half(frame, world);
        if poly.len() >= 3 {
            pic.hatch(&poly, hex(0xdfe1e5), hex(0xa9adb4), 7.0);
        }
    }
    if detail {
        let outline: Vec<_> = boundary_edges(tris)
            .into_iter()
            .map(|(a, b)| (fit.map(rest[a]), fit.map(rest[b])))
            .collect();
        pic.segments(&outline, 1.2, hex(0xa8a8a8), 1.0);
    }
    let colours = distortion_colours(tris, rest, x);
    fill_tris(pic, fit, tris, x, &colours, detail);
    let boundary: Vec<_> = boundary_edges(tris)
        .into_iter()
        .map(|(a, b)| (fit.map(x[a]), fit.map(x[b])))
        .collect();
    pic.segments(
        &boundary,
        if detail { 1.1 } else { 0.8 },
        hex(0x3a3a3a),
        0.9,
    );
    if let Some((segs, scale)) = panel.fibres {
        fibres::draw_flat(pic, fit, segs, scale);
    }
    let r = if detail { 3.2 } else { 2.0 };
    for (v, p) in x.iter().enumerate() {
        if view.highlight.get(v).copied().unwrap_or(false) {
            let (sx, sy) = fit.map(*p);
            pic.disc(sx, sy, r + 0.8, hex(0x7a3410));
            pic.disc(sx, sy, r, hex(0xee7d3b));
        }
    }
}

/// A planar triangle body in each shot (last = main panel), coloured by
/// conformal distortion σ₁/σ₂ (light = conformal, dark red = 3 or more,
/// purple = inverted), with the rest outline in grey.
pub fn planar(
    tris: &[[usize; 3]],
    rest: &[[f64; 2]],
    shots: &[(usize, Vec<[f64; 2]>)],
    view: &View<'_>,
) -> Picture {
    planar_with(tris, rest, shots, view, None)
}

/// [`planar`] with each triangle's deformed fibre direction F a drawn in
/// the main panel, coloured by stretch √I5, with the legend of the volume
/// pictures (see `fibres`) above the body.
pub fn planar_fibres(
    tris: &[[usize; 3]],
    shots: &[(usize, Vec<[f64; 2]>)],
    view: &View<'_>,
    fibres: &Fibres<'_, 2>,
) -> Picture {
    planar_with(tris, fibres.rest, shots, view, Some(fibres))
}

fn planar_with(
    tris: &[[usize; 3]],
    rest: &[[f64; 2]],
    shots: &[(usize, Vec<[f64; 2]>)],
    view: &View<'_>,
    fibres: Option<&Fibres<'_, 2>>,
) -> Picture {
    let (w, h) = (view.size.0 as f64, view.size.1 as f64);
    let mut pic = Picture::new(view.size.0, view.size.1, hex(0xfbfbfb));
    let Some((last_frame, last)) = shots.last() else {
        return pic;
    };
    let mut every: Vec<[f64; 2]> = rest.to_vec();
    for (_, x) in shots {
        every.extend_from_slice(x);
    }
    let top = title_height(h);
    let margin = 0.025 * w.min(h) + 4.0;
    let bar = (0.02 * h).clamp(8.0, 14.0);
    let legend = 3.2 * bar;
    let strip = if shots.len() > 2 { 0.26 * h } else { 0.0 };
    // the main panel frames the result; thumbnails share one framing of all shots
    // with fibres, their legend gets a row of its own under the title
    let key = if fibres.is_some() {
        fibres::legend_height(h)
    } else {
        0.0
    };
    let main_vp = (
        margin,
        top + key,
        w - 2.0 * margin,
        h - top - key - strip - margin - legend,
    );
    let fit = Fit2::new(last, main_vp);
    let segs = fibres.map(|f| fibres::planar_segments(tris, last, f));
    let panel = Panel {
        frame: main_vp,
        detail: true,
        fibres: segs.as_deref().map(|s| (s, StretchScale::of(s))),
    };
    draw_state(&mut pic, &fit, tris, rest, last, view, &panel);
    title(
        &mut pic,
        view.title,
        &format!("frame {last_frame}, {} triangles", tris.len()),
    );
    if let Some((_, scale)) = panel.fibres {
        fibres::legend(&mut pic, scale);
    }
    let by = main_vp.1 + main_vp.3 + 0.6 * bar;
    colour_bar(
        &mut pic,
        (margin, by, (0.3 * w).min(260.0), bar),
        heat,
        &[("1", 0.0), ("√3", 0.5), ("3+", 1.0)],
        "conformal distortion σ₁/σ₂ (purple: inverted)",
    );
    if strip > 0.0 {
        let k = shots.len().min(6);
        let cell = (w - 2.0 * margin) / k as f64;
        let label = (0.022 * h).clamp(11.0, 18.0);
        let y0 = h - strip - 0.3 * margin;
        for j in 0..k {
            let i = j * (shots.len() - 1) / (k - 1).max(1);
            let (cw, ch) = (0.92 * cell, strip - 1.6 * label);
            let mut card = Picture::new(cw as usize, ch as usize, hex(0xffffff));
            let f = Fit2::new(&every, (4.0, 4.0, cw - 8.0, ch - 8.0));
            let thumb = Panel {
                frame: (0.0, 0.0, cw, ch),
                detail: false,
                fibres: None,
            };
            draw_state(&mut card, &f, tris, rest, &shots[i].1, view, &thumb);
            let cx = margin + j as f64 * cell + 0.04 * cell;
            pic.paste(&card, cx as i64, (y0 + 1.6 * label) as i64);
            let text = format!("frame {}", shots[i].0);
            pic.text(cx, y0, &text, label, hex(0x404040), Orient::Across);
        }
    }
    pic
}
