//! The deformation gradients `ecc check` visits: hard cases and random ones.
//!
//! Every hard case is F = U diag(σ) Vᵀ with random rotations U, V (except the
//! exact rest state), so the SVD is exercised in general position. The σ
//! come from the one hard-case table, `ecc_runtime::reference::cases`
//! (rows `CHECK`, labelled as below), and so do the rotations:
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

use ecc_runtime::reference::cases as table;
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

/// A uniformly random rotation ([`ecc_runtime::reference::cases::rotation`]).
pub fn random_rotation<const D: usize>(rng: &mut ChaCha8Rng) -> SMatrix<f64, D, D> {
    table::rotation::<D>(rng)
}

/// The hard cases followed by `samples` random ones.
pub fn cases<const D: usize>(rng: &mut ChaCha8Rng, samples: usize) -> Vec<Case<D>> {
    let mut out = vec![Case {
        name: "rest",
        f: SMatrix::identity(),
    }];
    let rows = std::iter::once(("rotation", "rest")).chain(table::CHECK.iter().copied());
    for (name, case) in rows {
        let Some(sigma) = table::sigma::<D>(case) else {
            continue;
        };
        let u = random_rotation::<D>(rng);
        let v = if name == "rotation" {
            SMatrix::identity()
        } else {
            random_rotation::<D>(rng)
        };
        out.push(Case {
            name,
            f: table::compose(&u, &sigma, &v),
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
