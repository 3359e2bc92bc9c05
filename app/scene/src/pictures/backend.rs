//! A plotters drawing backend over a [`Picture`]: lines, polygons, circles
//! and rectangles are anti-aliased tiny-skia paths, text is the embedded
//! font ([`super::text`]). Plotters then needs neither its bitmap backend
//! nor a font feature (no system font lookup at run time).
//!
//! Plotters hands integer pixel coordinates; 1-pixel lines are drawn through
//! pixel centres (+½) so that axes and grid lines stay crisp.

use std::convert::Infallible;

use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
    FontTransform,
};

use super::image::{Orient, Picture, Rgb};
use super::text;

/// Plotters draws into this picture.
pub(crate) struct SkiaBackend<'a> {
    pic: &'a mut Picture,
}

impl<'a> SkiaBackend<'a> {
    pub(crate) fn new(pic: &'a mut Picture) -> Self {
        SkiaBackend { pic }
    }
}

fn rgb(c: BackendColor) -> Rgb {
    let (r, g, b) = c.rgb;
    [r as f32 / 255.0, g as f32 / 255.0, b as f32 / 255.0]
}

/// Pixel centre of an integer coordinate.
fn centre(p: BackendCoord) -> (f64, f64) {
    (p.0 as f64 + 0.5, p.1 as f64 + 0.5)
}

type Res = Result<(), DrawingErrorKind<Infallible>>;

impl DrawingBackend for SkiaBackend<'_> {
    type ErrorType = Infallible;

    fn get_size(&self) -> (u32, u32) {
        (self.pic.width() as u32, self.pic.height() as u32)
    }

    fn ensure_prepared(&mut self) -> Res {
        Ok(())
    }

    fn present(&mut self) -> Res {
        Ok(())
    }

    fn draw_pixel(&mut self, p: BackendCoord, c: BackendColor) -> Res {
        let (x, y) = (p.0 as f64, p.1 as f64);
        let pts = [(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)];
        self.pic.polygon(&pts, rgb(c), c.alpha as f32);
        Ok(())
    }

    fn draw_line<S: BackendStyle>(&mut self, a: BackendCoord, b: BackendCoord, s: &S) -> Res {
        let c = s.color();
        let w = s.stroke_width().max(1) as f64;
        self.pic
            .polyline(&[centre(a), centre(b)], w, rgb(c), c.alpha as f32, None);
        Ok(())
    }

    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        s: &S,
        fill: bool,
    ) -> Res {
        let c = s.color();
        if fill {
            let (x0, y0, x1, y1) = (a.0 as f64, a.1 as f64, b.0 as f64 + 1.0, b.1 as f64 + 1.0);
            let pts = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)];
            self.pic.polygon(&pts, rgb(c), c.alpha as f32);
        } else {
            let (p, q) = (centre(a), centre(b));
            let pts = [(p.0, p.1), (q.0, p.1), (q.0, q.1), (p.0, q.1), (p.0, p.1)];
            let w = s.stroke_width().max(1) as f64;
            self.pic.polyline(&pts, w, rgb(c), c.alpha as f32, None);
        }
        Ok(())
    }

    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Res {
        let c = s.color();
        let pts: Vec<(f64, f64)> = path.into_iter().map(centre).collect();
        let w = s.stroke_width().max(1) as f64;
        self.pic.polyline(&pts, w, rgb(c), c.alpha as f32, None);
        Ok(())
    }

    fn draw_circle<S: BackendStyle>(&mut self, at: BackendCoord, r: u32, s: &S, fill: bool) -> Res {
        let c = s.color();
        let (x, y) = centre(at);
        if fill {
            self.pic.disc(x, y, r as f64, rgb(c));
        } else {
            let n = 48;
            let pts: Vec<(f64, f64)> = (0..=n)
                .map(|k| {
                    let t = std::f64::consts::TAU * k as f64 / n as f64;
                    (x + r as f64 * t.cos(), y + r as f64 * t.sin())
                })
                .collect();
            let w = s.stroke_width().max(1) as f64;
            self.pic.polyline(&pts, w, rgb(c), c.alpha as f32, None);
        }
        Ok(())
    }

    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        s: &S,
    ) -> Res {
        let c = s.color();
        let pts: Vec<(f64, f64)> = vert.into_iter().map(centre).collect();
        self.pic.polygon(&pts, rgb(c), c.alpha as f32);
        Ok(())
    }

    fn draw_text<T: BackendTextStyle>(&mut self, s: &str, style: &T, pos: BackendCoord) -> Res {
        let size = style.size();
        let (w, h) = (text::width(s, size), text::line_height(size));
        // the anchor offset in the text's own frame, as plotters' default does
        let dx = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Right => -w,
            HPos::Center => -0.5 * w,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0.0,
            VPos::Center => -0.5 * h,
            VPos::Bottom => -h,
        };
        let (x, y) = (pos.0 as f64, pos.1 as f64);
        let c = rgb(style.color());
        match style.transform() {
            // reading upwards: the text's x runs along −y, its y along +x
            FontTransform::Rotate270 => self.pic.text(x + dy, y - dx, s, size, c, Orient::Up),
            _ => self.pic.text(x + dx, y + dy, s, size, c, Orient::Across),
        };
        Ok(())
    }

    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        s: &str,
        style: &T,
    ) -> Result<(u32, u32), DrawingErrorKind<Infallible>> {
        let size = style.size();
        Ok((
            text::width(s, size).ceil() as u32,
            text::line_height(size).ceil() as u32,
        ))
    }
}
