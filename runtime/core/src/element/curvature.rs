//! Raw directional curvature of one element, dxᵀ ∇²ψ_e dx, without forming
//! the element Hessian.
//!
//! With F = Ds Dm⁻¹ (linear in x) and dF = dDs Dm⁻¹ the change of F along
//! the nodal direction dx,
//!
//! (1) dxᵀ ∇²ψ_e dx = |q| d²/dt² Ψ(F + t dF)|_{t=0} = |q| vec(dF)ᵀ H vec(dF),
//!
//! H = ∂²Ψ/∂f² the raw F-space Hessian. Its modal form (Smith et al. 2019,
//! eqs. 22–23; Zhu 2020, eq. 28), with the signed SVD F = U Σ Vᵀ, is
//! H = Σ_ij A_ij d_i d_jᵀ + Σ_{i<j} λ_twist,ij t tᵀ + λ_flip,ij l lᵀ, with
//! d_i = vec(U e_i e_iᵀ Vᵀ), t = vec(U (e_j e_iᵀ − e_i e_jᵀ) Vᵀ)/√2 and
//! l = vec(U (e_j e_iᵀ + e_i e_jᵀ) Vᵀ)/√2. Every mode is vec(U M Vᵀ) for a
//! fixed M, and ⟨U M Vᵀ, dF⟩ = ⟨M, Uᵀ dF V⟩, so with the rotated direction
//!
//! (2) dF̃ = Uᵀ dF V,
//!
//! the projections are d_i · dF = dF̃_ii, t · dF = (dF̃_ji − dF̃_ij)/√2 and
//! l · dF = (dF̃_ji + dF̃_ij)/√2, and (1) becomes
//!
//! (3) dF : H : dF = Σ_ij A_ij dF̃_ii dF̃_jj
//!     + Σ_{i<j} [λ_twist,ij (dF̃_ij − dF̃_ji)²/2 + λ_flip,ij (dF̃_ij + dF̃_ji)²/2].
//!
//! A d×d product and the stretch-space data replace the 6×6 / 12×12 Hessian.
//! σ and [`Spectral`](crate::Spectral) are the element kernel's
//! ([`element_eval`](crate::element_eval)): in 3D from the same
//! [`signed_svd`](crate::signed_svd) call, in 2D from the same closed form as
//! [`signed_svd2`](crate::signed_svd2) (bit-identical σ, tested), whose frame
//! rotates dF without its two atan2 and two sin_cos (eqs. 4–5 at
//! `frame_2d`; that halves the pass on triangles). A, λ_twist, λ_flip are
//! read through the same unfiltered stretch-space data
//! (`Filtered::new(.., Filter::None)`: symmetrised A, a full A with a
//! non-finite entry reduced to its diagonal), so removable singularities
//! (σ_i = σ_j, σ_i + σ_j ≈ 0) get exactly the limits the raw Hessian gets.
//! A genuine pole (a non-finite eigenvalue, e.g. ARAP's twist at
//! σ_i + σ_j = 0) makes (3) non-finite (+∞, or NaN when dF has no component
//! on the pole's mode), as dxᵀ H dx is with the raw Hessian's ±∞ entries.

use super::eval::element_f;
use super::rest::Rest;
use crate::assemble::Filtered;
use crate::dim::{Dim, Nodes, Space};
use crate::energy::Energy;
use crate::filter::Filter;
use crate::spectral::{Spectral, pair_indices};
use crate::svd::conformal_parts;
use crate::svd::signed_svd;
use nalgebra::SMatrix;

/// dxᵀ ∇²ψ_e(x) dx with the *raw* (unfiltered) element Hessian, eq. (1)–(3)
/// of the module docs: |q| · d²/dt² Ψ(F + t dF) at t = 0.
///
/// Equals `dlᵀ · element_eval(e, rest, x, Filter::None, true).hess · dl`
/// (dl = `dx` node-major) up to rounding wherever that is finite, and is
/// non-finite wherever that Hessian has a non-finite entry. Where |q| Ψ(F)
/// is not finite (outside the energy's domain, or a non-finite `x`) it is
/// `+∞`, the value the trust-region ratio has always given such elements.
#[inline]
pub fn element_curvature<const D: usize, E: Energy<D> + ?Sized>(
    e: &E,
    rest: &Rest<D>,
    x: &Nodes<D>,
    dx: &Nodes<D>,
) -> f64
where
    Space<D>: Dim<D>,
{
    // eq. (2): dF = dDs Dm⁻¹ is element_f of the direction (F is linear in x).
    let (f, df) = (element_f(rest, x), element_f(rest, dx));
    let frame = if D == 2 {
        frame_2d(&f, &df)
    } else {
        frame_svd(&f, &df)
    };
    let Some((sigma, dft)) = frame else {
        return f64::INFINITY;
    };
    let s = e.spectral(&sigma);
    if !(rest.measure * s.psi).is_finite() {
        return f64::INFINITY;
    }
    rest.measure * modal_form(&Filtered::new(&s, Filter::None), &dft)
}

/// σ and dF̃ = Uᵀ dF V from the signed SVD; `None` when it is not finite.
#[inline]
fn frame_svd<const D: usize>(
    f: &SMatrix<f64, D, D>,
    df: &SMatrix<f64, D, D>,
) -> Option<([f64; D], SMatrix<f64, D, D>)> {
    let svd = signed_svd(f);
    svd.is_finite()
        .then(|| (svd.sigma, svd.u.transpose() * df * svd.v))
}

/// (cos α, sin α) of α = atan2(y, x) for r = |(x, y)|, without the
/// trigonometry unless r = 0 (then atan2's signed-zero conventions).
#[inline]
fn unit(x: f64, y: f64, r: f64) -> (f64, f64) {
    if r == 0.0 {
        let a = y.atan2(x);
        (a.cos(), a.sin())
    } else {
        (x / r, y / r)
    }
}

/// D = 2: σ and dF̃ of [`signed_svd2`](crate::signed_svd2)'s frame without its
/// trigonometry. With F = Q rot(α₂) + R refl(α₁) (E, H, P, G, Q, R as
/// there), σ = (Q + R, Q − R), U = rot(φ), V = rot(ψ), φ ± ψ = α₁, α₂, one has
/// Uᵀ rot(β) V = rot(β − α₂) and Uᵀ refl(β) V = refl(β − α₁); so with dF's own
/// parts E′, H′, P′, G′ (4) Ẽ + iH̃ = (E′ + iH′) e^{−iα₂},
/// P̃ + iG̃ = (P′ + iG′) e^{−iα₁} and (5) dF̃ = [[Ẽ + P̃, G̃ − H̃], [G̃ + H̃, Ẽ − P̃]].
#[inline]
fn frame_2d<const D: usize>(
    f: &SMatrix<f64, D, D>,
    df: &SMatrix<f64, D, D>,
) -> Option<([f64; D], SMatrix<f64, D, D>)> {
    let [e, h, p, g] = conformal_parts(f);
    let (q, r) = (e.hypot(h), p.hypot(g));
    let sigma = [q + r, q - r];
    if !(sigma[0].is_finite() && sigma[1].is_finite()) {
        return None;
    }
    let ((c2, s2), (c1, s1)) = (unit(e, h, q), unit(p, g, r));
    let [de, dh, dp, dg] = conformal_parts(df);
    let (te, th) = (de * c2 + dh * s2, dh * c2 - de * s2);
    let (tp, tg) = (dp * c1 + dg * s1, dg * c1 - dp * s1);
    let t = [[te + tp, tg - th], [tg + th, te - tp]];
    Some((
        std::array::from_fn(|i| sigma[i]),
        SMatrix::from_fn(|i, j| t[i][j]),
    ))
}

/// dF : H : dF from the stretch-space data and dF̃ = Uᵀ dF V, eq. (3).
#[inline]
fn modal_form<const D: usize>(f: &Filtered<D>, dft: &SMatrix<f64, D, D>) -> f64 {
    let mut q = 0.0;
    for i in 0..D {
        if f.diagonal {
            q += f.scale[i][i] * dft[(i, i)] * dft[(i, i)];
        } else {
            for j in 0..D {
                q += f.scale[i][j] * dft[(i, i)] * dft[(j, j)];
            }
        }
    }
    for k in 0..Spectral::<D>::PAIRS {
        let (i, j) = pair_indices::<D>(k);
        let (a, b) = (dft[(i, j)], dft[(j, i)]);
        q += 0.5 * (f.twist[k] * (a - b) * (a - b) + f.flip[k] * (a + b) * (a + b));
    }
    q
}

#[cfg(test)]
mod tests {
    use super::element_curvature;
    use crate::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
    use crate::reference::cases::{compose, hard_cases_2d, hard_cases_3d, rng, rotation};
    use crate::reference::curvature_reference as reference;
    use crate::{Dim, Energy, Nodes, Rest, Space};
    use rand::Rng;
    use rand_chacha::ChaCha8Rng;

    /// Checks every energy at every hard case; returns (compared, non-finite).
    fn check<const D: usize>(
        energies: &[&dyn Energy<D>],
        cases: &[[f64; D]],
        p: Nodes<D>,
        r: &mut ChaCha8Rng,
    ) -> (usize, usize)
    where
        Space<D>: Dim<D>,
    {
        let rest = <Space<D> as Dim<D>>::rest(&p).unwrap();
        let (mut compared, mut infinite) = (0, 0);
        for e in energies {
            for sigma in cases {
                let f = compose(&rotation::<D>(r), sigma, &rotation::<D>(r));
                let (mut xs, mut dxs) = (Vec::new(), Vec::new());
                for q in p.as_ref() {
                    let y = f * nalgebra::SVector::<f64, D>::from(*q);
                    xs.push(std::array::from_fn(|i| y[i]));
                    dxs.push(std::array::from_fn(|_| r.gen_range(-1.0..1.0)));
                }
                let idx: Vec<usize> = (0..xs.len()).collect();
                let x = <Space<D> as Dim<D>>::gather(&xs, &idx);
                let dx = <Space<D> as Dim<D>>::gather(&dxs, &idx);
                let got = element_curvature(*e, &rest, &x, &dx);
                let (want, scale) = reference(*e, &rest, &x, &dx);
                assert_eq!(got.is_finite(), want.is_finite(), "{} {sigma:?}", e.name());
                if want.is_finite() {
                    let err = (got - want).abs();
                    assert!(
                        err <= 1e-12 * scale,
                        "{} {sigma:?}: {got} vs {want}",
                        e.name()
                    );
                    compared += 1;
                } else {
                    infinite += 1;
                }
            }
        }
        (compared, infinite)
    }

    #[test]
    fn equals_the_raw_element_hessian_along_dx_2d() {
        let cases: Vec<[f64; 2]> = hard_cases_2d().iter().map(|c| c.sigma).collect();
        let snh = StableNeoHookean::new(1.0, 10.0);
        let energies: [&dyn Energy<2>; 3] = [&Arap, &SymmetricDirichlet, &snh];
        let p = [[0.3, -0.2], [1.7, 0.4], [-0.5, 0.9]];
        let (compared, infinite) = check(&energies, &cases, p, &mut rng(31));
        // SD is +∞ at the inverted cases, ARAP's twist has a pole at σ1 + σ2 = 0.
        assert!(compared > 25 && infinite > 0, "{compared} / {infinite}");
    }

    #[test]
    fn equals_the_raw_element_hessian_along_dx_3d() {
        let cases: Vec<[f64; 3]> = hard_cases_3d().iter().map(|c| c.sigma).collect();
        let snh = StableNeoHookean::new(1.0, 10.0);
        let energies: [&dyn Energy<3>; 3] = [&Arap, &SymmetricDirichlet, &snh];
        let p = [
            [0.2, 0.1, 0.0],
            [1.3, -0.4, 0.2],
            [0.1, 1.1, -0.3],
            [0.5, 0.4, 1.6],
        ];
        let (compared, infinite) = check(&energies, &cases, p, &mut rng(32));
        // rounding moves the 3D antipodal case off ARAP's pole: see the next test
        assert!(compared > 30, "{compared} / {infinite}");
    }

    /// ARAP's pole σ1 + σ2 = 0 and SD's boundary σ = 0 hit exactly (unit
    /// tet, diagonal F: no rounding in F or its SVD): not finite, like dxᵀ H dx.
    #[test]
    fn poles_and_the_domain_boundary_are_not_finite_3d() {
        let p = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let rest = Rest::<3>::new(p).unwrap();
        let dx = [
            [0.1, -0.2, 0.3],
            [0.4, 0.0, -0.1],
            [0.2, 0.5, 0.1],
            [-0.3, 0.1, 0.2],
        ];
        let diag = |s: [f64; 3]| p.map(|q| [s[0] * q[0], s[1] * q[1], s[2] * q[2]]);
        let cases: [(&dyn Energy<3>, [f64; 3]); 2] = [
            (&Arap, [1.2, 0.9, -0.9]),
            (&SymmetricDirichlet, [1.2, 0.9, 0.0]),
        ];
        for (e, sigma) in cases {
            let x = diag(sigma);
            let (want, _) = reference(e, &rest, &x, &dx);
            let got = element_curvature(e, &rest, &x, &dx);
            assert!(
                !want.is_finite() && !got.is_finite(),
                "{}: {got} / {want}",
                e.name()
            );
        }
        // and a finite neighbour of the pole stays finite
        let x = diag([1.2, 0.9, -0.8]);
        assert!(element_curvature(&Arap, &rest, &x, &dx).is_finite());
    }

    /// `frame_2d` gives `signed_svd2`'s σ bit for bit and its Uᵀ dF V to
    /// rounding, also at R = 0 (repeated σ), Q = 0 (σ0 + σ1 = 0) and F = 0.
    #[test]
    fn the_2d_frame_is_signed_svd2s() {
        use super::{frame_2d, frame_svd};
        use nalgebra::Matrix2;
        let mut r = rng(33);
        let mut fs = vec![
            Matrix2::identity(),
            Matrix2::new(0.9, 0.0, 0.0, -0.9),
            Matrix2::new(-0.0, 0.0, 0.0, -0.0),
            Matrix2::new(0.0, -1.3, 1.3, 0.0),
            Matrix2::new(-0.7, 0.0, 0.0, -0.7),
            Matrix2::new(1e3, 0.2, -0.1, 1e-6),
        ];
        for c in hard_cases_2d() {
            fs.push(compose(
                &rotation::<2>(&mut r),
                &c.sigma,
                &rotation::<2>(&mut r),
            ));
        }
        for (k, f) in fs.iter().enumerate() {
            let df = Matrix2::new(0.3, -0.7, 0.5, 0.1 + 0.01 * k as f64);
            let (s2, t2) = frame_2d(f, &df).unwrap();
            let (s, t) = frame_svd(f, &df).unwrap();
            assert_eq!(s2.map(f64::to_bits), s.map(f64::to_bits), "{f}");
            assert!((t2 - t).amax() <= 1e-14 * df.amax(), "{f}: {t2} vs {t}");
        }
        let nan = Matrix2::new(f64::NAN, 0.0, 0.0, 1.0);
        let inf = Matrix2::new(f64::INFINITY, 0.0, 0.0, 1.0);
        assert!(frame_2d(&nan, &nan).is_none() && frame_2d(&inf, &inf).is_none());
    }

    #[test]
    fn a_non_finite_position_gives_infinity() {
        let rest = Rest::<2>::new([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).unwrap();
        let x = [[0.0, 0.0], [f64::NAN, 0.0], [0.0, 1.0]];
        let dx = [[0.1, 0.2], [0.3, -0.1], [0.0, 0.5]];
        assert_eq!(element_curvature(&Arap, &rest, &x, &dx), f64::INFINITY);
    }
}
