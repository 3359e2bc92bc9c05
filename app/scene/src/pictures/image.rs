//! An RGB float image with the few drawing primitives the pictures need:
//! rectangles, thick lines (disc stamping), text (the built-in bitmap
//! font), box downsampling for anti-aliasing, and PNG encoding (`png` crate).

use super::font;

/// An RGB colour with components in [0, 1].
pub type Rgb = [f32; 3];

/// A picture: `w × h` pixels, row-major from the top-left corner.
#[derive(Clone, Debug, PartialEq)]
pub struct Picture {
    /// Width in pixels.
    pub w: usize,
    /// Height in pixels.
    pub h: usize,
    /// Pixels.
    pub px: Vec<Rgb>,
}

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

impl Picture {
    /// A picture filled with `bg`.
    pub fn new(w: usize, h: usize, bg: Rgb) -> Self {
        Picture {
            w,
            h,
            px: vec![bg; w * h],
        }
    }

    /// Set a pixel (ignored outside the picture).
    #[inline]
    pub fn set(&mut self, x: i64, y: i64, c: Rgb) {
        if x >= 0 && y >= 0 && (x as usize) < self.w && (y as usize) < self.h {
            self.px[y as usize * self.w + x as usize] = c;
        }
    }

    /// Blend a colour over a pixel with opacity `a`.
    #[inline]
    pub fn blend(&mut self, x: i64, y: i64, c: Rgb, a: f32) {
        if x >= 0 && y >= 0 && (x as usize) < self.w && (y as usize) < self.h {
            let p = &mut self.px[y as usize * self.w + x as usize];
            *p = mix(*p, c, a.clamp(0.0, 1.0));
        }
    }

    /// Fill the rectangle [x0, x1) × [y0, y1).
    pub fn fill_rect(&mut self, x0: i64, y0: i64, x1: i64, y1: i64, c: Rgb) {
        for y in y0.max(0)..y1.min(self.h as i64) {
            for x in x0.max(0)..x1.min(self.w as i64) {
                self.set(x, y, c);
            }
        }
    }

    /// A vertical gradient from `top` to `bottom`.
    pub fn gradient(&mut self, top: Rgb, bottom: Rgb) {
        for y in 0..self.h {
            let c = mix(top, bottom, y as f32 / self.h.max(1) as f32);
            self.px[y * self.w..(y + 1) * self.w].fill(c);
        }
    }

    /// A filled disc of radius `r` (pixel centres within r).
    pub fn disc(&mut self, cx: f64, cy: f64, r: f64, c: Rgb) {
        let (x0, x1) = ((cx - r).floor() as i64, (cx + r).ceil() as i64);
        let (y0, y1) = ((cy - r).floor() as i64, (cy + r).ceil() as i64);
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (dx, dy) = (x as f64 + 0.5 - cx, y as f64 + 0.5 - cy);
                if dx * dx + dy * dy <= r * r {
                    self.set(x, y, c);
                }
            }
        }
    }

    /// A line of the given width (discs stamped every half pixel).
    pub fn line(&mut self, a: (f64, f64), b: (f64, f64), width: f64, c: Rgb) {
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let n = (len * 2.0).ceil().max(1.0) as usize;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            self.disc(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1), 0.5 * width, c);
        }
    }

    /// A dashed line.
    pub fn dashed(&mut self, a: (f64, f64), b: (f64, f64), width: f64, dash: f64, c: Rgb) {
        let len = ((b.0 - a.0).powi(2) + (b.1 - a.1).powi(2)).sqrt();
        let n = (len / dash).ceil().max(1.0) as usize;
        for i in (0..n).step_by(2) {
            let (t0, t1) = (i as f64 / n as f64, ((i + 1) as f64 / n as f64).min(1.0));
            let p = |t: f64| (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
            self.line(p(t0), p(t1), width, c);
        }
    }

    /// Draw `text` with its top-left corner at (x, y), glyph pixels `scale` wide.
    pub fn text(&mut self, x: i64, y: i64, text: &str, scale: i64, c: Rgb) {
        let mut cx = x;
        for ch in text.chars() {
            let g = font::glyph(ch);
            for (row, bits) in g.iter().enumerate() {
                for col in 0..font::WIDTH {
                    if bits & (1 << (font::WIDTH - 1 - col)) != 0 {
                        let px = cx + col as i64 * scale;
                        let py = y + row as i64 * scale;
                        self.fill_rect(px, py, px + scale, py + scale, c);
                    }
                }
            }
            cx += font::ADVANCE as i64 * scale;
        }
    }

    /// Draw text rotated by +90° (reading bottom to top), its baseline start at (x, y).
    pub fn text_vertical(&mut self, x: i64, y: i64, text: &str, scale: i64, c: Rgb) {
        let mut cy = y;
        for ch in text.chars() {
            let g = font::glyph(ch);
            for (row, bits) in g.iter().enumerate() {
                for col in 0..font::WIDTH {
                    if bits & (1 << (font::WIDTH - 1 - col)) != 0 {
                        let px = x + row as i64 * scale;
                        let py = cy - (col as i64 + 1) * scale;
                        self.fill_rect(px, py, px + scale, py + scale, c);
                    }
                }
            }
            cy -= font::ADVANCE as i64 * scale;
        }
    }

    /// Width in pixels of `text` at `scale`.
    pub fn text_width(text: &str, scale: i64) -> i64 {
        text.chars().count() as i64 * font::ADVANCE as i64 * scale - scale
    }

    /// Copy `other` with its top-left corner at (x, y).
    pub fn paste(&mut self, other: &Picture, x: i64, y: i64) {
        for j in 0..other.h {
            for i in 0..other.w {
                self.set(x + i as i64, y + j as i64, other.px[j * other.w + i]);
            }
        }
    }

    /// Average `k × k` blocks (anti-aliasing of a supersampled picture).
    pub fn downsample(&self, k: usize) -> Picture {
        let (w, h) = (self.w / k, self.h / k);
        let mut out = Picture::new(w, h, [0.0; 3]);
        let inv = 1.0 / (k * k) as f32;
        for y in 0..h {
            for x in 0..w {
                let mut acc = [0.0f32; 3];
                for dy in 0..k {
                    let row = &self.px[(y * k + dy) * self.w + x * k..];
                    for p in &row[..k] {
                        acc[0] += p[0];
                        acc[1] += p[1];
                        acc[2] += p[2];
                    }
                }
                out.px[y * w + x] = scale(acc, inv);
            }
        }
        out
    }

    /// 8-bit RGB PNG bytes.
    pub fn to_png(&self) -> Vec<u8> {
        let mut bytes = Vec::new();
        let data: Vec<u8> = self
            .px
            .iter()
            .flat_map(|p| p.map(|c| (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8))
            .collect();
        {
            let mut enc = png::Encoder::new(&mut bytes, self.w as u32, self.h as u32);
            enc.set_color(png::ColorType::Rgb);
            enc.set_depth(png::BitDepth::Eight);
            enc.set_compression(png::Compression::High);
            // writing into a Vec cannot fail except for a size overflow,
            // which the picture sizes (≤ 8192²) rule out
            if let Ok(mut w) = enc.write_header() {
                let _ = w.write_image_data(&data);
            }
        }
        bytes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn png_round_trips_size_and_colour() {
        let mut p = Picture::new(8, 4, hex(0x336699));
        p.set(1, 1, [1.0, 0.0, 0.0]);
        let bytes = p.to_png();
        let dec = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut r = dec.read_info().unwrap();
        let mut buf = vec![0; r.output_buffer_size().unwrap()];
        let info = r.next_frame(&mut buf).unwrap();
        assert_eq!((info.width, info.height), (8, 4));
        assert_eq!(&buf[0..3], &[0x33, 0x66, 0x99]);
        assert_eq!(&buf[(8 + 1) * 3..(8 + 1) * 3 + 3], &[255, 0, 0]);
    }

    #[test]
    fn downsample_averages() {
        let mut p = Picture::new(2, 2, [0.0; 3]);
        p.set(0, 0, [1.0; 3]);
        let d = p.downsample(2);
        assert_eq!(d.px, vec![[0.25; 3]]);
    }
}
