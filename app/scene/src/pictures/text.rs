//! Text in the embedded TrueType font (DejaVu Sans, `assets/fonts/`, with
//! its licence): glyph outlines rasterised by `ab_glyph` into a coverage
//! mask, which the pictures blend in any of four orientations. Nothing is
//! looked up on the system: the font is compiled into the binary.

use std::sync::LazyLock;

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};

/// DejaVu Sans 2.37 (Bitstream Vera licence, see `assets/fonts/LICENSE`).
const DEJAVU_SANS: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

static FONT: LazyLock<FontRef<'static>> = LazyLock::new(|| {
    // the bytes are a fixed, embedded font; `embedded_font_parses` checks them
    FontRef::try_from_slice(DEJAVU_SANS).expect("the embedded DejaVu Sans parses")
});

/// A line of text rasterised at a pixel size: coverage in [0, 1], row-major,
/// `w × h`, the top row at the font's ascent line.
#[derive(Clone, Debug)]
pub(crate) struct Mask {
    pub w: usize,
    pub h: usize,
    pub cov: Vec<f32>,
}

/// Width (advances plus kerning) of `text` at pixel size `size`.
pub(crate) fn width(text: &str, size: f64) -> f64 {
    let font = FONT.as_scaled(PxScale::from(size as f32));
    let mut x = 0.0f32;
    let mut prev = None;
    for ch in text.chars() {
        let id = font.glyph_id(ch);
        if let Some(p) = prev {
            x += font.kern(p, id);
        }
        x += font.h_advance(id);
        prev = Some(id);
    }
    x as f64
}

/// Line height (ascent − descent) at pixel size `size`.
pub(crate) fn line_height(size: f64) -> f64 {
    let font = FONT.as_scaled(PxScale::from(size as f32));
    (font.ascent() - font.descent()) as f64
}

/// Ascent (top of the line box to the baseline) at pixel size `size`.
pub(crate) fn ascent(size: f64) -> f64 {
    FONT.as_scaled(PxScale::from(size as f32)).ascent() as f64
}

/// Rasterise one line of text at pixel size `size`.
pub(crate) fn rasterise(text: &str, size: f64) -> Mask {
    let scale = PxScale::from(size as f32);
    let font = FONT.as_scaled(scale);
    let ascent = font.ascent();
    let w = width(text, size).ceil() as usize + 2;
    let h = line_height(size).ceil() as usize + 1;
    let mut cov = vec![0.0f32; w * h];
    let mut caret = 0.0f32;
    let mut prev = None;
    for ch in text.chars() {
        let id = font.glyph_id(ch);
        if let Some(p) = prev {
            caret += font.kern(p, id);
        }
        let glyph = id.with_scale_and_position(scale, point(caret, ascent));
        caret += font.h_advance(id);
        prev = Some(id);
        let Some(outline) = FONT.outline_glyph(glyph) else {
            continue; // a space
        };
        let bb = outline.px_bounds();
        outline.draw(|gx, gy, c| {
            let x = bb.min.x as i64 + gx as i64;
            let y = bb.min.y as i64 + gy as i64;
            if x >= 0 && y >= 0 && (x as usize) < w && (y as usize) < h {
                let k = y as usize * w + x as usize;
                cov[k] = (cov[k] + c).min(1.0);
            }
        });
    }
    Mask { w, h, cov }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_font_parses_and_has_the_glyphs_the_labels_use() {
        for ch in "g‖∇E‖∞σ₁×ρ⁻⁰¹²³⁴⁵⁶⁷⁸⁹–".chars() {
            assert_ne!(FONT.glyph_id(ch).0, 0, "no glyph for {ch:?}");
        }
    }

    #[test]
    fn descenders_reach_below_the_baseline() {
        // "g" has a descender, "s" has none: the 5×7 font drew them alike
        let g = rasterise("g", 40.0);
        let s = rasterise("s", 40.0);
        let below = |m: &Mask| {
            let base = ascent(40.0).ceil() as usize + 2;
            (base..m.h)
                .flat_map(|y| (0..m.w).map(move |x| (x, y)))
                .filter(|&(x, y)| m.cov[y * m.w + x] > 0.5)
                .count()
        };
        assert!(below(&g) > 20, "g: {}", below(&g));
        assert_eq!(below(&s), 0);
        assert!(width("gg", 20.0) > width("g", 20.0));
    }
}
