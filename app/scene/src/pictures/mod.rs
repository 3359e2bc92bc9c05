//! Pictures without heavy dependencies: a software rasteriser with a
//! z-buffer and Lambert shading, a 5×7 bitmap font, and PNG output.
//!
//! * [`volume`]: the boundary of a tet mesh, shaded, from an orbit camera
//!   around the up direction (−gravity, else the ground normal, else +y),
//!   with handles in orange and the ground as a checker floor; a strip of
//!   thumbnails shows earlier frames.
//! * [`planar`]: planar triangle meshes coloured by conformal distortion
//!   σ₁/σ₂, with the rest outline and handles.
//! * [`parameterization`]: the surface with a checkerboard mapped through
//!   the uv map (a good map keeps squares square), next to the uv layout
//!   coloured by isometric distortion max(σ₁, 1/σ₂).
//! * [`convergence`]: ‖∇E‖∞ on a log scale against Newton iteration (per
//!   solve) and against the time spent in Newton solves, with the tolerance.
//!
//! Everything is drawn at twice the size and box-filtered down (anti-aliasing).

mod font;
mod image;
mod param;
mod planar;
mod plot;
mod raster;
mod volume;

pub use image::{Picture, Rgb, hex, mix};
pub use param::parameterization;
pub use planar::planar;
pub use plot::convergence;
pub use volume::volume;

/// Supersampling factor.
pub(crate) const SS: usize = 2;

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

/// A blue → white → red ramp for t ∈ [0, 1].
pub(crate) fn ramp(t: f64) -> Rgb {
    let t = t.clamp(0.0, 1.0) as f32;
    let (blue, white, red) = (hex(0x3b6fb6), hex(0xf2efe9), hex(0xc8312c));
    if t < 0.5 {
        mix(blue, white, 2.0 * t)
    } else {
        mix(white, red, 2.0 * t - 1.0)
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

/// Title bar: the title at the top-left of a supersampled picture.
pub(crate) fn title(pic: &mut Picture, text: &str, sub: &str) {
    let s = SS as i64;
    pic.text(14 * s, 10 * s, text, 2 * s, hex(0x202020));
    if !sub.is_empty() {
        let x = 14 * s + Picture::text_width(text, 2 * s) + 14 * s;
        pic.text(x, 14 * s, sub, s, hex(0x606060));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn singular_values_of_2x2() {
        let (s1, s2) = sv2(3.0, 0.0, 0.0, -2.0);
        assert!((s1 - 3.0).abs() < 1e-12 && (s2 - 2.0).abs() < 1e-12);
        let (s1, s2) = sv2(1.0, 1.0, 0.0, 1.0);
        // golden ratio pair
        assert!((s1 * s2 - 1.0).abs() < 1e-12 && (s1 - 1.618_033_988_749_895).abs() < 1e-12);
    }
}
