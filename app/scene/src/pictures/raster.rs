//! A small software rasteriser: a perspective camera fitted to the points
//! it must show, and z-buffered triangle filling with a per-pixel shader.
//!
//! Triangles are filled with edge functions at pixel centres; the shader
//! receives the barycentric coordinates and the pixel distance to each
//! edge (for wireframe overlays). Depth is interpolated linearly in screen
//! space, which is exact enough for a depth test of small triangles.

use super::image::{Picture, Rgb};

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

/// A depth buffer matching a picture, with a clip rectangle.
pub struct ZBuffer {
    w: usize,
    z: Vec<f64>,
    /// Pixels outside [x0, x1) × [y0, y1) are never drawn.
    clip: (i64, i64, i64, i64),
}

impl ZBuffer {
    /// Everything infinitely far; the whole picture drawable.
    pub fn new(pic: &Picture) -> Self {
        ZBuffer {
            w: pic.w,
            z: vec![f64::INFINITY; pic.w * pic.h],
            clip: (0, 0, pic.w as i64, pic.h as i64),
        }
    }

    /// Only the viewport `(x, y, w, h)` drawable.
    pub fn clipped(pic: &Picture, vp: (f64, f64, f64, f64)) -> Self {
        let mut z = ZBuffer::new(pic);
        z.clip = (
            vp.0.max(0.0) as i64,
            vp.1.max(0.0) as i64,
            ((vp.0 + vp.2) as i64).min(pic.w as i64),
            ((vp.1 + vp.3) as i64).min(pic.h as i64),
        );
        z
    }
}

/// Call `f(pixel index)` for every pixel of a screen-space triangle that
/// passes the depth test (nothing is written).
pub fn cover(zb: &ZBuffer, p: [[f64; 3]; 3], mut f: impl FnMut(usize)) {
    rasterize(zb, p, |k, _, _, _| f(k));
}

/// Visit the covered pixels passing the depth test: `visit(k, z, bary, edge_px)`.
fn rasterize(
    zb: &ZBuffer,
    p: [[f64; 3]; 3],
    mut visit: impl FnMut(usize, f64, [f64; 3], [f64; 3]),
) {
    let area =
        (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]);
    if area.abs() < 1e-12 || !area.is_finite() {
        return;
    }
    let (cx0, cy0, cx1, cy1) = zb.clip;
    let x0 = (p.iter().map(|q| q[0]).fold(f64::INFINITY, f64::min).floor() as i64).max(cx0);
    let x1 = (p
        .iter()
        .map(|q| q[0])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil() as i64)
        .min(cx1 - 1);
    let y0 = (p.iter().map(|q| q[1]).fold(f64::INFINITY, f64::min).floor() as i64).max(cy0);
    let y1 = (p
        .iter()
        .map(|q| q[1])
        .fold(f64::NEG_INFINITY, f64::max)
        .ceil() as i64)
        .min(cy1 - 1);
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
            let k = y as usize * zb.w + x as usize;
            if z >= zb.z[k] {
                continue;
            }
            let dist: [f64; 3] = std::array::from_fn(|i| e[i] * area.abs() / edge_len[i]);
            visit(k, z, e, dist);
        }
    }
}

/// Fill a screen-space triangle (`[x, y, depth]` per corner) with a z-test.
/// `shade(bary, edge_px)` returns the colour or `None` to skip the pixel.
pub fn triangle(
    pic: &mut Picture,
    zb: &mut ZBuffer,
    p: [[f64; 3]; 3],
    mut shade: impl FnMut([f64; 3], [f64; 3]) -> Option<Rgb>,
) {
    let mut hits: Vec<(usize, f64, Rgb)> = Vec::new();
    rasterize(zb, p, |k, z, e, dist| {
        if let Some(c) = shade(e, dist) {
            hits.push((k, z, c));
        }
    });
    for (k, z, c) in hits {
        zb.z[k] = z;
        pic.px[k] = c;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearer_triangle_wins_and_camera_fits_points() {
        let mut pic = Picture::new(20, 20, [0.0; 3]);
        let mut zb = ZBuffer::new(&pic);
        let far = [[0.0, 0.0, 2.0], [20.0, 0.0, 2.0], [0.0, 20.0, 2.0]];
        let near = [[0.0, 0.0, 1.0], [20.0, 0.0, 1.0], [0.0, 20.0, 1.0]];
        triangle(&mut pic, &mut zb, near, |_, _| Some([1.0, 0.0, 0.0]));
        triangle(&mut pic, &mut zb, far, |_, _| Some([0.0, 1.0, 0.0]));
        assert_eq!(pic.px[2 * 20 + 2], [1.0, 0.0, 0.0]);
        assert_eq!(pic.px[19 * 20 + 19], [0.0; 3]);
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
