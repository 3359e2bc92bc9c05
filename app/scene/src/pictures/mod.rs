//! Pictures and plots through maintained crates: tiny-skia for
//! anti-aliased 2D drawing, plotters (over a tiny-skia backend) for plots,
//! text in an embedded TrueType font (DejaVu Sans, rasterised by ab_glyph),
//! and a small z-buffer rasteriser, supersampled, for shaded 3D surfaces.
//! Every picture is written through one PNG encoder ([`Picture::to_png`]).
//!
//! * [`volume`]: the boundary of a tet mesh, shaded, from an orbit camera
//!   around the up direction (−gravity, else the ground normal, else +y),
//!   with handles in orange and the ground as a checker floor; a strip of
//!   thumbnails shows earlier frames.
//!   With fibres ([`volume_fibres`]), each skin element's deformed fibre
//!   direction F a is drawn through its centroid, coloured by √I5.
//! * [`planar`]: planar triangle meshes coloured by conformal distortion
//!   σ₁/σ₂, with the rest outline and handles; with fibres
//!   ([`planar_fibres`]) each triangle's F a is drawn the same way.
//! * [`parameterization`]: the surface with a checkerboard mapped through
//!   the uv map (a good map keeps squares square), next to the uv layout
//!   coloured by isometric distortion max(σ₁, 1/σ₂).
//! * [`convergence`]: ‖∇E‖∞ on a log scale against Newton iteration (per
//!   solve) and against the time spent in Newton solves, with the tolerance.
//! * [`Chart`]: line charts with linear or log axes and a legend (the
//!   convergence plot and the benchmark report's figures).

mod backend;
mod chart;
mod fibres;
mod image;
mod param;
mod planar;
mod plot;
mod raster;
mod text;
mod volume;

pub use chart::{Chart, Legend, PALETTE, Series};
pub use fibres::Fibres;
pub use image::{Orient, Picture, Rgb, hex, mix};
pub use param::parameterization;
pub use planar::{planar, planar_fibres};
pub use plot::convergence;
pub use volume::{volume, volume_fibres};

/// How to draw a body.
#[derive(Clone, Copy, Debug)]
pub struct View<'a> {
    /// Title text.
    pub title: &'a str,
    /// Picture size in pixels.
    pub size: (usize, usize),
    /// Camera azimuth and elevation (degrees) around `up`.
    pub camera: (f64, f64),
    /// Per-vertex handle flag.
    pub highlight: &'a [bool],
    /// Ground plane (unit normal, height), if any.
    pub ground: Option<([f64; 3], f64)>,
    /// Up direction.
    pub up: [f64; 3],
}

/// A blue → purple → red ramp for t ∈ [0, 1], dark enough everywhere to
/// read as a line on white (frames of a run in a plot).
pub(crate) fn ramp(t: f64) -> Rgb {
    let t = t.clamp(0.0, 1.0) as f32;
    let (blue, purple, red) = (hex(0x2166ac), hex(0x8e3f9e), hex(0xd7301f));
    if t < 0.5 {
        mix(blue, purple, 2.0 * t)
    } else {
        mix(purple, red, 2.0 * t - 1.0)
    }
}

/// A sequential ramp (light yellow → orange → dark red) for t ∈ [0, 1].
pub(crate) fn heat(t: f64) -> Rgb {
    let t = t.clamp(0.0, 1.0) as f32;
    let (a, b, c) = (hex(0xfff3c4), hex(0xf39c3d), hex(0x9e1b1b));
    if t < 0.5 {
        mix(a, b, 2.0 * t)
    } else {
        mix(b, c, 2.0 * t - 1.0)
    }
}

/// Singular values (σ₁ ≥ σ₂ ≥ 0) of a 2×2 matrix [[a, b], [c, d]].
pub(crate) fn sv2(a: f64, b: f64, c: f64, d: f64) -> (f64, f64) {
    let e = 0.5 * (a + d);
    let f = 0.5 * (a - d);
    let g = 0.5 * (c + b);
    let h = 0.5 * (c - b);
    let q = (e * e + h * h).sqrt();
    let r = (f * f + g * g).sqrt();
    (q + r, (q - r).abs())
}

/// Pixel size of a picture's title for a picture `h` pixels high.
pub(crate) fn title_size(h: f64) -> f64 {
    (0.032 * h).clamp(15.0, 30.0)
}

/// Height of the title bar of a picture `h` pixels high.
pub(crate) fn title_height(h: f64) -> f64 {
    2.2 * title_size(h)
}

/// Title bar: the title at the top-left, the subtitle after it in grey.
/// Returns the x where the text ends.
pub(crate) fn title(pic: &mut Picture, text: &str, sub: &str) -> f64 {
    let size = title_size(pic.height() as f64);
    let (x, y) = (0.6 * size, 0.5 * size);
    let mut end = x + pic.text(x, y, text, size, hex(0x202020), Orient::Across);
    if !sub.is_empty() {
        let small = (0.68 * size).max(12.0);
        // on the title's baseline
        let dy = text::ascent(size) - text::ascent(small);
        let sx = end + 0.8 * size;
        end = sx + pic.text(sx, y + dy, sub, small, hex(0x5a5a5a), Orient::Across);
    }
    end
}

/// A horizontal colour bar `w × h` at (x, y) for `colour(t)`, t ∈ [0, 1],
/// with tick labels at the given t and a caption to its right.
pub(crate) fn colour_bar(
    pic: &mut Picture,
    (x, y, w, h): (f64, f64, f64, f64),
    colour: impl Fn(f64) -> Rgb,
    ticks: &[(&str, f64)],
    caption: &str,
) {
    let n = w.ceil().max(1.0) as usize;
    for i in 0..n {
        let t = (i as f64 + 0.5) / n as f64;
        pic.fill_rect(x + i as f64, y, 1.0, h, colour(t));
    }
    let ink = hex(0x404040);
    let size = (1.3 * h).clamp(11.0, 18.0);
    for (label, t) in ticks {
        let tx = x + t * w;
        pic.line((tx, y + h), (tx, y + h + 0.35 * size), 1.0, ink);
        let lw = Picture::text_width(label, size);
        pic.text(
            tx - 0.5 * lw,
            y + h + 0.4 * size,
            label,
            size,
            ink,
            Orient::Across,
        );
    }
    let cy = y + 0.5 * h - 0.5 * text::line_height(size);
    pic.text(x + w + 0.7 * size, cy, caption, size, ink, Orient::Across);
}

#[cfg(test)]
mod tests;
