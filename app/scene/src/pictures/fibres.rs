//! Fibres drawn over a body picture (issue #16): each element's deformed
//! fibre direction F a as a short anti-aliased segment through its centroid,
//! coloured by the fibre stretch √I5 = ‖F a‖ (a diverging map around 1 with
//! a legend). One routine ([`marks`]) thins the segments on screen and
//! places and colours them; the volume picture draws the marks into its
//! z-buffered layer ([`draw`]), the planar picture straight onto the
//! picture ([`draw_flat`]).
//!
//! **Which fibres.** Volume pictures draw the body opaque, so only elements
//! with a vertex on the boundary are candidates and their segments are
//! depth-tested with a bias of one element size towards the eye: the skin's
//! fibres show, those behind the body or deep inside it do not. Planar
//! pictures take every triangle. On big meshes the candidates are thinned
//! on screen: at most one segment per cell of [`CELL`] pixels, the nearest
//! (in 2D: the first) first — an even subsample, independent of the mesh
//! size.
//!
//! **Segments.** With F = Ds Dm⁻¹ (Ds, Dm the deformed and rest edge
//! matrices), F a = Ds (Dm⁻¹ a); the segment is centroid ± 0.35 ℓ F a, with
//! ℓ the element's mean rest edge length (its length shows the stretch too,
//! ‖F a‖ clamped to [¼, 3]), drawn as a dark halo under a coloured core.
//! Planar bodies are drawn as the z = 0 plane of the same construction.

use ecc_mesh::tet_boundary_faces;

use super::image::{Picture, Rgb, hex, mix};
use super::planar::Fit2;
use super::raster::{Camera, Layer, SS, dot, sub, triangle};
use super::{colour_bar, text, title_height};

/// Screen cell (pixels) holding at most one fibre.
pub const CELL: f64 = 16.0;

/// Half-width (pixels) of a fibre's coloured core; the dark halo adds
/// [`HALO`] on each side.
const CORE: f64 = 0.95;
const HALO: f64 = 0.9;
const HALO_INK: u32 = 0x1b1b1b;

/// Per-element fibre directions of a tet (`D = 3`) or triangle (`D = 2`)
/// mesh, in rest space.
#[derive(Clone, Copy, Debug)]
pub struct Fibres<'a, const D: usize> {
    /// Rest positions.
    pub rest: &'a [[f64; D]],
    /// One direction per element (any length; zero is skipped).
    pub dirs: &'a [[f64; D]],
}

/// Dm⁻¹ a (the fibre in the tet's edge coordinates) and the mean rest edge
/// length; `None` for a degenerate tet or a zero direction.
fn rest_fibre(rest: &[[f64; 3]], t: &[usize; 4], a: [f64; 3]) -> Option<([f64; 3], f64)> {
    let e: [[f64; 3]; 3] = std::array::from_fn(|k| sub(rest[t[k + 1]], rest[t[0]]));
    // Dm = [e0 e1 e2] (columns); solve Dm w = a by Cramer's rule
    let det = |c: [[f64; 3]; 3]| dot(c[0], super::raster::cross(c[1], c[2]));
    let d = det(e);
    let n = dot(a, a).sqrt();
    if d.abs() < 1e-300 || !d.is_finite() || n == 0.0 || !n.is_finite() {
        return None;
    }
    let a = a.map(|c| c / n);
    let w: [f64; 3] = std::array::from_fn(|k| {
        let mut c = e;
        c[k] = a;
        det(c) / d
    });
    let mut len = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            let v = sub(rest[t[i]], rest[t[j]]);
            len += dot(v, v).sqrt() / 6.0;
        }
    }
    Some((w, len))
}

/// One fibre segment of the current shot.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Segment {
    /// Centroid and F a (world).
    pub centre: [f64; 3],
    pub fa: [f64; 3],
    /// Mean rest edge length.
    pub len: f64,
}

impl Segment {
    /// √I5 = ‖F a‖.
    pub fn stretch(&self) -> f64 {
        dot(self.fa, self.fa).sqrt()
    }
}

/// The segments of the candidate tets (a vertex on the boundary) at `x`.
pub(crate) fn segments(tets: &[[usize; 4]], x: &[[f64; 3]], f: &Fibres<'_, 3>) -> Vec<Segment> {
    let mut on_skin = vec![false; x.len()];
    for face in tet_boundary_faces(tets) {
        for v in face {
            on_skin[v] = true;
        }
    }
    let mut out = Vec::new();
    for (t, tet) in tets.iter().enumerate() {
        if !tet.iter().any(|&v| on_skin[v]) {
            continue;
        }
        let Some((w, len)) = f.dirs.get(t).and_then(|a| rest_fibre(f.rest, tet, *a)) else {
            continue;
        };
        let fa: [f64; 3] = std::array::from_fn(|r| {
            (0..3)
                .map(|k| (x[tet[k + 1]][r] - x[tet[0]][r]) * w[k])
                .sum()
        });
        let centre = std::array::from_fn(|r| tet.iter().map(|&v| x[v][r]).sum::<f64>() / 4.0);
        if fa.iter().chain(&centre).all(|c| c.is_finite()) {
            out.push(Segment { centre, fa, len });
        }
    }
    out
}

/// The 2D [`rest_fibre`]: Dm⁻¹ a for a triangle and its mean rest edge
/// length; `None` for a degenerate triangle or a zero direction.
fn rest_fibre_2d(rest: &[[f64; 2]], t: &[usize; 3], a: [f64; 2]) -> Option<([f64; 2], f64)> {
    let e: [[f64; 2]; 2] =
        std::array::from_fn(|k| [0, 1].map(|r| rest[t[k + 1]][r] - rest[t[0]][r]));
    // Dm = [e0 e1] (columns): det Dm = e0 × e1
    let d = e[0][0] * e[1][1] - e[1][0] * e[0][1];
    let n = a[0].hypot(a[1]);
    if d.abs() < 1e-300 || !d.is_finite() || n == 0.0 || !n.is_finite() {
        return None;
    }
    let a = a.map(|c| c / n);
    let w = [
        (a[0] * e[1][1] - e[1][0] * a[1]) / d,
        (e[0][0] * a[1] - a[0] * e[0][1]) / d,
    ];
    let edge =
        |i: usize, j: usize| (rest[t[i]][0] - rest[t[j]][0]).hypot(rest[t[i]][1] - rest[t[j]][1]);
    let len = (edge(0, 1) + edge(1, 2) + edge(2, 0)) / 3.0;
    Some((w, len))
}

/// The segments of every triangle at `x`, in the z = 0 plane.
pub(crate) fn planar_segments(
    tris: &[[usize; 3]],
    x: &[[f64; 2]],
    f: &Fibres<'_, 2>,
) -> Vec<Segment> {
    let mut out = Vec::new();
    for (t, tri) in tris.iter().enumerate() {
        let Some((w, len)) = f.dirs.get(t).and_then(|a| rest_fibre_2d(f.rest, tri, *a)) else {
            continue;
        };
        let fa2: [f64; 2] = std::array::from_fn(|r| {
            (0..2)
                .map(|k| (x[tri[k + 1]][r] - x[tri[0]][r]) * w[k])
                .sum()
        });
        let c: [f64; 2] = std::array::from_fn(|r| tri.iter().map(|&v| x[v][r]).sum::<f64>() / 3.0);
        let (fa, centre) = ([fa2[0], fa2[1], 0.0], [c[0], c[1], 0.0]);
        if fa.iter().chain(&centre).all(|c| c.is_finite()) {
            out.push(Segment { centre, fa, len });
        }
    }
    out
}

/// The stretch colour scale: √I5 ∈ [1 − m, 1 + m] ↦ t ∈ [0, 1].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct StretchScale {
    pub m: f64,
}

impl StretchScale {
    /// Symmetric around 1, covering 95 % of the segments (a few extreme
    /// elements at a handle do not wash the colours out; beyond the range
    /// the end colours are used) and at least ±0.5 %.
    pub fn of(segs: &[Segment]) -> Self {
        let mut d: Vec<f64> = segs.iter().map(|s| (s.stretch() - 1.0).abs()).collect();
        d.sort_by(f64::total_cmp);
        let q = d
            .get((0.95 * d.len() as f64) as usize)
            .or(d.last())
            .copied()
            .unwrap_or(0.0);
        StretchScale { m: q.max(0.005) }
    }

    pub fn t(&self, stretch: f64) -> f64 {
        (0.5 + 0.5 * (stretch - 1.0) / self.m).clamp(0.0, 1.0)
    }
}

/// Diverging map: compressed green, unstretched white, stretched magenta
/// (ColorBrewer PiYG end points, light enough to read inside the dark halo
/// and distinct from the blue body and the orange handles).
pub(crate) fn stretch_colour(t: f64) -> Rgb {
    let t = t.clamp(0.0, 1.0) as f32;
    let (lo, mid, hi) = (hex(0x4dac26), hex(0xf7f7f7), hex(0xd01c8b));
    if t < 0.5 {
        mix(lo, mid, 2.0 * t)
    } else {
        mix(mid, hi, 2.0 * t - 1.0)
    }
}

/// A screen-space quad from a to b (samples, with depth) of half-width `hw`.
fn quad(layer: &mut Layer, a: [f64; 3], b: [f64; 3], hw: f64, c: Rgb) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l = (dx * dx + dy * dy).sqrt();
    if !(l > 1e-9) {
        return;
    }
    // extend by hw along the segment too (square caps), extrapolating the
    // depth linearly: halo and core then share one depth function
    let (ux, uy) = (dx / l * hw, dy / l * hw);
    let (nx, ny) = (-uy, ux);
    let dz = (b[2] - a[2]) * hw / l;
    let (za, zb) = (a[2] - dz, b[2] + dz);
    let p = [
        [a[0] - ux + nx, a[1] - uy + ny, za],
        [a[0] - ux - nx, a[1] - uy - ny, za],
        [b[0] + ux - nx, b[1] + uy - ny, zb],
        [b[0] + ux + nx, b[1] + uy + ny, zb],
    ];
    for tri in [[0, 1, 2], [0, 2, 3]] {
        triangle(layer, tri.map(|k| p[k]), |_, _| Some((c, 1.0)));
    }
}

/// One fibre as drawn: screen end points (x, y, depth), the depth bias and
/// the core colour.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Mark {
    pub a: [f64; 3],
    pub b: [f64; 3],
    /// The segment's mean rest edge length (volume pictures move the mark
    /// this far towards the eye).
    pub len: f64,
    pub colour: Rgb,
}

/// The marks of `segs` on a `size` screen (`project`: world → screen x, y
/// and depth): at most one per `cell × cell` square, nearest first, each
/// centroid ± 0.35 ℓ F a/‖F a‖·clamp(‖F a‖, ¼, 3), coloured by √I5.
pub(crate) fn marks(
    segs: &[Segment],
    scale: StretchScale,
    size: (f64, f64),
    cell: f64,
    project: impl Fn([f64; 3]) -> [f64; 3],
) -> Vec<Mark> {
    let (w, h) = size;
    let nx = (w / cell).ceil() as usize + 1;
    let ny = (h / cell).ceil() as usize + 1;
    let mut taken = vec![false; nx * ny];
    let mut order: Vec<([f64; 3], &Segment)> =
        segs.iter().map(|s| (project(s.centre), s)).collect();
    order.sort_by(|a, b| a.0[2].total_cmp(&b.0[2]));
    let mut out = Vec::new();
    for (p, s) in order {
        if !(p[0] >= 0.0 && p[1] >= 0.0 && p[0] < w && p[1] < h) {
            continue;
        }
        let k = (p[1] / cell) as usize * nx + (p[0] / cell) as usize;
        if std::mem::replace(&mut taken[k], true) {
            continue;
        }
        let st = s.stretch();
        let half = 0.35 * s.len * st.clamp(0.25, 3.0) / st.max(1e-300);
        let end = |sign: f64| project(std::array::from_fn(|i| s.centre[i] + sign * half * s.fa[i]));
        out.push(Mark {
            a: end(-1.0),
            b: end(1.0),
            len: s.len,
            colour: stretch_colour(scale.t(st)),
        });
    }
    out
}

/// Draw the fibres into `layer` (after the body): thinned on screen, nearest
/// first, depth-biased by one element size towards the eye.
pub(crate) fn draw(layer: &mut Layer, cam: &Camera, segs: &[Segment], scale: StretchScale) {
    let ss = SS as f64;
    for m in marks(segs, scale, layer.size(), CELL * ss, |q| cam.project(q)) {
        // depth towards the eye by one element size: the skin's fibres
        // pass the depth test against the surface they lie under
        let bias = |p: [f64; 3]| [p[0], p[1], p[2] - m.len];
        let (a, b) = (bias(m.a), bias(m.b));
        quad(layer, a, b, (CORE + HALO) * ss, hex(HALO_INK));
        let lift = |p: [f64; 3]| [p[0], p[1], p[2] * (1.0 - 1e-5)];
        quad(layer, lift(a), lift(b), CORE * ss, m.colour);
    }
}

/// Draw the fibres of a planar body onto `pic` (after the body) through the
/// body's screen map. Every triangle is a candidate, so the thinning cell
/// is also at least 1.5 mean segment lengths: neighbouring fibres along a
/// row do not run into one line.
pub(crate) fn draw_flat(pic: &mut Picture, fit: &Fit2, segs: &[Segment], scale: StretchScale) {
    let size = (pic.width() as f64, pic.height() as f64);
    let project = |q: [f64; 3]| {
        let (x, y) = fit.map([q[0], q[1]]);
        [x, y, 0.0]
    };
    // a segment's screen length: 0.7 ℓ clamp(‖F a‖, ¼, 3) times the map's scale
    let unit = {
        let (a, b) = (project([0.0; 3]), project([1.0, 0.0, 0.0]));
        (a[0] - b[0]).hypot(a[1] - b[1])
    };
    let mean = segs
        .iter()
        .map(|s| 0.7 * s.len * s.stretch().clamp(0.25, 3.0) * unit)
        .sum::<f64>()
        / segs.len().max(1) as f64;
    for m in marks(segs, scale, size, CELL.max(1.5 * mean), project) {
        let (a, b) = ((m.a[0], m.a[1]), (m.b[0], m.b[1]));
        pic.bar(a, b, 2.0 * (CORE + HALO), hex(HALO_INK));
        pic.bar(a, b, 2.0 * CORE, m.colour);
    }
}

/// Bar height and label size of the legend in a picture `h` pixels high.
fn legend_sizes(h: f64) -> (f64, f64) {
    let bh = (0.018 * h).clamp(8.0, 16.0);
    (bh, (1.3 * bh).clamp(11.0, 18.0))
}

/// Height of the legend's row (gap, bar, tick labels, gap) under the title
/// bar of a picture `h` pixels high.
pub(crate) fn legend_height(h: f64) -> f64 {
    let (bh, size) = legend_sizes(h);
    1.8 * bh + 0.4 * size + text::line_height(size)
}

/// The legend (colour bar of √I5) in the top-right corner, under the title bar.
pub(crate) fn legend(pic: &mut Picture, scale: StretchScale) {
    let (w, h) = (pic.width() as f64, pic.height() as f64);
    let top = title_height(h);
    let bw = (0.2 * w).clamp(90.0, 320.0);
    let (bh, size) = legend_sizes(h);
    let caption = "fibre stretch √I5";
    let cw = Picture::text_width(caption, size) + 0.7 * size;
    let x = w - bw - cw - 0.03 * w;
    let y = top + 0.4 * bh;
    let (lo, hi) = (
        format!("≤{:.3}", 1.0 - scale.m),
        format!("≥{:.3}", 1.0 + scale.m),
    );
    colour_bar(
        pic,
        (x, y, bw, bh),
        stretch_colour,
        &[(lo.as_str(), 0.0), ("1", 0.5), (hi.as_str(), 1.0)],
        caption,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rest_fibre_maps_back_to_the_direction_and_stretch_is_norm_fa() {
        let rest = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let t = [0, 1, 2, 3];
        let (w, len) = rest_fibre(&rest, &t, [0.0, 3.0, 4.0]).unwrap();
        assert!((w[0]).abs() < 1e-15 && (w[1] - 0.6).abs() < 1e-15 && (w[2] - 0.8).abs() < 1e-15);
        assert!((len - (3.0 + 3.0 * 2f64.sqrt()) / 6.0).abs() < 1e-15);
        // stretched by 2 along y: F a = (0, 1.2, 0.8), √I5 = √(1.44 + 0.64)
        let x: Vec<[f64; 3]> = rest.iter().map(|p| [p[0], 2.0 * p[1], p[2]]).collect();
        let f = Fibres::<3> {
            rest: &rest,
            dirs: &[[0.0, 3.0, 4.0]],
        };
        let s = segments(&[t], &x, &f);
        assert_eq!(s.len(), 1);
        assert!((s[0].stretch() - 2.08f64.sqrt()).abs() < 1e-14);
        assert!(rest_fibre(&rest, &t, [0.0; 3]).is_none());
        let flat = [[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        assert!(rest_fibre(&flat, &t, [1.0, 0.0, 0.0]).is_none());
    }

    #[test]
    fn planar_fibres_are_fa_through_the_centroid_in_the_plane() {
        let rest = [[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]];
        let t = [0, 1, 2];
        let (w, len) = rest_fibre_2d(&rest, &t, [3.0, 4.0]).unwrap();
        // Dm = diag(2, 1): Dm⁻¹ a = (0.3, 0.8)
        assert!((w[0] - 0.3).abs() < 1e-15 && (w[1] - 0.8).abs() < 1e-15);
        assert!((len - (3.0 + 5f64.sqrt()) / 3.0).abs() < 1e-15);
        // F = [[1, 1], [0, 2]] (a shear and a stretch): F a = (1.4, 1.6)
        let x: Vec<[f64; 2]> = rest.iter().map(|p| [p[0] + p[1], 2.0 * p[1]]).collect();
        let f = Fibres::<2> {
            rest: &rest,
            dirs: &[[3.0, 4.0]],
        };
        let s = planar_segments(&[t], &x, &f);
        assert_eq!(s.len(), 1);
        assert!((s[0].fa[0] - 1.4).abs() < 1e-14 && (s[0].fa[1] - 1.6).abs() < 1e-14);
        assert_eq!(s[0].fa[2], 0.0);
        let c = [1.0, 2.0 / 3.0, 0.0];
        assert!((0..3).all(|i| (s[0].centre[i] - c[i]).abs() < 1e-15));
        assert!(rest_fibre_2d(&rest, &t, [0.0; 2]).is_none());
        let flat = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert!(rest_fibre_2d(&flat, &t, [1.0, 0.0]).is_none());
    }

    #[test]
    fn marks_keep_one_per_cell_nearest_first() {
        let seg = |x: f64, z: f64| Segment {
            centre: [x, 5.0, z],
            fa: [1.0, 0.0, 0.0],
            len: 1.0,
        };
        // two in the first cell (the nearer, z = 1, wins), one in the
        // second, one off screen
        let segs = [seg(2.0, 3.0), seg(3.0, 1.0), seg(12.0, 2.0), seg(-1.0, 0.0)];
        let m = marks(&segs, StretchScale { m: 0.1 }, (20.0, 10.0), 10.0, |p| p);
        assert_eq!(m.len(), 2);
        assert_eq!(m[0].a, [3.0 - 0.35, 5.0, 1.0]);
        assert_eq!(m[1].b, [12.0 + 0.35, 5.0, 2.0]);
        assert_eq!(m[0].colour, hex(0xf7f7f7));
    }

    #[test]
    fn stretch_scale_is_symmetric_around_one() {
        let seg = |k: f64| Segment {
            centre: [0.0; 3],
            fa: [k, 0.0, 0.0],
            len: 1.0,
        };
        let sc = StretchScale::of(&[seg(0.9), seg(1.05)]);
        assert!((sc.m - 0.1).abs() < 1e-15);
        // one outlier in 40 does not set the range
        let mut many: Vec<Segment> = (0..39).map(|k| seg(1.0 + 0.001 * k as f64)).collect();
        many.push(seg(3.0));
        assert!((StretchScale::of(&many).m - 0.038).abs() < 1e-12);
        assert_eq!(StretchScale::of(&[seg(1.0)]).m, 0.005);
        assert_eq!(sc.t(1.0), 0.5);
        assert!((sc.t(0.9)).abs() < 1e-12 && sc.t(1.2) == 1.0);
        assert_eq!(stretch_colour(0.5), hex(0xf7f7f7));
        assert_eq!(stretch_colour(0.0), hex(0x4dac26));
    }
}
