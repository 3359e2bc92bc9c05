//! Line charts for the report, drawn with ecc-scene's software rasteriser
//! ([`ecc_scene::pictures::Picture`]: anti-aliased lines, the 5×7 ASCII font,
//! PNG output). Linear or log₁₀ axes, one colour per series, a legend, and
//! optional dashed horizontal reference lines. Labels must be ASCII (the
//! font has no other glyphs).

use ecc_scene::pictures::{Picture, Rgb, hex};

/// Supersampling factor (drawn at SS× then box-filtered).
const SS: usize = 2;

/// One curve.
#[derive(Clone, Debug)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Draw a dot at every point.
    pub dots: bool,
}

/// A chart.
#[derive(Clone, Debug, Default)]
pub struct Chart {
    pub title: String,
    pub xlabel: String,
    pub ylabel: String,
    pub log_x: bool,
    pub log_y: bool,
    pub series: Vec<Series>,
    /// Dashed horizontal lines at these y values.
    pub hlines: Vec<f64>,
}

/// The series palette (colour-blind-friendly, Okabe–Ito).
pub const PALETTE: [u32; 8] = [
    0x0072b2, 0xd55e00, 0x009e73, 0xcc79a7, 0xe69f00, 0x56b4e9, 0x000000, 0xf0e442,
];

fn colour(i: usize) -> Rgb {
    hex(PALETTE[i % PALETTE.len()])
}

fn nice_step(span: f64, n: f64) -> f64 {
    let raw = (span / n).max(1e-300);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 5.0 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

fn tick_label(v: f64, log: bool, step: f64) -> String {
    if log {
        return format!("1e{}", v.round() as i64);
    }
    if step >= 1.0 || v == 0.0 {
        format!("{v:.0}")
    } else {
        let digits = (-step.log10().floor()).max(0.0) as usize;
        format!("{v:.digits$}")
    }
}

impl Chart {
    fn tx(&self, x: f64) -> Option<f64> {
        let v = if self.log_x {
            (x > 0.0).then(|| x.log10())?
        } else {
            x
        };
        v.is_finite().then_some(v)
    }

    fn ty(&self, y: f64) -> Option<f64> {
        let v = if self.log_y {
            (y > 0.0).then(|| y.log10())?
        } else {
            y
        };
        v.is_finite().then_some(v)
    }

    /// Render to PNG bytes at `w`×`h` pixels.
    pub fn png(&self, w: usize, h: usize) -> Vec<u8> {
        self.picture(w, h).to_png()
    }

    /// Render to a picture at `w`×`h` pixels.
    pub fn picture(&self, w: usize, h: usize) -> Picture {
        let s = SS as f64;
        let si = SS as i64;
        let (pw, ph) = (w * SS, h * SS);
        let mut pic = Picture::new(pw, ph, hex(0xffffff));
        let ink = hex(0x303030);
        let grid = hex(0xe6e6e6);
        // data range
        let pts: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|se| {
                se.points
                    .iter()
                    .filter_map(|&(x, y)| Some((self.tx(x)?, self.ty(y)?)))
            })
            .collect();
        let hl: Vec<f64> = self.hlines.iter().filter_map(|&y| self.ty(y)).collect();
        let (mut x0, mut x1) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |a, p| {
            (a.0.min(p.0), a.1.max(p.0))
        });
        let (mut y0, mut y1) = pts
            .iter()
            .map(|p| p.1)
            .chain(hl.iter().copied())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |a, y| {
                (a.0.min(y), a.1.max(y))
            });
        if !x0.is_finite() {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        if !self.log_x && x0 > 0.0 {
            x0 = 0.0;
        }
        if x1 - x0 < 1e-12 {
            x1 = x0 + 1.0;
        }
        if self.log_y {
            y0 = y0.floor();
            y1 = y1.ceil();
        }
        if y1 - y0 < 1e-12 {
            y1 = y0 + 1.0;
        }
        if self.log_x {
            x0 = x0.floor();
            x1 = x1.ceil();
        }
        let (left, right, top, bottom) = (78.0 * s, 200.0 * s, 40.0 * s, 52.0 * s);
        let (aw, ah) = (pw as f64 - left - right, ph as f64 - top - bottom);
        let map = |x: f64, y: f64| {
            (
                left + aw * (x - x0) / (x1 - x0),
                top + ah * (1.0 - (y - y0) / (y1 - y0)),
            )
        };
        // y ticks
        let ystep = if self.log_y {
            ((y1 - y0) / 8.0).ceil().max(1.0)
        } else {
            nice_step(y1 - y0, 6.0)
        };
        let mut v = (y0 / ystep).ceil() * ystep;
        while v <= y1 + 1e-9 {
            let (_, py) = map(x0, v);
            pic.line((left, py), (left + aw, py), s, grid);
            let lab = tick_label(v, self.log_y, ystep);
            pic.text(
                left as i64 - Picture::text_width(&lab, si) - 6 * si,
                py as i64 - 3 * si,
                &lab,
                si,
                ink,
            );
            v += ystep;
        }
        let xstep = if self.log_x {
            ((x1 - x0) / 8.0).ceil().max(1.0)
        } else {
            nice_step(x1 - x0, 6.0)
        };
        let mut v = (x0 / xstep).ceil() * xstep;
        while v <= x1 + 1e-9 * (x1 - x0).abs().max(1.0) {
            let (px, _) = map(v, y0);
            pic.line((px, top), (px, top + ah), s, grid);
            let lab = tick_label(v, self.log_x, xstep);
            pic.text(
                px as i64 - Picture::text_width(&lab, si) / 2,
                (top + ah) as i64 + 7 * si,
                &lab,
                si,
                ink,
            );
            v += xstep;
        }
        for (a, b) in [
            ((left, top), (left + aw, top)),
            ((left + aw, top), (left + aw, top + ah)),
            ((left + aw, top + ah), (left, top + ah)),
            ((left, top + ah), (left, top)),
        ] {
            pic.line(a, b, 1.2 * s, ink);
        }
        for &y in &hl {
            let (_, py) = map(x0, y);
            pic.dashed((left, py), (left + aw, py), 1.2 * s, 6.0 * s, hex(0x909090));
        }
        for (i, se) in self.series.iter().enumerate() {
            let c = colour(i);
            let p: Vec<(f64, f64)> = se
                .points
                .iter()
                .filter_map(|&(x, y)| Some(map(self.tx(x)?, self.ty(y)?)))
                .collect();
            for win in p.windows(2) {
                pic.line(win[0], win[1], 1.8 * s, c);
            }
            if se.dots || p.len() == 1 {
                for q in &p {
                    pic.disc(q.0, q.1, 2.6 * s, c);
                }
            }
            // legend
            let ly = top + (8.0 + 16.0 * i as f64) * s;
            let lx = left + aw + 12.0 * s;
            pic.line((lx, ly), (lx + 18.0 * s, ly), 2.4 * s, c);
            pic.text(
                (lx + 24.0 * s) as i64,
                ly as i64 - 3 * si,
                &se.label,
                si,
                ink,
            );
        }
        pic.text(left as i64, 12 * si, &self.title, 2 * si, hex(0x202020));
        pic.text(
            (left + 0.5 * aw) as i64 - Picture::text_width(&self.xlabel, si) / 2,
            (top + ah) as i64 + 24 * si,
            &self.xlabel,
            si,
            ink,
        );
        pic.text_vertical(
            14 * si,
            (top + 0.5 * ah) as i64 + Picture::text_width(&self.ylabel, si) / 2,
            &self.ylabel,
            si,
            ink,
        );
        pic.downsample(SS)
    }
}
