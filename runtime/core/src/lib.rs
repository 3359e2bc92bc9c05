//! # ecc-runtime: the eigensystem core
//!
//! Everything generated code plugs into. An isotropic energy density Ψ(F) depends
//! on F only through its *signed* singular values σ (F = U diag(σ) Vᵀ with
//! U, V ∈ SO(d); the reflection, if any, is moved into the smallest σ).
//! An energy therefore describes itself in stretch space ([`Energy`] →
//! [`Spectral`]), and this crate lifts that description back to F-space
//! (gradient, raw and PSD-filtered Hessian, eigenpairs) and to element
//! (x-space) Hessians. It depends on nalgebra only and never on the compiler
//! crates (`ecc-dsl`, `ecc-codegen`).
//!
//! ## The maths
//!
//! With d = 2 or 3, column-major `vec` (Smith et al. 2019, eq. 1:
//! vec(F)[c·d + r] = F_rc), Ψ_i = ∂Ψ/∂σ_i and A = ∂²Ψ/∂σ²:
//!
//! * gradient: ∂Ψ/∂F = U diag(Ψ_σ) Vᵀ;
//! * Hessian: ∂²Ψ/∂f² = Σ_ij A_ij d_i d_jᵀ + Σ_pairs λ_twist t tᵀ + λ_flip l lᵀ,
//!   with scaling modes d_i = vec(U e_i e_iᵀ Vᵀ) and, for each pair (i, j), the
//!   twist t = vec(U (e_j e_iᵀ − e_i e_jᵀ) Vᵀ)/√2 and flip
//!   l = vec(U (e_j e_iᵀ + e_i e_jᵀ) Vᵀ)/√2, with λ_twist = (Ψ_i + Ψ_j)/(σ_i + σ_j)
//!   and λ_flip = (Ψ_i − Ψ_j)/(σ_i − σ_j) (Zhu 2020 eq. 28; Smith eqs. 22–23).
//!   {d_i, t, l} is an orthonormal basis of R^{d²}, so filtering = mapping each
//!   eigenvalue (the d² − d pair values and the d eigenvalues of A).
//!
//! Pair slots: 3D k = 0 → (1, 2), k = 1 → (2, 0), k = 2 → (0, 1); 2D k = 0 → (0, 1).
//!
//! ## Map of the crate
//!
//! | module | what |
//! |---|---|
//! | [`svd`] | [`signed_svd2`] (closed form), [`signed_svd3`] (analytic V from FᵀF + Gram–Schmidt QR), [`signed_svd`] dispatch |
//! | [`sym`] | closed-form symmetric 2×2 / 3×3 eigensolvers |
//! | [`invariants`] | [`spectral_from_invariants`]: Ψ through ∂Ψ/∂I_k, ∂²Ψ/∂I_k∂I_l (App. D, eqs. 22–27) |
//! | [`stretch`] | [`spectral_from_stretch`]: Ψ through ∂Ψ/∂σ, ∂²Ψ/∂σ² (Zhu §4) |
//! | [`divided`] | removable singularities of the divided differences, switch threshold ε^{1/3} |
//! | [`filter`] | [`Filter`]: `None` (raw), `Clamp` (default), `ClampEps(ε)`, `Abs` |
//! | [`dim`] | [`Space<D>`] and the sealed [`Dim<D>`]: the d², d + 1 and d(d + 1) sized types and kernels; callers are generic over `D` with `Space<D>: Dim<D>` |
//! | [`point`] | [`gradient_f`], [`hessian_f`] (raw or filtered), [`eigen_f`]: F-space quantities at one point |
//! | [`element`] | [`Rest<D>`] (Dm⁻¹, measure), [`element_f`], [`element_psi`], [`element_eval`] (x-space, × rest measure), [`element_curvature`] (raw dxᵀ H dx without the Hessian) |
//! | [`energies`] | hand-written ARAP, Symmetric Dirichlet, Stable Neo-Hookean |
//! | [`reference`](mod@reference) | nalgebra projection and central differences [`fd_gradient_f`](reference::fd_gradient_f), [`fd_hessian_f`](reference::fd_hessian_f) (tests, benches, `ecc check`); [`reference::check`]: the F-space checker (gradient, raw Hessian vs differences, eigenpairs vs `SymmetricEigen`, filtered Hessians PSD and equal to the numeric projection); with the `cases` feature, `reference::cases`: the one named hard-case table and seeded rotations |
//!
//! ## Writing an energy
//!
//! Implement [`Energy`] for `D = 2` and/or `3`; `spectral` returns
//! [`Spectral`], most easily through one of the two generic paths:
//!
//! ```
//! use ecc_runtime::{spectral_from_invariants, element_eval, Energy, Filter, Rest, Spectral};
//!
//! /// Ψ = ‖F‖² − 2 det F + 1 … any function of the invariants I1, I2, I3.
//! struct MyEnergy;
//! impl Energy<3> for MyEnergy {
//!     fn name(&self) -> &str { "mine" }
//!     fn psi(&self, s: &[f64; 3]) -> f64 {
//!         let (i2, i3) = (s.iter().map(|x| x * x).sum::<f64>(), s[0] * s[1] * s[2]);
//!         i2 - 2.0 * i3 + 1.0
//!     }
//!     fn spectral(&self, s: &[f64; 3]) -> Spectral<3> {
//!         // d1 = [Ψ1, Ψ2, Ψ3], d2 = [Ψ11, Ψ22, Ψ33, Ψ12, Ψ13, Ψ23]
//!         let psi = self.psi(s);
//!         spectral_from_invariants(s, psi, [0.0, 1.0, -2.0], [0.0; 6], false, true)
//!     }
//! }
//!
//! let rest = Rest::<3>::new([[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).unwrap();
//! let x = [[0.0; 3], [1.2, 0.1, 0.0], [0.0, 0.9, 0.0], [0.1, 0.0, 1.1]];
//! let ev = element_eval(&MyEnergy, &rest, &x, Filter::Clamp, true);
//! assert!(ev.psi.is_finite() && ev.hess.iter().all(|h| h.is_finite()));
//! ```
//!
//! `decoupled = true` declares a_ij ≡ 0 (diagonal scaling block, no eigensolve);
//! `sign_symmetric = true` declares Ψ unchanged by (σ_i, σ_j) ↦ (−σ_j, −σ_i),
//! true for every function of I2 and I3 (of FᵀF, of J), false with I1 (ARAP).
//! It lets the runtime replace the twist's 0/0 at σ_i = −σ_j by its limit.
//!
//! ## Accuracy (what the tests establish)
//!
//! * SVD: ‖F − U diag(σ) Vᵀ‖ ≤ 10⁻¹³‖F‖, ‖UᵀU − I‖, ‖VᵀV − I‖ ≤ 10⁻¹³, det = +1,
//!   |σ| equal to nalgebra's to 10⁻¹³‖F‖, at repeated, zero, nearly equal
//!   (10⁻⁹), graded (σ spanning 10⁻³²…1) and random F.
//! * Divided differences: |λ − exact| ≤ 3·10⁻¹¹ relative across all gaps
//!   10⁻¹⁶…10⁻¹ (theory: ≈ ε^{2/3}).
//! * Gradient / raw Hessian vs central differences of Ψ(F): worst 3·10⁻⁸ / 2·10⁻⁶
//!   relative over all hard cases (the differences themselves are that accurate).
//! * Eigenvalues vs nalgebra's `SymmetricEigen` of the raw Hessian: ≤ 10⁻¹¹ relative.
//! * Filtered Hessians: exactly symmetric, finite, PSD (≥ floor − 10⁻¹¹‖H‖), equal
//!   to the numeric projection of the raw Hessian to 10⁻¹¹ relative.
//!
//! ## Non-finite values
//!
//! Ψ = +∞ (outside the domain) gives zero gradient and Hessian. A non-finite
//! eigenvalue (a genuine pole, e.g. ARAP's twist at σ_i + σ_j = 0) is mapped to the
//! filter's floor by every filter except `None`; a scaling block with a
//! non-finite entry is replaced by its diagonal. A non-finite F gives σ = NaN, a
//! NaN element energy and zero derivatives. No input makes the runtime panic.
//!
//! ## Speed
//!
//! `cargo bench -p ecc-benches --bench eigen` compares, per tetrahedron, the
//! analytic projected 12×12 (`element_eval::<3>`, `Filter::Clamp`) with nalgebra's
//! numeric projection of the 12×12 and of the 9×9, and the SVD with nalgebra's;
//! it prints the ratios at the end of the run.

// Index loops mirror the maths (u_a[r]·w_b[n], pair slots) more clearly than iterators.
#![allow(clippy::needless_range_loop)]

mod assemble;
pub mod dim;
pub mod divided;
pub mod element;
pub mod energies;
pub mod energy;
pub mod fibre;
pub mod filter;
pub mod invariants;
mod modes;
pub mod point;
pub mod reference;
pub mod spectral;
pub mod stretch;
pub mod svd;
pub mod sym;

pub use dim::{Dim, ElemMat, ElemVec, FMat, FVec, Nodes, Space};
pub use element::{
    Congruence, ElementEval, Rest, RestError, element_curvature, element_eval,
    element_eval_projected, element_f, element_psi,
};
pub use energy::{Energy, EnergyInfo, ParamError};
pub use fibre::{FibreDerivs, FibreEnergy, FibreUse};
pub use filter::Filter;
pub use invariants::spectral_from_invariants;
pub use point::{eigen_f, gradient_f, hessian_f};
pub use spectral::{PAIRS_2D, PAIRS_3D, ScaleBlock, Spectral, pair_indices};
pub use stretch::spectral_from_stretch;
pub use svd::{Svd, signed_svd, signed_svd2, signed_svd3};
