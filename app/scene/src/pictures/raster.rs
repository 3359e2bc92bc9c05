//! A small software rasteriser for shaded 3D surfaces: a perspective camera
//! fitted to the points it must show, and z-buffered triangle filling with a
//! per-pixel shader into a supersampled layer ([`SS`]× per axis), which is
//! box-filtered down onto the picture — anti-aliased silhouettes and edges
//! (tiny-skia has no depth test, and a closed surface drawn in painter's
//! order would leak its back faces through anti-aliased seams).
//!
//! Triangles are filled with edge functions at sample centres; the shader
//! receives the barycentric coordinates and the sample distance to each
//! edge (for wireframe overlays). Depth is interpolated linearly in screen
//! space, which is exact enough for a depth test of small triangles.

use super::image::{Picture, Rgb};

/// Supersampling factor of a layer, per axis (9 samples per pixel).
pub(crate) const SS: usize = 3;
/// 3-vector helpers.
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
/// Dot product.
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// Cross product.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// Unit vector (zero stays zero).
pub fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    if l > 0.0 { a.map(|c| c / l) } else { a }
}

/// A perspective camera looking at a target, fitted into a viewport.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    eye: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    fwd: [f64; 3],
    scale: f64,
    off: (f64, f64),
}

impl Camera {
    /// A camera at `target + distance·dir` looking at `target`, with `up_hint`
    /// as the screen's up, fitted so that every point of `points` lands in
    /// the viewport `(x, y, w, h)` (pixels) with a margin.
    pub fn fit(
        target: [f64; 3],
        dir: [f64; 3],
        up_hint: [f64; 3],
        distance: f64,
        points: &[[f64; 3]],
        viewport: (f64, f64, f64, f64),
    ) -> Self {
        let dir = normalize(dir);
        let eye = [
            target[0] + distance * dir[0],
            target[1] + distance * dir[1],
            target[2] + distance * dir[2],
        ];
        let fwd = dir.map(|c| -c);
        let mut right = normalize(cross(fwd, up_hint));
        if dot(right, right) == 0.0 {
            right = normalize(cross(fwd, [1.0, 0.0, 0.0]));
        }
        let up = cross(right, fwd);
        let mut cam = Camera {
            eye,
            right,
            up,
            fwd,
            scale: 1.0,
            off: (0.0, 0.0),
        };
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points {
            let (x, y, _) = cam.raw(*p);
            lo = [lo[0].min(x), lo[1].min(y)];
            hi = [hi[0].max(x), hi[1].max(y)];
        }
        if !(lo[0].is_finite() && hi[0] > lo[0]) {
            lo = [-1.0, -1.0];
            hi = [1.0, 1.0];
        }
        let (vx, vy, vw, vh) = viewport;
        let s = (vw / (hi[0] - lo[0]).max(1e-12)).min(vh / (hi[1] - lo[1]).max(1e-12));
        cam.scale = s;
        // centre the projected box in the viewport (screen y grows downwards)
        let cx = 0.5 * (lo[0] + hi[0]);
        let cy = 0.5 * (lo[1] + hi[1]);
        cam.off = (vx + 0.5 * vw - s * cx, vy + 0.5 * vh + s * cy);
        cam
    }

    fn raw(&self, p: [f64; 3]) -> (f64, f64, f64) {
        let d = sub(p, self.eye);
        let z = dot(d, self.fwd).max(1e-9);
        (dot(d, self.right) / z, dot(d, self.up) / z, z)
    }

    /// Screen position (pixels) and depth of a point.
    pub fn project(&self, p: [f64; 3]) -> [f64; 3] {
        let (x, y, z) = self.raw(p);
        [self.off.0 + self.scale * x, self.off.1 - self.scale * y, z]
    }

    /// Direction from a point towards the eye.
    pub fn eye_dir(&self, p: [f64; 3]) -> [f64; 3] {
        normalize(sub(self.eye, p))
    }

    /// The viewing direction.
    pub fn forward(&self) -> [f64; 3] {
        self.fwd
    }
}

/// A supersampled RGBA layer with a depth buffer, covering the picture
/// rectangle `origin + [0, w) × [0, h)` (whole pixels).
pub struct Layer {
    origin: (i64, i64),
    /// Size in samples.
    w: usize,
    h: usize,
    /// Premultiplied colour and opacity of each sample, 8 bits each (a
    /// 2048² picture has 38 M samples).
    px: Vec<[u8; 4]>,
    z: Vec<f32>,
}

impl Layer {
    /// A transparent layer over the picture viewport `(x, y, w, h)` (pixels).
    pub fn new(vp: (f64, f64, f64, f64)) -> Self {
        let origin = (vp.0.floor() as i64, vp.1.floor() as i64);
        let (w, h) = (vp.2.max(1.0) as usize * SS, vp.3.max(1.0) as usize * SS);
        Layer {
            origin,
            w,
            h,
            px: vec![[0; 4]; w * h],
            z: vec![f32::INFINITY; w * h],
        }
    }

    /// The layer in its own (sample) coordinates, for [`Camera::fit`],
    /// shrunk by `pad` pixels on every side.
    pub fn viewport(&self, pad: f64) -> (f64, f64, f64, f64) {
        let p = pad * SS as f64;
        (p, p, self.w as f64 - 2.0 * p, self.h as f64 - 2.0 * p)
    }

    /// Size in samples.
    pub fn size(&self) -> (f64, f64) {
        (self.w as f64, self.h as f64)
    }

    /// Scale the colour of the covered samples by `f` (a shadow).
    pub fn darken(&mut self, covered: &[bool], f: f32) {
        for (p, m) in self.px.iter_mut().zip(covered) {
            if *m {
                for c in &mut p[..3] {
                    *c = (*c as f32 * f).round() as u8;
                }
            }
        }
    }

    /// Number of samples.
    pub fn samples(&self) -> usize {
        self.px.len()
    }

    /// Box-filter the layer down to pixels and draw it over `pic` (source-over).
    pub fn composite(&self, pic: &mut Picture) {
        let (w, h) = (self.w / SS, self.h / SS);
        let (pw, ph) = (pic.width() as i64, pic.height() as i64);
        let inv = 1.0 / (SS * SS * 255) as f32;
        let px = pic.pixmap_mut().pixels_mut();
        for y in 0..h {
            for x in 0..w {
                let (tx, ty) = (self.origin.0 + x as i64, self.origin.1 + y as i64);
                if tx < 0 || ty < 0 || tx >= pw || ty >= ph {
                    continue;
                }
                let mut sum = [0u32; 4];
                for dy in 0..SS {
                    let row = (y * SS + dy) * self.w + x * SS;
                    for p in &self.px[row..row + SS] {
                        for c in 0..4 {
                            sum[c] += p[c] as u32;
                        }
                    }
                }
                let acc = sum.map(|v| v as f32);
                let a = acc[3] * inv;
                if a <= 0.0 {
                    continue;
                }
                let d = &mut px[(ty * pw + tx) as usize];
                let k = 1.0 - a;
                let ch = |s: f32, dst: u8| {
                    (s * inv * 255.0 + dst as f32 * k).round().clamp(0.0, 255.0) as u8
                };
                let al = ch(acc[3], d.alpha());
                if let Some(p) = tiny_skia::PremultipliedColorU8::from_rgba(
                    ch(acc[0], d.red()).min(al),
                    ch(acc[1], d.green()).min(al),
                    ch(acc[2], d.blue()).min(al),
                    al,
                ) {
                    *d = p;
                }
            }
        }
    }
}

/// Call `f(sample index)` for every sample of a screen-space triangle that
/// passes the depth test (nothing is written).
pub fn cover(layer: &Layer, p: [[f64; 3]; 3], mut f: impl FnMut(usize)) {
    rasterize(layer, p, |k, _, _, _| f(k));
}

/// Visit the covered samples passing the depth test: `visit(k, z, bary, edge_dist)`.
fn rasterize(
    layer: &Layer,
    p: [[f64; 3]; 3],
    mut visit: impl FnMut(usize, f64, [f64; 3], [f64; 3]),
) {
    let area =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let lo = |c: usize| p.iter().map(|q| q[c]).fold(f64::INFINITY, f64::min).floor();
    let hi = |c: usize| {
        p.iter()
            .map(|q| q[c])
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil()
    };
    let x0 = lo(0).max(0.0) as usize;
    let y0 = lo(1).max(0.0) as usize;
    let x1 = hi(0).min(layer.w as f64 - 1.0);
    let y1 = hi(1).min(layer.h as f64 - 1.0);
    if x1 < 0.0 || y1 < 0.0 {
        return;
    }
    let (x1, y1) = (x1 as usize, y1 as usize);
    // edge i is opposite corner i
    let edge_len: [f64; 3] = std::array::from_fn(|i| {
        let (a, b) = (p[(i + 1) % 3], p[(i + 2) % 3]);
        ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2))
            .sqrt()
            .max(1e-12)
    });
    for y in y0..=y1 {
        for x in x0..=x1 {
            let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
            let e: [f64; 3] = std::array::from_fn(|i| {
                let (a, b) = (p[(i + 1) % 3], p[(i + 2) % 3]);
                ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / area
            });
            if e.iter().any(|v| *v < 0.0) {
                continue;
            }
            let z = e[0] * p[0][2] + e[1] * p[1][2] + e[2] * p[2][2];
            let k = y * layer.w + x;
            if z as f32 >= layer.z[k] {
                continue;
            }
            let dist: [f64; 3] = std::array::from_fn(|i| e[i] * area.abs() / edge_len[i]);
            visit(k, z, e, dist);
        }
    }
}

/// Fill a screen-space triangle (`[x, y, depth]` per corner, in samples)
/// with a z-test. `shade(bary, edge_dist)` returns the colour and opacity,
/// or `None` to skip the sample.
pub fn triangle(
    layer: &mut Layer,
    p: [[f64; 3]; 3],
    mut shade: impl FnMut([f64; 3], [f64; 3]) -> Option<(Rgb, f32)>,
) {
    let mut hits: Vec<(usize, f64, Rgb, f32)> = Vec::new();
    rasterize(layer, p, |k, z, e, dist| {
        if let Some((c, a)) = shade(e, dist) {
            hits.push((k, z, c, a));
        }
    });
    for (k, z, c, a) in hits {
        layer.z[k] = z as f32;
        let a = a.clamp(0.0, 1.0);
        let q = |v: f32| (v.clamp(0.0, 1.0) * a * 255.0).round() as u8;
        layer.px[k] = [q(c[0]), q(c[1]), q(c[2]), (a * 255.0).round() as u8];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearer_triangle_wins_and_camera_fits_points() {
        let mut pic = Picture::new(20, 20, [0.0; 3]);
        let mut layer = Layer::new((0.0, 0.0, 20.0, 20.0));
        let n = 20.0 * SS as f64;
        let far = [[0.0, 0.0, 2.0], [n, 0.0, 2.0], [0.0, n, 2.0]];
        let near = [[0.0, 0.0, 1.0], [n, 0.0, 1.0], [0.0, n, 1.0]];
        triangle(&mut layer, near, |_, _| Some(([1.0, 0.0, 0.0], 1.0)));
        triangle(&mut layer, far, |_, _| Some(([0.0, 1.0, 0.0], 1.0)));
        layer.composite(&mut pic);
        assert_eq!(pic.rgb(2, 2), [255, 0, 0]);
        assert_eq!(pic.rgb(19, 19), [0; 3]);
        // the hypotenuse crosses pixels: partly covered ones are mixed (anti-aliased)
        let edge: Vec<[u8; 3]> = (0..20).map(|x| pic.rgb(x, 19 - x)).collect();
        assert!(
            edge.iter().any(|c| c[0] > 40 && c[0] < 215),
            "no intermediate shade on the edge: {edge:?}"
        );
        let pts = [[-1.0, -1.0, 0.0], [1.0, 1.0, 0.0]];
        let cam = Camera::fit(
            [0.0; 3],
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            10.0,
            &pts,
            (10.0, 10.0, 80.0, 80.0),
        );
        let a = cam.project(pts[0]);
        let b = cam.project(pts[1]);
        assert!(
            (a[0] - 10.0).abs() < 1e-9 && (b[0] - 90.0).abs() < 1e-9,
            "{a:?} {b:?}"
        );
        assert!(a[1] > b[1], "screen y grows downwards");
    }
}
