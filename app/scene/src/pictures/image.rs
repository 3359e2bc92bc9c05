//! The picture: a tiny-skia pixmap with the few drawing operations the
//! pictures and plots need — anti-aliased polygons, strokes (solid or
//! dashed), discs and text in the embedded font — and the one PNG encoder
//! (`png` crate) every picture and plot is written through.

use tiny_skia::{
    Color, FillRule, LineCap, LineJoin, Mask, Paint, PathBuilder, Pixmap, PixmapPaint, Stroke,
    StrokeDash, Transform,
};

use super::text;

/// An RGB colour with components in [0, 1].
pub type Rgb = [f32; 3];

/// Hex colour `0xRRGGBB` as [`Rgb`].
pub const fn hex(c: u32) -> Rgb {
    [
        ((c >> 16) & 0xff) as f32 / 255.0,
        ((c >> 8) & 0xff) as f32 / 255.0,
        (c & 0xff) as f32 / 255.0,
    ]
}

/// Linear interpolation of colours.
pub fn mix(a: Rgb, b: Rgb, t: f32) -> Rgb {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

/// Scale a colour.
pub fn scale(a: Rgb, s: f32) -> Rgb {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// A tiny-skia colour with opacity `alpha` (components clamped to [0, 1]).
pub(crate) fn color(c: Rgb, alpha: f32) -> Color {
    let [r, g, b] = c.map(|v| v.clamp(0.0, 1.0));
    Color::from_rgba(r, g, b, alpha.clamp(0.0, 1.0)).unwrap_or(Color::BLACK)
}

fn paint(c: Rgb, alpha: f32) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(color(c, alpha));
    p.anti_alias = true;
    p
}

/// A point in pixels.
pub type Px = (f64, f64);

/// Text orientation: reading left to right, or bottom to top (y labels).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orient {
    /// Horizontal.
    Across,
    /// Rotated by 90° counter-clockwise.
    Up,
}

/// A picture: an opaque `width × height` RGBA pixmap.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    pix: Pixmap,
}

impl Picture {
    /// A picture filled with `bg` (sizes below 1 pixel become 1).
    pub fn new(w: usize, h: usize, bg: Rgb) -> Self {
        let (w, h) = (w.clamp(1, 16384) as u32, h.clamp(1, 16384) as u32);
        // non-zero sizes up to 16384² always allocate a pixmap
        let mut pix = Pixmap::new(w, h).unwrap_or_else(|| unreachable!("{w}×{h} pixmap"));
        pix.fill(color(bg, 1.0));
        Picture { pix }
    }

    /// Width in pixels.
    pub fn width(&self) -> usize {
        self.pix.width() as usize
    }

    /// Height in pixels.
    pub fn height(&self) -> usize {
        self.pix.height() as usize
    }

    /// The 8-bit RGB colour of a pixel (black outside the picture).
    pub fn rgb(&self, x: usize, y: usize) -> [u8; 3] {
        self.pix
            .pixel(x as u32, y as u32)
            .map(|p| {
                let c = p.demultiply();
                [c.red(), c.green(), c.blue()]
            })
            .unwrap_or([0; 3])
    }

    pub(crate) fn pixmap_mut(&mut self) -> &mut Pixmap {
        &mut self.pix
    }

    /// Fill the rectangle at (x, y) of size w × h.
    pub fn fill_rect(&mut self, x: f64, y: f64, w: f64, h: f64, c: Rgb) {
        let pts = [(x, y), (x + w, y), (x + w, y + h), (x, y + h)];
        self.polygon(&pts, c, 1.0);
    }

    /// A vertical gradient from `top` to `bottom` over the whole picture.
    pub fn gradient(&mut self, top: Rgb, bottom: Rgb) {
        let h = self.height().max(1);
        let w = self.width();
        for (y, row) in self.pix.pixels_mut().chunks_mut(w).enumerate() {
            let c = color(mix(top, bottom, y as f32 / h as f32), 1.0)
                .premultiply()
                .to_color_u8();
            row.fill(c);
        }
    }

    /// Fill a closed polygon with opacity `alpha` (anti-aliased).
    pub fn polygon(&mut self, pts: &[(f64, f64)], c: Rgb, alpha: f32) {
        if let Some(path) = polygon_path(pts) {
            let p = paint(c, alpha);
            self.pix
                .fill_path(&path, &p, FillRule::Winding, Transform::identity(), None);
        }
    }

    /// Composite sub-pixel pieces, each a (position, area in pixels²,
    /// colour): a piece adds its area-weighted colour to the four pixels
    /// around it with bilinear weights (a tent filter: uniform pieces sum to
    /// a uniform coverage, where binning by the containing pixel would
    /// mottle), and every pixel reached is then covered by min(Σ area, 1) of
    /// their mean colour — anti-aliasing in the limit of pieces much smaller
    /// than a pixel (a dense mesh's triangles), one pass over the pieces
    /// instead of one anti-aliased path fill each.
    pub fn splat(&mut self, pieces: &[((f64, f64), f64, Rgb)]) {
        let (w, h) = (self.width(), self.height());
        let mut acc = vec![[0.0f32; 4]; w * h];
        let mut add = |i: i64, j: i64, a: f32, c: Rgb| {
            if i >= 0 && j >= 0 && (i as usize) < w && (j as usize) < h {
                let p = &mut acc[j as usize * w + i as usize];
                for k in 0..3 {
                    p[k] += a * c[k];
                }
                p[3] += a;
            }
        };
        for &((x, y), area, c) in pieces {
            // also rejects NaN positions and areas
            if !(x.is_finite() && y.is_finite() && area > 0.0) {
                continue;
            }
            // pixel centres at (i + ½, j + ½)
            let (u, v) = (x - 0.5, y - 0.5);
            let (i, j) = (u.floor(), v.floor());
            let (fx, fy) = ((u - i) as f32, (v - j) as f32);
            let (i, j, a) = (i as i64, j as i64, area as f32);
            add(i, j, a * (1.0 - fx) * (1.0 - fy), c);
            add(i + 1, j, a * fx * (1.0 - fy), c);
            add(i, j + 1, a * (1.0 - fx) * fy, c);
            add(i + 1, j + 1, a * fx * fy, c);
        }
        for (px, p) in self.pix.pixels_mut().iter_mut().zip(&acc) {
            if p[3] <= 0.0 {
                continue;
            }
            let cov = p[3].min(1.0);
            let old = px.demultiply();
            let mix = |o: u8, s: f32| {
                ((1.0 - cov) * o as f32 + cov * 255.0 * (s / p[3]))
                    .round()
                    .clamp(0.0, 255.0) as u8
            };
            let rgba = [
                mix(old.red(), p[0]),
                mix(old.green(), p[1]),
                mix(old.blue(), p[2]),
            ];
            if let Some(c) =
                tiny_skia::PremultipliedColorU8::from_rgba(rgba[0], rgba[1], rgba[2], 255)
            {
                *px = c;
            }
        }
    }

    /// Fill a closed polygon and stroke its outline `seam` pixels wide in
    /// the same colour: adjacent triangles then close their anti-aliased
    /// seams (coverage 1/2 + 1/2 would let the background through).
    pub fn tile(&mut self, pts: &[(f64, f64)], c: Rgb, seam: f64) {
        if let Some(path) = polygon_path(pts) {
            let p = paint(c, 1.0);
            let t = Transform::identity();
            self.pix.fill_path(&path, &p, FillRule::Winding, t, None);
            let s = Stroke {
                width: seam as f32,
                line_join: LineJoin::Round,
                ..Stroke::default()
            };
            self.pix.stroke_path(&path, &p, &s, t, None);
        }
    }

    /// An open polyline `width` pixels wide, dashed with period `2·dash` when
    /// `dash` is given, with opacity `alpha`.
    pub fn polyline(
        &mut self,
        pts: &[(f64, f64)],
        width: f64,
        c: Rgb,
        alpha: f32,
        dash: Option<f64>,
    ) {
        self.polyline_masked(pts, width, c, alpha, dash, None);
    }

    fn polyline_masked(
        &mut self,
        pts: &[(f64, f64)],
        width: f64,
        c: Rgb,
        alpha: f32,
        dash: Option<f64>,
        mask: Option<&Mask>,
    ) {
        let mut pb = PathBuilder::new();
        for (i, p) in pts.iter().enumerate() {
            if i == 0 {
                pb.move_to(p.0 as f32, p.1 as f32);
            } else {
                pb.line_to(p.0 as f32, p.1 as f32);
            }
        }
        let Some(path) = pb.finish() else { return };
        let s = Stroke {
            width: width as f32,
            line_cap: if dash.is_some() {
                LineCap::Butt
            } else {
                LineCap::Round
            },
            line_join: LineJoin::Round,
            dash: dash.and_then(|d| StrokeDash::new(vec![d as f32, d as f32], 0.0)),
            ..Stroke::default()
        };
        self.pix
            .stroke_path(&path, &paint(c, alpha), &s, Transform::identity(), mask);
    }

    /// Many segments as one stroke (overlaps at shared ends do not darken
    /// a translucent colour twice).
    pub fn segments(&mut self, segs: &[(Px, Px)], width: f64, c: Rgb, alpha: f32) {
        let mut pb = PathBuilder::new();
        for (a, b) in segs {
            pb.move_to(a.0 as f32, a.1 as f32);
            pb.line_to(b.0 as f32, b.1 as f32);
        }
        let Some(path) = pb.finish() else { return };
        let s = Stroke {
            width: width as f32,
            line_cap: LineCap::Round,
            ..Stroke::default()
        };
        self.pix
            .stroke_path(&path, &paint(c, alpha), &s, Transform::identity(), None);
    }

    /// A line segment.
    pub fn line(&mut self, a: (f64, f64), b: (f64, f64), width: f64, c: Rgb) {
        self.polyline(&[a, b], width, c, 1.0, None);
    }

    /// A line segment with square caps (a stroke that ends as far beyond
    /// its end points as it is wide on each side).
    pub fn bar(&mut self, a: (f64, f64), b: (f64, f64), width: f64, c: Rgb) {
        let mut pb = PathBuilder::new();
        pb.move_to(a.0 as f32, a.1 as f32);
        pb.line_to(b.0 as f32, b.1 as f32);
        let Some(path) = pb.finish() else { return };
        let s = Stroke {
            width: width as f32,
            line_cap: LineCap::Square,
            ..Stroke::default()
        };
        self.pix
            .stroke_path(&path, &paint(c, 1.0), &s, Transform::identity(), None);
    }

    /// A filled disc.
    pub fn disc(&mut self, cx: f64, cy: f64, r: f64, c: Rgb) {
        if let Some(path) = PathBuilder::from_circle(cx as f32, cy as f32, r as f32) {
            self.pix.fill_path(
                &path,
                &paint(c, 1.0),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
        }
    }

    /// Fill a polygon with `bg` and hatch it with diagonal `ink` lines every
    /// `spacing` pixels (a ground or a wall seen edge-on).
    pub fn hatch(&mut self, pts: &[(f64, f64)], bg: Rgb, ink: Rgb, spacing: f64) {
        let Some(path) = polygon_path(pts) else {
            return;
        };
        self.polygon(pts, bg, 0.85);
        let Some(mut mask) = Mask::new(self.pix.width(), self.pix.height()) else {
            return;
        };
        mask.fill_path(&path, FillRule::Winding, true, Transform::identity());
        let (w, h) = (self.width() as f64, self.height() as f64);
        let mut x = -h;
        while x < w {
            self.polyline_masked(&[(x, h), (x + h, 0.0)], 1.0, ink, 0.85, None, Some(&mask));
            x += spacing.max(2.0);
        }
    }

    /// Draw `text` at pixel size `size` with the top of its line box at
    /// (x, y) (for [`Orient::Up`]: the line box's left edge at x, the text
    /// starting at y and reading upwards). Returns the text's advance width.
    pub fn text(&mut self, x: f64, y: f64, s: &str, size: f64, c: Rgb, orient: Orient) -> f64 {
        let m = text::rasterise(s, size);
        let (x0, y0) = (x.round() as i64, y.round() as i64);
        let target = color(c, 1.0).premultiply();
        let (w, h) = (self.width() as i64, self.height() as i64);
        let px = self.pix.pixels_mut();
        for my in 0..m.h {
            for mx in 0..m.w {
                let a = m.cov[my * m.w + mx];
                if a <= 0.0 {
                    continue;
                }
                let (tx, ty) = match orient {
                    Orient::Across => (x0 + mx as i64, y0 + my as i64),
                    Orient::Up => (x0 + my as i64, y0 - mx as i64),
                };
                if tx < 0 || ty < 0 || tx >= w || ty >= h {
                    continue;
                }
                blend(&mut px[(ty * w + tx) as usize], target, a);
            }
        }
        text::width(s, size)
    }

    /// Advance width of `text` at pixel size `size`.
    pub fn text_width(s: &str, size: f64) -> f64 {
        text::width(s, size)
    }

    /// Copy `other` with its top-left corner at (x, y).
    pub fn paste(&mut self, other: &Picture, x: i64, y: i64) {
        self.pix.draw_pixmap(
            x as i32,
            y as i32,
            other.pix.as_ref(),
            &PixmapPaint::default(),
            Transform::identity(),
            None,
        );
    }

    /// 8-bit RGB PNG bytes (the pictures are opaque).
    pub fn to_png(&self) -> Vec<u8> {
        let data: Vec<u8> = self
            .pix
            .pixels()
            .iter()
            .flat_map(|p| {
                let c = p.demultiply();
                [c.red(), c.green(), c.blue()]
            })
            .collect();
        let mut bytes = Vec::new();
        {
            let mut enc = png::Encoder::new(&mut bytes, self.pix.width(), self.pix.height());
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            enc.set_compression(png::Compression::High);
            // writing into a Vec cannot fail except for a size overflow,
            // which the picture sizes (≤ 16384²) rule out
            if let Ok(mut w) = enc.write_header() {
                let _ = w.write_image_data(&data);
            }
        }
        bytes
    }
}

/// Source-over of a premultiplied colour with extra coverage `a`.
fn blend(dst: &mut tiny_skia::PremultipliedColorU8, src: tiny_skia::PremultipliedColor, a: f32) {
    let k = 1.0 - src.alpha() * a;
    let ch = |s: f32, d: u8| ((s * a * 255.0 + d as f32 * k).round()).clamp(0.0, 255.0) as u8;
    let (r, g, b, al) = (
        ch(src.red(), dst.red()),
        ch(src.green(), dst.green()),
        ch(src.blue(), dst.blue()),
        ch(src.alpha(), dst.alpha()),
    );
    // premultiplied channels never exceed alpha after source-over
    if let Some(p) = tiny_skia::PremultipliedColorU8::from_rgba(r.min(al), g.min(al), b.min(al), al)
    {
        *dst = p;
    }
}

fn polygon_path(pts: &[(f64, f64)]) -> Option<tiny_skia::Path> {
    let (first, rest) = pts.split_first()?;
    let mut pb = PathBuilder::new();
    pb.move_to(first.0 as f32, first.1 as f32);
    for p in rest {
        pb.line_to(p.0 as f32, p.1 as f32);
    }
    pb.close();
    pb.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
        let dec = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut r = dec.read_info().unwrap();
        let mut buf = vec![0; r.output_buffer_size().unwrap()];
        let info = r.next_frame(&mut buf).unwrap();
        (info.width, info.height, buf)
    }

    #[test]
    fn png_round_trips_size_and_colour() {
        let mut p = Picture::new(8, 4, hex(0x336699));
        p.fill_rect(1.0, 1.0, 1.0, 1.0, [1.0, 0.0, 0.0]);
        let (w, h, buf) = decode(&p.to_png());
        assert_eq!((w, h), (8, 4));
        assert_eq!(&buf[0..3], &[0x33, 0x66, 0x99]);
        assert_eq!(&buf[(8 + 1) * 3..(8 + 1) * 3 + 3], &[255, 0, 0]);
    }

    #[test]
    fn edges_are_anti_aliased() {
        // a black disc on white: its rim has grey pixels between 0 and 255
        let mut p = Picture::new(40, 40, [1.0; 3]);
        p.disc(20.0, 20.0, 12.3, [0.0; 3]);
        p.line((2.0, 3.0), (37.0, 11.0), 1.5, [0.0; 3]);
        let greys = (0..40)
            .flat_map(|y| (0..40).map(move |x| (x, y)))
            .filter(|&(x, y)| (20..235).contains(&p.rgb(x, y)[0]))
            .count();
        assert!(greys > 40, "{greys} intermediate pixels");
        assert_eq!(p.rgb(20, 20), [0, 0, 0]);
        assert_eq!(p.rgb(39, 39), [255, 255, 255]);
    }

    #[test]
    fn text_leaves_ink_inside_its_box_only() {
        let mut p = Picture::new(200, 60, [1.0; 3]);
        let w = p.text(10.0, 10.0, "gradient", 24.0, [0.0; 3], Orient::Across);
        assert!(w > 60.0 && w < 150.0, "width {w}");
        let ink = |x0: usize, x1: usize, y0: usize, y1: usize| {
            (y0..y1)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| p.rgb(x, y)[0] < 128)
                .count()
        };
        let lh = text::line_height(24.0).ceil() as usize;
        assert!(ink(10, 10 + w as usize + 1, 10, 10 + lh + 1) > 100);
        assert_eq!(ink(0, 200, 10 + lh + 2, 60), 0, "ink below the line box");
        assert_eq!(ink(12 + w as usize, 200, 0, 60), 0, "ink after the text");
        // upwards: the same ink, in a tall box
        let mut q = Picture::new(60, 200, [1.0; 3]);
        q.text(10.0, 190.0, "gradient", 24.0, [0.0; 3], Orient::Up);
        let tall = (0..200)
            .flat_map(|y| (0..60).map(move |x| (x, y)))
            .filter(|&(x, y)| q.rgb(x, y)[0] < 128);
        let (mut ylo, mut yhi) = (200, 0);
        for (_, y) in tall {
            (ylo, yhi) = (ylo.min(y), yhi.max(y));
        }
        assert!(yhi <= 190 && yhi - ylo > 60, "{ylo}..{yhi}");
    }
}
