//! The deformation gradients `ecc check` visits: hard cases and random ones.
//!
//! Every hard case is F = U diag(σ) Vᵀ with random rotations U, V (except the
//! exact rest state), so the SVD is exercised in general position:
//!
//! | case | σ (3D) | σ (2D) |
//! |---|---|---|
//! | rest | F = I exactly | F = I exactly |
//! | rotation | (1, 1, 1), F = R | (1, 1) |
//! | uniform scale | (1.7, 1.7, 1.7) | (1.7, 1.7) |
//! | repeated σ | (1.3, 1.3, 0.8) | (1.3, 1.3) with U ≠ V |
//! | σ 1e-9 apart | (1.3, 1.3 + 1e-9, 0.8) | (1.3, 1.3 + 1e-9) |
//! | σi + σj ≈ 0 | (1.2, 0.7, −0.7 + 1e-9) | (0.7, −0.7 + 1e-9) |
//! | σ = 1e-6 | (1, 0.9, 1e-6) | (1, 1e-6) |
//! | inverted | (1.2, 0.9, −0.8) | (1.2, −0.8) |
//! | σ = 1e3 | (1e3, 2, 0.5) | (1e3, 0.5) |
//!
//! Random cases are F = I + E with E uniform in [−0.6, 0.6]^{d×d} (some are
//! inverted; barrier energies skip those as outside the domain).

use nalgebra::SMatrix;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// One point to check.
pub struct Case<const D: usize> {
    /// Row label in the report ("random" for every random sample).
    pub name: &'static str,
    /// The deformation gradient.
    pub f: SMatrix<f64, D, D>,
}

/// A uniformly random rotation (Gram–Schmidt of a random matrix, det fixed to +1).
pub fn random_rotation<const D: usize>(rng: &mut ChaCha8Rng) -> SMatrix<f64, D, D> {
    loop {
        let mut cols: [[f64; D]; D] =
            std::array::from_fn(|_| std::array::from_fn(|_| rng.gen_range(-1.0..1.0)));
        let mut ok = true;
        for j in 0..D {
            for k in 0..j {
                let ck = cols[k];
                let dot: f64 = cols[j].iter().zip(&ck).map(|(a, b)| a * b).sum();
                for (x, y) in cols[j].iter_mut().zip(&ck) {
                    *x -= dot * y;
                }
            }
            let n: f64 = cols[j].iter().map(|x| x * x).sum::<f64>().sqrt();
            if n < 1e-3 {
                ok = false;
                break;
            }
            cols[j].iter_mut().for_each(|x| *x /= n);
        }
        if !ok {
            continue;
        }
        let mut q = SMatrix::<f64, D, D>::from_fn(|i, j| cols[j][i]);
        if det(&q) < 0.0 {
            for i in 0..D {
                q[(i, D - 1)] = -q[(i, D - 1)];
            }
        }
        return q;
    }
}

/// Determinant for D = 2 or 3.
pub fn det<const D: usize>(m: &SMatrix<f64, D, D>) -> f64 {
    match D {
        2 => m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)],
        _ => {
            m[(0, 0)] * (m[(1, 1)] * m[(2, 2)] - m[(1, 2)] * m[(2, 1)])
                - m[(0, 1)] * (m[(1, 0)] * m[(2, 2)] - m[(1, 2)] * m[(2, 0)])
                + m[(0, 2)] * (m[(1, 0)] * m[(2, 1)] - m[(1, 1)] * m[(2, 0)])
        }
    }
}

fn sigma_list<const D: usize>() -> Vec<(&'static str, [f64; 3], [f64; 2])> {
    vec![
        ("rotation", [1.0, 1.0, 1.0], [1.0, 1.0]),
        ("uniform scale", [1.7, 1.7, 1.7], [1.7, 1.7]),
        ("repeated sigma", [1.3, 1.3, 0.8], [1.3, 1.3]),
        (
            "sigma 1e-9 apart",
            [1.3, 1.3 + 1e-9, 0.8],
            [1.3, 1.3 + 1e-9],
        ),
        (
            "sigma_i+sigma_j~0",
            [1.2, 0.7, -0.7 + 1e-9],
            [0.7, -0.7 + 1e-9],
        ),
        ("sigma = 1e-6", [1.0, 0.9, 1e-6], [1.0, 1e-6]),
        ("inverted", [1.2, 0.9, -0.8], [1.2, -0.8]),
        ("sigma = 1e3", [1e3, 2.0, 0.5], [1e3, 0.5]),
    ]
}

/// The hard cases followed by `samples` random ones.
pub fn cases<const D: usize>(rng: &mut ChaCha8Rng, samples: usize) -> Vec<Case<D>> {
    let mut out = vec![Case {
        name: "rest",
        f: SMatrix::identity(),
    }];
    for (name, s3, s2) in sigma_list::<D>() {
        let sigma: [f64; D] = std::array::from_fn(|i| if D == 2 { s2[i] } else { s3[i] });
        let u = random_rotation::<D>(rng);
        let v = if name == "rotation" {
            SMatrix::identity()
        } else {
            random_rotation::<D>(rng)
        };
        let s = SMatrix::<f64, D, D>::from_fn(|i, j| if i == j { sigma[i] } else { 0.0 });
        out.push(Case {
            name,
            f: u * s * v.transpose(),
        });
    }
    for _ in 0..samples {
        let f = SMatrix::<f64, D, D>::from_fn(|i, j| {
            let e: f64 = rng.gen_range(-0.6..0.6);
            if i == j { 1.0 + e } else { e }
        });
        out.push(Case { name: "random", f });
    }
    out
}
