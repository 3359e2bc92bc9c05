//! The Rust snippet of README.md, compiled and checked.

use ecc_macros::energy;
use ecc_runtime::{Energy, ScaleBlock};

energy! { pub struct Snh; param mu = 1.0; param lambda = 10.0;
psi = mu/2*(IC - d) + lambda/2*(J - 1 - mu/lambda)^2; }

#[test]
fn readme_snippet_works() {
    let arap = energy!(I2 - 2 * I1 + d);
    let s = Energy::<3>::spectral(&arap, &[1.2, 0.9, 0.8]);
    // ARAP (Smith et al. 2019, eq. 30): Ψ_σi = 2σi − 2, A = 2I, twist about
    // axis k = 2 − 4/(σi + σj), flips 2.
    for (g, want) in s.grad.iter().zip([0.4, -0.2, -0.4]) {
        assert!((g - want).abs() < 1e-14, "ARAP gradient {g} vs {want}");
    }
    assert_eq!(s.scale, ScaleBlock::Diagonal([2.0; 3]));
    assert!((s.twist[0] - (2.0 - 4.0 / 1.7)).abs() < 1e-14);
    assert_eq!(s.flip, [2.0; 3]);

    let snh = Snh {
        mu: 2.0,
        ..Snh::default()
    };
    assert_eq!((snh.mu, snh.lambda), (2.0, 10.0));
    // Rest is stress-free for this Stable Neo-Hookean variant (α = 1 + μ/λ):
    // Ψ_σi = μσi + λ(J − α)·J/σi = μ − μ = 0 at σ = 1.
    let rest = Energy::<3>::spectral(&snh, &[1.0, 1.0, 1.0]);
    for g in rest.grad {
        assert!(g.abs() < 1e-14, "rest gradient {g}");
    }
}
