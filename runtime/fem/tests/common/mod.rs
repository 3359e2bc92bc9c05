//! Shared helpers for the integration tests.
#![allow(dead_code)]

use ecc_fem::{Filter, Term};

/// Zero-rest-length-offset springs: e = ½ k ‖x_i − x_j − r_ij‖² (quadratic,
/// convex, couples vertex pairs; the minimiser is any translate of the rest
/// offsets, so some vertex must be fixed or anchored).
pub struct OffsetSprings<const D: usize> {
    pub edges: Vec<usize>,
    pub offsets: Vec<[f64; D]>,
    pub k: f64,
}

impl<const D: usize> OffsetSprings<D> {
    pub fn from_rest(rest: &[[f64; D]], edges: Vec<usize>, k: f64) -> Self {
        let offsets = edges
            .chunks(2)
            .map(|e| std::array::from_fn(|c| rest[e[0]][c] - rest[e[1]][c]))
            .collect();
        OffsetSprings { edges, offsets, k }
    }

    fn residual(&self, s: usize, x: &[[f64; D]]) -> [f64; D] {
        let (i, j) = (self.edges[2 * s], self.edges[2 * s + 1]);
        std::array::from_fn(|c| x[i][c] - x[j][c] - self.offsets[s][c])
    }
}

impl<const D: usize> Term<D> for OffsetSprings<D> {
    fn name(&self) -> &str {
        "springs"
    }
    fn arity(&self) -> usize {
        2
    }
    fn stencils(&self) -> &[usize] {
        &self.edges
    }
    fn value(&self, s: usize, x: &[[f64; D]]) -> f64 {
        0.5 * self.k * self.residual(s, x).iter().map(|r| r * r).sum::<f64>()
    }
    fn evaluate(
        &self,
        s: usize,
        x: &[[f64; D]],
        _f: Filter,
        grad: &mut [f64],
        hess: Option<&mut [f64]>,
    ) -> f64 {
        let r = self.residual(s, x);
        for c in 0..D {
            grad[c] = self.k * r[c];
            grad[D + c] = -self.k * r[c];
        }
        if let Some(h) = hess {
            let n = 2 * D;
            h.fill(0.0);
            for c in 0..D {
                h[c * n + c] = self.k;
                h[(D + c) * n + D + c] = self.k;
                h[c * n + D + c] = -self.k;
                h[(D + c) * n + c] = -self.k;
            }
        }
        self.value(s, x)
    }
}

/// A structured (m+1)×(m+1) grid on [0,1]², two triangles per cell (CCW).
pub fn grid(m: usize) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
    let mut x = Vec::new();
    for i in 0..=m {
        for j in 0..=m {
            x.push([j as f64 / m as f64, i as f64 / m as f64]);
        }
    }
    let mut t = Vec::new();
    let w = m + 1;
    for i in 0..m {
        for j in 0..m {
            let a = i * w + j;
            t.push([a, a + 1, a + w + 1]);
            t.push([a, a + w + 1, a + w]);
        }
    }
    (x, t)
}

/// Unique edges of a triangle list, flat pairs.
pub fn edges(tris: &[[usize; 3]]) -> Vec<usize> {
    let mut e: Vec<(usize, usize)> = tris
        .iter()
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    e.sort_unstable();
    e.dedup();
    e.into_iter().flat_map(|(a, b)| [a, b]).collect()
}

/// Path to a public mesh (the repository's `data/`, or `$ECC_DATA_DIR`).
pub fn data(name: &str) -> std::path::PathBuf {
    ecc_mesh::data_file(name)
}

/// A structured m×m×m grid of the unit cube, 6 positively oriented tets per cell.
pub fn tet_grid(m: usize) -> (Vec<[f64; 3]>, Vec<[usize; 4]>) {
    let w = m + 1;
    let id = |i: usize, j: usize, k: usize| (k * w + j) * w + i;
    let mut x = Vec::new();
    for k in 0..=m {
        for j in 0..=m {
            for i in 0..=m {
                x.push([
                    i as f64 / m as f64,
                    j as f64 / m as f64,
                    k as f64 / m as f64,
                ]);
            }
        }
    }
    let perms = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    let mut tets = Vec::new();
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                for p in perms {
                    let mut c = [i, j, k];
                    let mut t = [id(c[0], c[1], c[2]), 0, 0, 0];
                    for (s, &axis) in p.iter().enumerate() {
                        c[axis] += 1;
                        t[s + 1] = id(c[0], c[1], c[2]);
                    }
                    if ecc_fem::quality::tet_signed_volume(&x, t) < 0.0 {
                        t.swap(1, 2);
                    }
                    tets.push(t);
                }
            }
        }
    }
    (x, tets)
}

/// Deterministic pseudo-random numbers in [−1, 1].
pub fn noise(seed: u64, n: usize) -> Vec<f64> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.gen_range(-1.0..1.0)).collect()
}
