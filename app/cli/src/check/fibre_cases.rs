//! The (F, a) pairs at which `ecc check` verifies a fibre part ψ(I4, I5).
//!
//! Every hard case of [`super::cases`] (the one table,
//! `ecc_runtime::reference::cases`, rows `CHECK`, plus rest and rotation) is
//! composed here as F = U diag(σ) Vᵀ from the table's σ *in the table's
//! order* and random rotations U, V, so the right singular vectors v_k (the
//! columns of V) are known exactly. Each F is visited with the fibre
//!
//! | row suffix | a |
//! |---|---|
//! | `a generic` | a random unit vector |
//! | `a = vk` | v_k, the axis of σ_k (k = 1..d); the table lists the smallest, compressed or inverted σ last, so `a = v3` (2D: `a = v2`) is the compressed/inverted axis: F a = σ_d u_d |
//!
//! and one extra point has F a = 0 exactly: F = U diag(1.2, 0.9, 0) (2D:
//! U diag(1.2, 0)) with a = e_d, where every ψ of √I5 or log I5 is at its
//! cone point or pole. Random points are F = I + E, E uniform in
//! [−0.6, 0.6]^{d×d}, each with its own random unit a.

use ecc_runtime::reference::cases as table;
use nalgebra::{SMatrix, SVector};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// One fibre point to check.
pub struct FibreCase<const D: usize> {
    /// Row label in the report: `"<case>, <direction>"`.
    pub name: String,
    /// The deformation gradient.
    pub f: SMatrix<f64, D, D>,
    /// The unit rest-space fibre direction.
    pub a: SVector<f64, D>,
}

const AXES: [&str; 3] = ["a = v1", "a = v2", "a = v3"];

/// A uniformly random unit vector (rejection sampling from the cube, then normalised).
fn random_unit<const D: usize>(rng: &mut ChaCha8Rng) -> SVector<f64, D> {
    loop {
        let v = SVector::<f64, D>::from_fn(|_, _| rng.gen_range(-1.0..1.0));
        let n = v.norm();
        if n > 0.1 && n <= 1.0 {
            return v / n;
        }
    }
}

/// Every hard case × (generic, each singular axis), the F a = 0 point,
/// then `samples` random (F, a).
pub fn fibre_cases<const D: usize>(rng: &mut ChaCha8Rng, samples: usize) -> Vec<FibreCase<D>> {
    let mut out = Vec::new();
    let rows = [("rest", "rest"), ("rotation", "rest")]
        .into_iter()
        .chain(table::CHECK.iter().copied());
    for (name, case) in rows {
        let Some(sigma) = table::sigma::<D>(case) else {
            continue;
        };
        let (u, v) = match name {
            "rest" => (SMatrix::identity(), SMatrix::identity()),
            "rotation" => (table::rotation::<D>(rng), SMatrix::identity()),
            _ => (table::rotation::<D>(rng), table::rotation::<D>(rng)),
        };
        let f = table::compose(&u, &sigma, &v);
        out.push(FibreCase {
            name: format!("{name}, a generic"),
            f,
            a: random_unit::<D>(rng),
        });
        for (k, axis) in AXES.iter().enumerate().take(D) {
            out.push(FibreCase {
                name: format!("{name}, {axis}"),
                f,
                a: v.column(k).into_owned(),
            });
        }
    }
    let mut sigma = [1.2, 0.9, 0.0];
    sigma[D - 1] = 0.0;
    let sigma: [f64; D] = std::array::from_fn(|i| sigma[i]);
    let u = table::rotation::<D>(rng);
    out.push(FibreCase {
        name: "F a = 0".to_string(),
        f: table::compose(&u, &sigma, &SMatrix::identity()),
        a: SVector::from_fn(|i, _| if i == D - 1 { 1.0 } else { 0.0 }),
    });
    for _ in 0..samples {
        let f = SMatrix::<f64, D, D>::from_fn(|i, j| {
            let e: f64 = rng.gen_range(-0.6..0.6);
            if i == j { 1.0 + e } else { e }
        });
        out.push(FibreCase {
            name: "random".to_string(),
            f,
            a: random_unit::<D>(rng),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn axes_are_singular_vectors_and_fa_zero_is_exact() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let cases = fibre_cases::<3>(&mut rng, 2);
        let inv = cases.iter().find(|c| c.name == "inverted, a = v3").unwrap();
        // F v3 = σ3 u3 with σ3 = −0.8: |F a| = 0.8 and I4-relevant sign < 0.
        assert!(((inv.f * inv.a).norm() - 0.8).abs() < 1e-12);
        assert!(inv.f.determinant() < 0.0);
        let zero = cases.iter().find(|c| c.name == "F a = 0").unwrap();
        assert_eq!((zero.f * zero.a).norm(), 0.0);
        assert!(cases.iter().all(|c| (c.a.norm() - 1.0).abs() < 1e-12));
        assert_eq!(cases.iter().filter(|c| c.name == "random").count(), 2);
    }
}
