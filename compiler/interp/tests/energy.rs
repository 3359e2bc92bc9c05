//! InterpEnergy: stretch-space derivatives vs differences, vs the runtime's
//! hand-written energies, parameters, flags and loader errors.

use ecc_interp::{InterpEnergy, LoadError, load_psi, load_source};
use ecc_runtime::energies::{Arap, StableNeoHookean, SymmetricDirichlet};
use ecc_runtime::{Energy, ParamError, Spectral};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn lib(name: &str) -> String {
    format!(
        "{}/../../energies/psi/{name}.psi",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn interp<const D: usize>(name: &str) -> InterpEnergy<D> {
    let src = std::fs::read_to_string(lib(name)).unwrap();
    load_source::<D>(&src, &format!("{name}.psi"), &[]).unwrap_or_else(|e| panic!("{e}"))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / a.abs().max(b.abs()).max(1.0)
}

/// Random σ ordered as the signed SVD returns it (|σ0| ≥ |σ1| ≥ |σ2| > 0).
fn sigma<const D: usize>(rng: &mut ChaCha8Rng) -> [f64; D] {
    let mut s: [f64; D] = std::array::from_fn(|_| rng.gen_range(0.4..1.8));
    s.sort_by(|a, b| b.total_cmp(a));
    s
}

/// Central difference of `f` along coordinate `i` of σ.
fn diff<const D: usize>(f: impl Fn(&[f64; D]) -> f64, s: &[f64; D], i: usize) -> f64 {
    let h = 1e-5;
    let mut p = *s;
    let mut m = *s;
    p[i] += h;
    m[i] -= h;
    (f(&p) - f(&m)) / (2.0 * h)
}

fn check_derivatives<const D: usize>(name: &str, e: &InterpEnergy<D>, rng: &mut ChaCha8Rng) {
    for _ in 0..10 {
        let s = sigma::<D>(rng);
        let sp: Spectral<D> = e.spectral(&s);
        assert!(
            rel(sp.psi, e.psi(&s)) < 1e-14,
            "{name}: spectral psi vs psi"
        );
        for i in 0..D {
            let g = diff(|x| e.psi(x), &s, i);
            assert!(
                rel(sp.grad[i], g) < 1e-7,
                "{name} {D}D grad {i}: {} vs {g}",
                sp.grad[i]
            );
            for j in 0..D {
                let a = diff(|x| e.spectral(x).grad[j], &s, i);
                assert!(
                    rel(sp.scale.get(i, j), a) < 1e-6,
                    "{name} {D}D A[{i}][{j}]: {} vs {a}",
                    sp.scale.get(i, j)
                );
            }
        }
        for k in 0..D * (D - 1) / 2 {
            let (i, j) = ecc_runtime::pair_indices::<D>(k);
            let flip = (sp.grad[i] - sp.grad[j]) / (s[i] - s[j]);
            let twist = (sp.grad[i] + sp.grad[j]) / (s[i] + s[j]);
            if (s[i] - s[j]).abs() > 1e-3 {
                assert!(rel(sp.flip[k], flip) < 1e-9, "{name} flip {k}");
            }
            assert!(rel(sp.twist[k], twist) < 1e-9, "{name} twist {k}");
        }
    }
}

#[test]
fn derivatives_match_differences_for_the_whole_library() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for name in [
        "arap",
        "corotational",
        "sd2",
        "sarap2",
        "mips2",
        "stvk",
        "neohookean",
        "snh",
        "hencky2",
        "ogden2",
        "poly2",
        "polyneg2",
    ] {
        check_derivatives::<2>(name, &interp::<2>(name), &mut rng);
    }
    for name in [
        "arap",
        "corotational",
        "sd3",
        "sarap3",
        "stvk",
        "neohookean",
        "snh",
        "hencky",
        "ogden",
        "poly",
        "polyneg",
    ] {
        check_derivatives::<3>(name, &interp::<3>(name), &mut rng);
    }
}

fn same_spectral<const D: usize>(name: &str, a: &Spectral<D>, b: &Spectral<D>, with_psi: bool) {
    let tol = 1e-12;
    if with_psi {
        assert!(rel(a.psi, b.psi) < tol, "{name} psi {} vs {}", a.psi, b.psi);
    }
    for i in 0..D {
        assert!(rel(a.grad[i], b.grad[i]) < tol, "{name} grad");
        for j in 0..D {
            assert!(
                rel(a.scale.get(i, j), b.scale.get(i, j)) < tol,
                "{name} A[{i}][{j}]"
            );
        }
    }
    for k in 0..D * (D - 1) / 2 {
        assert!(
            rel(a.twist[k], b.twist[k]) < tol,
            "{name} twist {k}: {} vs {}",
            a.twist[k],
            b.twist[k]
        );
        assert!(
            rel(a.flip[k], b.flip[k]) < tol,
            "{name} flip {k}: {} vs {}",
            a.flip[k],
            b.flip[k]
        );
    }
}

#[test]
fn agrees_with_the_hand_written_runtime_energies() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let (arap2, arap3) = (interp::<2>("arap"), interp::<3>("arap"));
    let (sd2, sd3) = (interp::<2>("sd2"), interp::<3>("sd3"));
    let (snh2, snh3) = (interp::<2>("snh"), interp::<3>("snh"));
    let snh = StableNeoHookean::new(1.0, 10.0);
    for trial in 0..50 {
        let mut s2 = sigma::<2>(&mut rng);
        let mut s3 = sigma::<3>(&mut rng);
        if trial % 4 == 3 {
            s2[1] = -s2[1];
            s3[2] = -s3[2];
        }
        if trial % 7 == 6 {
            s3[1] = s3[0];
            s2[1] = s2[0];
        }
        same_spectral(
            "arap2",
            &arap2.spectral(&s2),
            &Energy::<2>::spectral(&Arap, &s2),
            true,
        );
        same_spectral(
            "arap3",
            &arap3.spectral(&s3),
            &Energy::<3>::spectral(&Arap, &s3),
            true,
        );
        same_spectral(
            "sd2",
            &sd2.spectral(&s2),
            &Energy::<2>::spectral(&SymmetricDirichlet, &s2),
            true,
        );
        same_spectral(
            "sd3",
            &sd3.spectral(&s3),
            &Energy::<3>::spectral(&SymmetricDirichlet, &s3),
            true,
        );
        // The hand-written SNH may drop a constant from Ψ; derivatives must agree.
        same_spectral(
            "snh2",
            &snh2.spectral(&s2),
            &Energy::<2>::spectral(&snh, &s2),
            false,
        );
        same_spectral(
            "snh3",
            &snh3.spectral(&s3),
            &Energy::<3>::spectral(&snh, &s3),
            false,
        );
    }
}

#[test]
fn outside_the_domain_is_infinite_never_nan() {
    let nh = interp::<3>("neohookean");
    let inverted = [1.2, 0.9, -0.8];
    assert_eq!(nh.psi(&inverted), f64::INFINITY);
    assert_eq!(nh.spectral(&inverted), Spectral::infinite());
    let hencky = interp::<2>("hencky2");
    assert_eq!(hencky.psi(&[1.0, -0.5]), f64::INFINITY);
    assert!(nh.info().barrier);
    assert!(!interp::<3>("arap").info().barrier);
}

#[test]
fn svd_free_energies_evaluate_from_i2_and_i3() {
    for (e, s) in [
        (interp::<2>("sd2"), [1.3, 0.7]),
        (interp::<2>("mips2"), [1.1, 0.4]),
    ] {
        assert!(e.info().svd_free_psi);
        let (i2, i3) = (s[0] * s[0] + s[1] * s[1], s[0] * s[1]);
        assert!(rel(e.psi_i2_i3(i2, i3).unwrap(), e.psi(&s)) < 1e-14);
    }
    let snh = interp::<3>("snh");
    assert!(snh.info().svd_free_psi);
    let s = [1.3, 0.9, 0.7];
    let (i2, i3) = (s.iter().map(|x| x * x).sum(), s.iter().product());
    assert!(rel(snh.psi_i2_i3(i2, i3).unwrap(), snh.psi(&s)) < 1e-14);
    let arap = interp::<3>("arap");
    assert!(!arap.info().svd_free_psi);
    assert_eq!(arap.psi_i2_i3(3.0, 1.0), None);
}

#[test]
fn parameters_can_be_listed_and_set() {
    let mut e = interp::<3>("snh");
    assert_eq!(
        e.params(),
        vec![("mu".to_string(), 1.0), ("lambda".to_string(), 10.0)]
    );
    let s = [1.3, 0.9, 0.7];
    let before = e.spectral(&s);
    e.set_param("mu", 2.0).unwrap();
    assert_eq!(e.params()[0].1, 2.0);
    let snh = StableNeoHookean::new(2.0, 10.0);
    same_spectral(
        "snh mu=2",
        &e.spectral(&s),
        &Energy::<3>::spectral(&snh, &s),
        false,
    );
    assert_ne!(before, e.spectral(&s));
    assert!(
        matches!(e.set_param("nu", 1.0), Err(ParamError::Unknown { known, .. }) if known == ["mu", "lambda"])
    );
    assert!(matches!(
        e.set_param("mu", f64::NAN),
        Err(ParamError::NotFinite { .. })
    ));
    assert_eq!(e.params()[0].1, 2.0, "a rejected value changes nothing");
}

#[test]
fn the_loader_reports_clear_errors() {
    let overrides = [("lambda".to_string(), 100.0)];
    let e = load_psi::<3>(lib("snh"), &overrides).unwrap();
    assert_eq!(e.name(), "snh");
    assert_eq!(e.params()[1].1, 100.0);

    match load_psi::<3>("/no/such/file.psi", &[]) {
        Err(LoadError::Io { path, .. }) => assert_eq!(path, "/no/such/file.psi"),
        other => panic!("{:?}", other.err()),
    }
    match load_source::<2>("param mu = 1\npsi = mu*I2 + foo\n", "bad.psi", &[]) {
        Err(e @ LoadError::Syntax { .. }) => {
            let text = e.to_string();
            assert!(text.contains("bad.psi:2:"), "{text}");
            assert!(text.contains("foo"), "{text}");
        }
        other => panic!("{:?}", other.err()),
    }
    match load_psi::<2>(lib("sd3"), &[]) {
        Err(LoadError::NoSuchDim { dim: 2, reason, .. }) => assert!(!reason.is_empty()),
        other => panic!("{:?}", other.err()),
    }
    let bad = [("nu".to_string(), 1.0)];
    assert!(matches!(
        load_psi::<3>(lib("snh"), &bad),
        Err(LoadError::Param {
            source: ParamError::Unknown { .. },
            ..
        })
    ));
    let inf = [("mu".to_string(), f64::INFINITY)];
    assert!(matches!(
        load_psi::<3>(lib("snh"), &inf),
        Err(LoadError::Param {
            source: ParamError::NotFinite { .. },
            ..
        })
    ));
}

/// Ψ1 of SD 3D vanishes on σ1 + σ2 = 0 and rounds to exactly 0.0 at this
/// σ (from the SVD of a rotated diag(1.2, 0.9, −0.9)); the twist must still be
/// the limit, not 2Ψ2 + σ0Ψ3.
#[test]
fn a_psi1_that_rounds_to_zero_keeps_the_antipodal_limit() {
    let sd3 = interp::<3>("sd3");
    for s in [
        [1.2, 0.9000000000000006, -0.9000000000000002],
        [1.2, 0.9, -0.9],
    ] {
        same_spectral(
            "sd3 antipodal",
            &sd3.spectral(&s),
            &Energy::<3>::spectral(&SymmetricDirichlet, &s),
            true,
        );
    }
}
