//! Flat drawings of planar triangle meshes (deformations and uv layouts).

use super::image::{Picture, Rgb, hex};
use super::raster::{ZBuffer, triangle};
use super::{SS, View, heat, sv2, title};

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

/// Fill triangles with per-triangle colours and optional dark edges.
pub(crate) fn fill_tris(
    pic: &mut Picture,
    fit: &Fit2,
    tris: &[[usize; 3]],
    x: &[[f64; 2]],
    colour: &[Rgb],
    edges: bool,
) {
    let mut zb = ZBuffer::new(pic);
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
    let wire = edges && mean_edge > 7.0 * SS as f64;
    let n = tris.len() as f64;
    for (k, t) in tris.iter().enumerate() {
        // later triangles on top (inverted ones may overlap)
        let depth = 1.0 - k as f64 / (n + 1.0);
        let p = t.map(|v| [scr[v].0, scr[v].1, depth]);
        let c = colour[k];
        triangle(pic, &mut zb, p, |_, dist| {
            if wire && dist.iter().fold(f64::INFINITY, |m, d| m.min(*d)) < 0.8 * SS as f64 {
                Some(c.map(|v| v * 0.55))
            } else {
                Some(c)
            }
        });
        // the rasteriser fills by orientation-independent edge tests
    }
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

fn draw_state(
    pic: &mut Picture,
    fit: &Fit2,
    tris: &[[usize; 3]],
    rest: &[[f64; 2]],
    x: &[[f64; 2]],
    view: &View<'_>,
    detail: bool,
) {
    if let Some((n, h)) = view.ground {
        // shade the half-plane n·p < h across the viewport
        let (nx, ny) = (n[0], n[1]);
        for py in 0..pic.h {
            for px in 0..pic.w {
                let p = [
                    (px as f64 + 0.5 - fit.ox) / fit.s,
                    (fit.oy - py as f64 - 0.5) / fit.s,
                ];
                if nx * p[0] + ny * p[1] < h {
                    let stripe = ((px + py) / (6 * SS)).is_multiple_of(2);
                    pic.blend(
                        px as i64,
                        py as i64,
                        if stripe { hex(0xb9bcc2) } else { hex(0xd3d5d9) },
                        0.85,
                    );
                }
            }
        }
    }
    if detail {
        for (a, b) in boundary_edges(tris) {
            pic.line(
                fit.map(rest[a]),
                fit.map(rest[b]),
                1.2 * SS as f64,
                hex(0xb5b5b5),
            );
        }
    }
    let colours = distortion_colours(tris, rest, x);
    fill_tris(pic, fit, tris, x, &colours, detail);
    for (v, p) in x.iter().enumerate() {
        if view.highlight.get(v).copied().unwrap_or(false) {
            let (sx, sy) = fit.map(*p);
            pic.disc(sx, sy, 2.2 * SS as f64, hex(0xee7d3b));
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
    let (w, h) = (view.size.0 * SS, view.size.1 * SS);
    let mut pic = Picture::new(w, h, hex(0xfbfbfb));
    let Some((last_frame, last)) = shots.last() else {
        return pic.downsample(SS);
    };
    let mut every: Vec<[f64; 2]> = rest.to_vec();
    for (_, x) in shots {
        every.extend_from_slice(x);
    }
    let top = 44.0 * SS as f64;
    let margin = 24.0 * SS as f64;
    let strip = if shots.len() > 2 {
        0.26 * h as f64
    } else {
        0.0
    };
    // the main panel frames the result; thumbnails share one framing of all shots
    let fit = Fit2::new(
        last,
        (
            margin,
            top,
            w as f64 - 2.0 * margin,
            h as f64 - top - strip - margin,
        ),
    );
    draw_state(&mut pic, &fit, tris, rest, last, view, true);
    title(
        &mut pic,
        view.title,
        &format!(
            "frame {last_frame}   {} triangles, colour = conformal distortion",
            tris.len()
        ),
    );
    if strip > 0.0 {
        let k = shots.len().min(6);
        let cell = (w as f64 - 2.0 * margin) / k as f64;
        let y0 = h as f64 - strip - 0.3 * margin;
        for j in 0..k {
            let i = j * (shots.len() - 1) / (k - 1).max(1);
            let vp = (
                margin + j as f64 * cell + 6.0 * SS as f64,
                y0 + 18.0 * SS as f64,
                cell - 12.0 * SS as f64,
                strip - 24.0 * SS as f64,
            );
            let mut cellpic = Picture::new(w, h, hex(0xffffff));
            let f = Fit2::new(&every, vp);
            draw_state(&mut cellpic, &f, tris, rest, &shots[i].1, view, false);
            // copy the cell's viewport
            for py in (vp.1 as usize)..((vp.1 + vp.3) as usize).min(h) {
                for px in (vp.0 as usize)..((vp.0 + vp.2) as usize).min(w) {
                    pic.px[py * w + px] = cellpic.px[py * w + px];
                }
            }
            pic.text(
                vp.0 as i64,
                y0 as i64,
                &format!("frame {}", shots[i].0),
                SS as i64,
                hex(0x404040),
            );
        }
    }
    pic.downsample(SS)
}
