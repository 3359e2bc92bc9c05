//! The library's fibre energies (energies/psi/fibre_*.psi, issue 16) three
//! ways — generated Rust (`ecc_energies::fibre_by_name`), interpreted
//! (`ecc_interp::fibre_from_module`) and the runtime's hand-written
//! `ecc_runtime::energies::fibre_by_name` — agree on ψ and its five partials
//! at random points incl. I4 < 0, I5 → 0 and large I5; the interpreted
//! partials match central differences; the raw F-space Hessian's numeric
//! eigenvalues are HOBAK's published forms (`ANISOTROPIC_*::clampedHessian`;
//! for fibre_fung, HOBAK's Fung structure with the HGO exponent), and
//! HOBAK's own Fung energy written in the language has HOBAK's eigenvalues
//! and clamped Hessian.

use ecc_runtime::fibre::{fibre_f, i5_eigenvalues, invariant5};
use ecc_runtime::{FibreDerivs, FibreEnergy, FibreUse, filter::Filter};
use nalgebra::{SMatrix, SVector, SymmetricEigen};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// (library stem, hand-written runtime name, the FibreUse HOBAK's form implies).
const FIBRES: [(&str, &str, FibreUse); 3] = [
    ("fibre_arap", "fibre-arap", FibreUse::Both),
    ("fibre_stvk", "fibre-stvk", FibreUse::I5),
    ("fibre_fung", "fibre-fung", FibreUse::I5),
];

fn interpreted<const D: usize>(stem: &str, params: &[(String, f64)]) -> Box<dyn FibreEnergy<D>> {
    let path = format!(
        "{}/../../energies/psi/{stem}.psi",
        env!("CARGO_MANIFEST_DIR")
    );
    let loaded = ecc_dsl::load_file(&path).unwrap();
    let f = ecc_interp::fibre_from_module::<D>(&loaded.module, &path, params).unwrap();
    Box::new(f.expect("a fibre part"))
}

fn arr(d: &FibreDerivs) -> [f64; 6] {
    [d.psi, d.d4, d.d5, d.d44, d.d45, d.d55]
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    a == b || (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

/// Points (I4, I5): random, inverted fibre, I5 → 0, large stretch, I4 = 0.
fn points() -> Vec<(f64, f64)> {
    let mut rng = ChaCha8Rng::seed_from_u64(16);
    let mut p: Vec<(f64, f64)> = (0..200)
        .map(|_| (rng.gen_range(-2.0..2.0), rng.gen_range(1e-3..4.0)))
        .collect();
    p.extend([
        (-0.5, 0.25),
        (1e-8, 1e-12),
        (-1e-8, 1e-12),
        (3.0, 9.0),
        (0.0, 1.0),
        (1.0, 1.0),
    ]);
    p
}

#[test]
fn generated_interpreted_and_hand_written_agree() {
    let params = [("mu".to_string(), 2.5)];
    for (stem, hand, uses) in FIBRES {
        let over: &[(String, f64)] = if stem == "fibre_fung" { &[] } else { &params };
        let interp = interpreted::<3>(stem, over);
        let mut gen3 = ecc_energies::fibre_by_name::<3>(stem).unwrap();
        let mut hand3 = ecc_runtime::energies::fibre_by_name::<3>(hand).unwrap();
        for (n, v) in over {
            gen3.set_fibre_param(n, *v).unwrap();
            hand3.set_fibre_param(n, *v).unwrap();
        }
        assert_eq!(interp.uses(), uses, "{stem}");
        assert_eq!(gen3.uses(), uses, "{stem}");
        assert_eq!(interp.fibre_params(), gen3.fibre_params(), "{stem}");
        for (i4, i5) in points() {
            let (a, b, c) = (
                arr(&interp.fibre(i4, i5)),
                arr(&gen3.fibre(i4, i5)),
                arr(&hand3.fibre(i4, i5)),
            );
            for k in 0..6 {
                assert!(
                    close(a[k], b[k], 1e-13),
                    "{stem} {k} at ({i4}, {i5}): interp {} gen {}",
                    a[k],
                    b[k]
                );
                assert!(
                    close(a[k], c[k], 1e-11),
                    "{stem} {k} at ({i4}, {i5}): interp {} hand {}",
                    a[k],
                    c[k]
                );
            }
        }
    }
}

#[test]
fn partials_match_central_differences() {
    for (stem, _, _) in FIBRES {
        let e = interpreted::<2>(stem, &[]);
        for (i4, i5) in points()
            .into_iter()
            .filter(|(i4, i5)| i4.abs() > 1e-3 && *i5 > 1e-2 && *i5 < 3.0)
        {
            let h = 1e-6 * (1.0 + i5);
            let f = |a: f64, b: f64| arr(&e.fibre(a, b));
            let d = f(i4, i5);
            let (p5, m5) = (f(i4, i5 + h), f(i4, i5 - h));
            let (p4, m4) = (f(i4 + h, i5), f(i4 - h, i5));
            let fd = |p: f64, m: f64| (p - m) / (2.0 * h);
            let want = [
                (d[1], fd(p4[0], m4[0])),
                (d[2], fd(p5[0], m5[0])),
                (d[3], fd(p4[1], m4[1])),
                (d[4], fd(p5[1], m5[1])),
                (d[5], fd(p5[2], m5[2])),
            ];
            for (k, (got, num)) in want.iter().enumerate() {
                assert!(
                    close(*got, *num, 1e-6),
                    "{stem} partial {k} at ({i4}, {i5}): {got} vs {num}"
                );
            }
        }
    }
}

#[test]
fn outside_the_domain_psi_is_infinite_never_nan() {
    let m = ecc_dsl::compile("fiber a\npsi = I2 - 3 + log(I5)^2", "t").unwrap();
    // The isotropic part loads like any energy when asked for explicitly.
    ecc_interp::iso_part_from_module::<3>(&m, "t.psi", &[]).unwrap();
    let f = ecc_interp::fibre_from_module::<3>(&m, "t.psi", &[])
        .unwrap()
        .unwrap();
    assert_eq!(f.fibre(1.0, 0.0).psi, f64::INFINITY);
    assert!(f.fibre(1.0, 2.0).psi.is_finite());
    let m = ecc_dsl::compile("fiber a\npsi = exp(log(I4))", "t").unwrap();
    let f = ecc_interp::fibre_from_module::<3>(&m, "t.psi", &[])
        .unwrap()
        .unwrap();
    assert_eq!(f.fibre(-0.5, 1.0).psi, f64::INFINITY, "I4 > 0 as written");
    assert_eq!(f.fibre(0.5, 1.0).psi, 0.5);
}

/// HOBAK's eigenvalues (`ANISOTROPIC_*::clampedHessian`): (along, across).
fn published(stem: &str, i4: f64, i5: f64) -> (f64, f64) {
    let (mu, k1, k2) = (1.0, 1.0, 1.0);
    match stem {
        "fibre_arap" => {
            let s = if i4 > 0.0 { 1.0 } else { -1.0 };
            (mu, mu * (1.0 - s / i5.sqrt()))
        }
        "fibre_stvk" => (2.0 * mu * (i5 - 1.0) + 4.0 * mu * i5, 2.0 * mu * (i5 - 1.0)),
        _ => {
            let t = i5 - 1.0;
            let e = (k2 * t * t).exp();
            (
                2.0 * e * k1 * t + 4.0 * e * k1 * (1.0 + 2.0 * k2 * t * t) * i5,
                2.0 * e * k1 * t,
            )
        }
    }
}

#[test]
fn raw_hessian_eigenvalues_are_hobaks_published_forms() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for (stem, _, _) in FIBRES {
        let e = ecc_energies::fibre_by_name::<3>(stem).unwrap();
        for trial in 0..40 {
            let mut f = SMatrix::<f64, 3, 3>::from_fn(|_, _| rng.gen_range(-1.5..1.5));
            if trial % 4 == 0 {
                f = -f; // inverted elements, fibre along the flipped axes
            }
            let a = SVector::<f64, 3>::from_fn(|_, _| rng.gen_range(-1.0..1.0)).normalize();
            let p = fibre_f(&*e, &f, &a, Filter::None, true);
            let eig = SymmetricEigen::new(p.hess).eigenvalues;
            let i5 = invariant5(&f, &a);
            let i4 = ecc_runtime::fibre::invariant4(&f, &a);
            let (along, across) = published(stem, i4, i5);
            let [l_al, l_ac, _] = i5_eigenvalues(&e.fibre(i4, i5), i5);
            assert!(
                close(l_al, along, 1e-10) && close(l_ac, across, 1e-10),
                "{stem}"
            );
            // multiset {along ×1, across ×2, 0 ×6} against the numeric eigensolve
            let mut want = vec![along, across, across, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            let mut got: Vec<f64> = eig.iter().copied().collect();
            want.sort_by(f64::total_cmp);
            got.sort_by(f64::total_cmp);
            let scale = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for (g, w) in got.iter().zip(&want) {
                assert!(
                    (g - w).abs() <= 1e-9 * scale,
                    "{stem} F = {f}: {got:?} vs {want:?}"
                );
            }
        }
    }
}

/// HOBAK's own Fung energy, written in the language: Ψ = μ(exp(I5 − 1) − I5)
/// (HOBAKv1 src/Hyperelastic/Volume/ANISOTROPIC_FUNG.cpp; the library's
/// fibre_fung.psi is the Holzapfel–Gasser–Ogden form instead). Its raw
/// Hessian's numeric eigenvalues are HOBAK's λ₀ = λ₁ + 4μ I5 e^{I5−1} (×1),
/// λ₁ = 2μ(e^{I5−1} − 1) (×2) and 0 (×6), and ecc's clamped Hessian is
/// HOBAK's `clampedHessian`, transcribed here from that file: the full
/// 2μ((e − 1) A⊗I + 2e vec(FA) vec(FA)ᵀ) when λ₀, λ₁ > 0, 0 when λ₀ < 0,
/// else λ₀ n nᵀ with n = vec(FA)/‖vec(FA)‖.
#[test]
fn hobaks_fung_written_in_the_language_has_hobaks_eigensystem() {
    let mu = 1.3;
    let m = ecc_dsl::compile(
        "fiber a\nparam mu = 1\npsi = mu*(exp(I5 - 1) - I5)",
        "hobak_fung",
    )
    .unwrap();
    let e = ecc_interp::fibre_from_module::<3>(&m, "hobak_fung", &[("mu".to_string(), mu)])
        .unwrap()
        .expect("a fibre part");
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (mut both, mut rank_one, mut zero) = (0, 0, 0);
    for trial in 0..60 {
        let scale = [0.2, 0.6, 1.0, 1.6][trial % 4];
        let mut f = SMatrix::<f64, 3, 3>::from_fn(|_, _| scale * rng.gen_range(-1.0..1.0));
        if trial % 3 == 0 {
            f = -f;
        }
        let a = SVector::<f64, 3>::from_fn(|_, _| rng.gen_range(-1.0..1.0)).normalize();
        let fa = f * a;
        let i5 = fa.norm_squared();
        let ex = (i5 - 1.0).exp();
        let l1 = 2.0 * mu * (ex - 1.0);
        let l0 = l1 + 4.0 * mu * i5 * ex;
        // vec(F A) column-major, A = a aᵀ: (F A)[r, c] = (F a)[r] a[c].
        let vfa = SVector::<f64, 9>::from_fn(|k, _| fa[k % 3] * a[k / 3]);
        let h5 = SMatrix::<f64, 9, 9>::from_fn(|i, j| {
            if i % 3 == j % 3 {
                a[i / 3] * a[j / 3]
            } else {
                0.0
            }
        });
        let full = (h5 * (ex - 1.0) + vfa * vfa.transpose() * (2.0 * ex)) * (2.0 * mu);
        let hobak_clamped = if l0 > 0.0 && l1 > 0.0 {
            both += 1;
            full
        } else if l0 < 0.0 {
            zero += 1;
            SMatrix::zeros()
        } else {
            rank_one += 1;
            let n = vfa.normalize();
            n * n.transpose() * l0
        };
        let raw = fibre_f(&e, &f, &a, Filter::None, true).hess;
        let mut got: Vec<f64> = SymmetricEigen::new(raw)
            .eigenvalues
            .iter()
            .copied()
            .collect();
        let mut want = vec![l0, l1, l1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        got.sort_by(f64::total_cmp);
        want.sort_by(f64::total_cmp);
        let s = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (g, w) in got.iter().zip(&want) {
            assert!((g - w).abs() <= 1e-10 * s, "F = {f}: {got:?} vs {want:?}");
        }
        assert!(
            (raw - full).abs().max() <= 1e-10 * s,
            "raw Hessian, F = {f}"
        );
        let clamped = fibre_f(&e, &f, &a, Filter::Clamp, true).hess;
        assert!(
            (clamped - hobak_clamped).abs().max() <= 1e-10 * s,
            "clamped Hessian, F = {f}"
        );
    }
    // The sample reaches HOBAK's two clamped branches, not only the PSD one
    // (λ₀ < 0 cannot happen: λ₀ = 2μ(e(1 + 2 I5) − 1) > 0 for I5 ≥ 0).
    assert!(both > 5 && rank_one > 5, "{both} {rank_one} {zero}");
}

/// The whole-energy entry points refuse a fibre energy instead of silently
/// evaluating its isotropic part alone (a different energy).
#[test]
fn whole_energy_loaders_refuse_a_fibre_part() {
    let src = "fiber a\nparam k = 2\npsi = I2 - 3 + k*(I5 - 1)^2";
    for err in [
        ecc_interp::load_source::<3>(src, "t.psi", &[]).err(),
        ecc_interp::load_source::<2>(src, "t.psi", &[]).err(),
        ecc_interp::load_psi::<3>("../../energies/psi/fibre_stvk.psi", &[]).err(),
    ] {
        let err = err.expect("a fibre energy must not load as an isotropic one");
        assert!(
            matches!(err, ecc_interp::LoadError::FibrePart { .. }),
            "{err}"
        );
        let text = err.to_string();
        assert!(
            text.contains("fiber a") && text.contains("--fiber"),
            "{text}"
        );
    }
    // An isotropic energy still loads.
    ecc_interp::load_source::<3>("psi = I2 - 3", "t.psi", &[]).unwrap();
}
