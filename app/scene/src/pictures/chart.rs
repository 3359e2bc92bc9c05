//! Line charts through plotters (drawn by [`super::backend::SkiaBackend`]):
//! linear or log₁₀ axes (decades labelled 10ⁿ, minor ticks at 2…9·10ⁿ),
//! one colour per series, a legend beside the plot, and dashed horizontal
//! reference lines. Used by the convergence plot and the benchmark report.

use std::ops::Range;

use plotters::prelude::*;

use super::backend::SkiaBackend;
use super::image::{Orient, Picture, Rgb, hex};
use super::text;

/// The series palette (colour-blind-friendly, Okabe–Ito).
pub const PALETTE: [u32; 8] = [
    0x0072b2, 0xd55e00, 0x009e73, 0xcc79a7, 0xe69f00, 0x56b4e9, 0x000000, 0xf0e442,
];

const INK: u32 = 0x303030;
const GRID: u32 = 0xe3e3e3;
const REFERENCE: u32 = 0x2e8b57;

/// One curve.
#[derive(Clone, Debug, Default)]
pub struct Series {
    /// Legend text (empty: not in the legend).
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Draw a dot at every point.
    pub dots: bool,
    /// Colour; `None` takes the next palette colour.
    pub colour: Option<Rgb>,
}

/// A chart.
#[derive(Clone, Debug, Default)]
pub struct Chart {
    pub title: String,
    pub xlabel: String,
    pub ylabel: String,
    pub log_x: bool,
    pub log_y: bool,
    /// Ticks on whole numbers only (iteration counts).
    pub integer_x: bool,
    pub series: Vec<Series>,
    /// Dashed horizontal lines at these y values.
    pub hlines: Vec<f64>,
    /// Legend text of the dashed lines (empty: not in the legend).
    pub hline_label: String,
    /// Where the legend goes.
    pub legend: Legend,
}

/// Where a chart's legend goes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Legend {
    /// To the right of the plot.
    #[default]
    Beside,
    /// Not drawn by the chart (the caller shows [`Chart::legend_row`]).
    Hidden,
}

/// Tick label of `v` on a linear axis spanning `span`: two decimals below
/// the span's leading digit, trailing zeros dropped (plotters picks the
/// tick step; 0.5, 1, 1.5 all read right).
pub(crate) fn fmt_tick(v: f64, span: f64) -> String {
    let digits = (2.0 - span.max(1e-300).log10().floor()).max(0.0) as usize;
    let s = format!("{v:.digits$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" { "0".into() } else { s }
}

/// 10ⁿ with a superscript exponent.
pub(crate) fn decade(n: i64) -> String {
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits: String = n
        .unsigned_abs()
        .to_string()
        .bytes()
        .map(|b| SUP[(b - b'0') as usize])
        .collect();
    format!("10{}{digits}", if n < 0 { "⁻" } else { "" })
}

fn rgb8(c: Rgb) -> RGBColor {
    let [r, g, b] = c.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
    RGBColor(r, g, b)
}

/// One axis: its range in plotted coordinates (log₁₀ when `log`).
#[derive(Clone, Debug)]
struct Axis {
    log: bool,
    range: Range<f64>,
}

impl Axis {
    /// The axis over the plotted values `v` (already log₁₀ when `log`).
    fn fit(v: impl Iterator<Item = f64>, log: bool, from_zero: bool, pad: bool) -> Axis {
        let (mut lo, mut hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |a, x| {
            (a.0.min(x), a.1.max(x))
        });
        if !lo.is_finite() {
            (lo, hi) = (0.0, 1.0);
        }
        if from_zero && !log && lo > 0.0 {
            lo = 0.0;
        }
        if log {
            // whole decades, with points on a decade kept off the frame
            (lo, hi) = ((lo - 0.1).floor(), (hi + 0.1).ceil());
        } else if pad {
            let d = (hi - lo).max(1e-12);
            (lo, hi) = (lo - 0.04 * d, hi + 0.04 * d);
        }
        if hi - lo < 1e-12 {
            hi = lo + 1.0;
        }
        Axis { log, range: lo..hi }
    }

    /// Plotted coordinate of a data value (`None`: not on a log axis).
    fn to(&self, v: f64) -> Option<f64> {
        let t = if self.log {
            (v > 0.0).then(|| v.log10())?
        } else {
            v
        };
        t.is_finite().then_some(t)
    }

    /// How many labels to ask plotters for: whole decades on a log axis,
    /// whole numbers on an `integer` one.
    fn labels(&self, integer: bool) -> usize {
        let span = self.range.end - self.range.start;
        if (self.log || integer) && span <= 10.0 {
            span.round() as usize + 1
        } else {
            7
        }
    }

    fn label(&self, v: f64) -> String {
        if self.log {
            decade(v.round() as i64)
        } else {
            fmt_tick(v, self.range.end - self.range.start)
        }
    }

    /// Plotted coordinates of the minor ticks (2…9 × 10ⁿ) of a log axis
    /// spanning at most 8 decades.
    fn minor(&self) -> Vec<f64> {
        if !self.log || self.range.end - self.range.start > 8.0 {
            return Vec::new();
        }
        let mut out = Vec::new();
        let mut d = self.range.start.floor();
        while d < self.range.end {
            out.extend((2..10).map(|k| d + (k as f64).log10()));
            d += 1.0;
        }
        out
    }
}

/// One legend entry with its top-left at `at`: a line swatch, then the label.
fn legend_entry(pic: &mut Picture, at: (f64, f64), label: &str, c: Rgb, dashed: bool, size: f64) {
    let mid = at.1 + 0.5 * text::line_height(size);
    let seg = [(at.0, mid), (at.0 + 1.65 * size, mid)];
    pic.polyline(&seg, 2.2, c, 1.0, dashed.then_some(0.2 * size));
    pic.text(
        at.0 + 2.2 * size,
        at.1,
        label,
        size,
        hex(INK),
        Orient::Across,
    );
}

/// Pixel sizes of a chart's text and margins for an area `h` pixels high.
struct Sizes {
    label: f64,
    title: f64,
}

impl Sizes {
    fn new(w: f64, h: f64) -> Self {
        let label = (0.03 * h.min(1.4 * w)).clamp(12.0, 18.0);
        Sizes {
            label,
            title: 1.25 * label,
        }
    }
}

/// What plotters placed, for drawing after it: the plotting area and the
/// pixel positions of the reference lines and minor ticks.
struct Placed {
    area: (f64, f64, f64, f64),
    hlines: Vec<f64>,
    minor_x: Vec<f64>,
    minor_y: Vec<f64>,
}

impl Chart {
    /// Render to PNG bytes at `w`×`h` pixels.
    pub fn png(&self, w: usize, h: usize) -> Vec<u8> {
        self.picture(w, h).to_png()
    }

    /// Render to a picture at `w`×`h` pixels.
    pub fn picture(&self, w: usize, h: usize) -> Picture {
        let mut pic = Picture::new(w, h, hex(0xffffff));
        self.draw(&mut pic, (0.0, 0.0, w as f64, h as f64));
        pic
    }

    /// The x axis starts at 0 (linear) or spans whole decades (log); the
    /// y axis is padded (linear) or spans whole decades (log).
    fn axes(&self) -> (Axis, Axis) {
        let x = Axis::fit(self.points().map(|p| p.0), self.log_x, true, false);
        let hl: Vec<f64> = self
            .hlines
            .iter()
            .filter_map(|&y| self.y_axis().to(y))
            .collect();
        let y = Axis::fit(
            self.points().map(|p| p.1).chain(hl),
            self.log_y,
            false,
            true,
        );
        (x, y)
    }

    fn y_axis(&self) -> Axis {
        Axis {
            log: self.log_y,
            range: 0.0..1.0,
        }
    }

    /// Every plottable point in plotted coordinates.
    fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        let (ax, ay) = (
            Axis {
                log: self.log_x,
                range: 0.0..1.0,
            },
            self.y_axis(),
        );
        self.series.iter().flat_map(move |s| {
            let (ax, ay) = (ax.clone(), ay.clone());
            s.points
                .iter()
                .filter_map(move |&(x, y)| Some((ax.to(x)?, ay.to(y)?)))
        })
    }

    fn colour(&self, i: usize) -> Rgb {
        self.series[i]
            .colour
            .unwrap_or_else(|| hex(PALETTE[i % PALETTE.len()]))
    }

    /// Legend entries: (label, colour, dashed).
    fn legend(&self) -> Vec<(String, Rgb, bool)> {
        let mut out: Vec<(String, Rgb, bool)> = (0..self.series.len())
            .filter(|&i| !self.series[i].label.is_empty())
            .map(|i| (self.series[i].label.clone(), self.colour(i), false))
            .collect();
        if !self.hline_label.is_empty() && !self.hlines.is_empty() {
            out.push((self.hline_label.clone(), hex(REFERENCE), true));
        }
        out
    }

    /// Draw the chart into the rectangle `(x, y, w, h)` of `pic`.
    pub fn draw(&self, pic: &mut Picture, area: (f64, f64, f64, f64)) {
        let sz = Sizes::new(area.2, area.3);
        let legend = match self.legend {
            Legend::Beside => self.legend(),
            Legend::Hidden => Vec::new(),
        };
        let swatch = 2.2 * sz.label;
        let widest = legend
            .iter()
            .map(|(l, _, _)| text::width(l, sz.label))
            .fold(0.0, f64::max);
        let legend_w = if legend.is_empty() {
            0.5 * sz.label
        } else {
            (widest + swatch + 1.6 * sz.label).min(0.4 * area.2)
        };
        // plotters cannot fail on this backend but for a degenerate layout
        // (an area too small for its labels): then the chart stays blank
        let Ok(placed) = self.plot(pic, area, legend_w, &sz) else {
            return;
        };
        self.draw_extras(pic, &placed, &sz);
        let (ax, ay, aw, _) = placed.area;
        let (lx, mut ly) = (ax + aw + 0.8 * sz.label, ay + 0.3 * sz.label);
        for (label, c, dashed) in &legend {
            legend_entry(pic, (lx, ly), label, *c, *dashed, sz.label);
            ly += 1.45 * sz.label;
        }
    }

    /// The legend as one row ending at `right` with its top at `y`, text at
    /// pixel size `size` (for charts drawn with [`Legend::Hidden`]).
    pub fn legend_row(&self, pic: &mut Picture, right: f64, y: f64, size: f64) {
        let entries = self.legend();
        let gap = 1.2 * size;
        let width = |l: &str| 2.2 * size + text::width(l, size);
        let mut x = right - self.legend_row_width(size);
        for (label, c, dashed) in &entries {
            legend_entry(pic, (x, y), label, *c, *dashed, size);
            x += width(label) + gap;
        }
    }

    /// Width of [`Chart::legend_row`] at pixel size `size`.
    pub fn legend_row_width(&self, size: f64) -> f64 {
        let gap = 1.2 * size;
        let entries = self.legend();
        let sum: f64 = entries
            .iter()
            .map(|(l, _, _)| 2.2 * size + text::width(l, size) + gap)
            .sum();
        (sum - gap).max(0.0)
    }

    /// The axes, grid, labels and curves, through plotters.
    fn plot(
        &self,
        pic: &mut Picture,
        area: (f64, f64, f64, f64),
        legend_w: f64,
        sz: &Sizes,
    ) -> Result<Placed, Box<dyn std::error::Error + '_>> {
        let (x, y) = self.axes();
        let root = SkiaBackend::new(pic).into_drawing_area();
        let root = root.shrink(
            (area.0 as i32, area.1 as i32),
            ((area.2 - legend_w).max(1.0) as u32, area.3.max(1.0) as u32),
        );
        let font = |s: f64| ("sans-serif", s).into_font().color(&rgb8(hex(INK)));
        let mut b = ChartBuilder::on(&root);
        b.margin_top((0.6 * sz.label) as i32)
            .margin_right((0.6 * sz.label) as i32)
            .x_label_area_size((2.9 * sz.label) as i32)
            .y_label_area_size((4.4 * sz.label) as i32);
        if !self.title.is_empty() {
            b.caption(&self.title, font(sz.title));
        }
        let mut chart = b.build_cartesian_2d(x.range.clone(), y.range.clone())?;
        let xf = |v: &f64| x.label(*v);
        let yf = |v: &f64| y.label(*v);
        let ink = rgb8(hex(INK));
        chart
            .configure_mesh()
            .x_labels(x.labels(self.integer_x))
            .y_labels(y.labels(false))
            .x_label_formatter(&xf)
            .y_label_formatter(&yf)
            .x_desc(&self.xlabel)
            .y_desc(&self.ylabel)
            .label_style(font(sz.label))
            .axis_desc_style(font(sz.label))
            .bold_line_style(rgb8(hex(GRID)))
            .light_line_style(TRANSPARENT)
            .axis_style(ink)
            .set_all_tick_mark_size((0.4 * sz.label) as i32)
            .draw()?;
        for (i, s) in self.series.iter().enumerate() {
            let c = rgb8(self.colour(i));
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter_map(|&(px, py)| Some((x.to(px)?, y.to(py)?)))
                .collect();
            let line = ShapeStyle {
                color: c.to_rgba(),
                filled: false,
                stroke_width: 2,
            };
            chart.draw_series(LineSeries::new(pts.iter().copied(), line))?;
            if s.dots || pts.len() == 1 {
                let r = (0.2 * sz.label).round().max(2.0) as i32;
                chart.draw_series(pts.iter().map(|p| Circle::new(*p, r, c.filled())))?;
            }
        }
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let px = |v: f64| chart.backend_coord(&(v, y.range.start)).0 as f64 + 0.5;
        let py = |v: f64| chart.backend_coord(&(x.range.start, v)).1 as f64 + 0.5;
        Ok(Placed {
            area: (
                xr.start as f64,
                yr.start as f64,
                (xr.end - xr.start) as f64,
                (yr.end - yr.start) as f64,
            ),
            hlines: self
                .hlines
                .iter()
                .filter_map(|&v| Some(py(y.to(v)?)))
                .collect(),
            minor_x: x.minor().into_iter().map(px).collect(),
            minor_y: y.minor().into_iter().map(py).collect(),
        })
    }

    /// The frame, minor log ticks and dashed reference lines.
    fn draw_extras(&self, pic: &mut Picture, p: &Placed, sz: &Sizes) {
        let (x0, y0, w, h) = p.area;
        let (x1, y1) = (x0 + w - 0.5, y0 + h - 0.5);
        let (x0, y0) = (x0 + 0.5, y0 + 0.5);
        let ink = hex(INK);
        let frame = [(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)];
        pic.polyline(&frame, 1.0, ink, 1.0, None);
        let t = 0.3 * sz.label;
        for &mx in &p.minor_x {
            pic.line((mx, y1 - t), (mx, y1), 1.0, ink);
        }
        for &my in &p.minor_y {
            pic.line((x0, my), (x0 + t, my), 1.0, ink);
        }
        for &hy in &p.hlines {
            let dash = Some(0.35 * sz.label);
            pic.polyline(&[(x0, hy), (x1, hy)], 1.6, hex(REFERENCE), 1.0, dash);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels() {
        assert_eq!(fmt_tick(0.4, 1.5), "0.4");
        assert_eq!(fmt_tick(1.5, 3.5), "1.5");
        assert_eq!(fmt_tick(2.0, 3.5), "2");
        assert_eq!(fmt_tick(20.0, 76.0), "20");
        assert_eq!(fmt_tick(0.30000000000000004, 3.5), "0.3");
        assert_eq!(fmt_tick(-0.0, 1.0), "0");
        assert_eq!(fmt_tick(25000.0, 1e5), "25000");
        assert_eq!(decade(-12), "10⁻¹²");
        assert_eq!(decade(3), "10³");
        assert_eq!(decade(0), "10⁰");
    }

    #[test]
    fn log_axes_cover_whole_decades_with_minor_ticks() {
        let a = Axis::fit([-3.4, 1.2].into_iter(), true, false, true);
        assert_eq!(a.range, -4.0..2.0);
        assert_eq!(a.labels(false), 7);
        assert_eq!(a.minor().len(), 6 * 8);
        let b = Axis::fit([-10.0, -3.0].into_iter(), true, false, true);
        assert_eq!(b.range, -11.0..-2.0);
        assert_eq!(a.to(-1.0), None);
        assert_eq!(a.label(-4.0), "10⁻⁴");
    }
}
