//! `load_parts` and `load_fibre_part`: the two parts of a `.psi` file, each
//! where it belongs, and no part dropped.

use std::path::PathBuf;

use ecc_interp::{LoadError, iso_part_is_zero, load_fibre_part, load_parts};
use ecc_runtime::{Energy, FibreEnergy};

fn library(stem: &str) -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../energies/psi")).join(stem)
}

/// A file in a fresh folder under the system's temporary folder.
fn scratch(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ecc-interp-parts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

const MUSCLE: &str = "fiber a\nparam mu = 1\nparam k = 2\npsi = mu*(I2 - 3) + k/2*(I5 - 1)^2\n";

#[test]
fn a_pure_fibre_file_is_its_fibre_part() {
    let mu = vec![("mu".to_string(), 40.0)];
    let f = load_fibre_part::<3>(library("fibre_stvk.psi"), &mu).unwrap();
    let mut lib = ecc_energies::fibre_by_name::<3>("fibre_stvk").unwrap();
    lib.set_fibre_param("mu", 40.0).unwrap();
    for (i4, i5) in [(1.0, 1.0), (0.3, 1.7), (-0.4, 0.2), (0.0, 1e-12)] {
        let (a, b) = (f.fibre(i4, i5), lib.fibre(i4, i5));
        assert!(
            (a.psi - b.psi).abs() <= 1e-12 * b.psi.abs().max(1.0),
            "{a:?} {b:?}"
        );
        assert!(
            (a.d5 - b.d5).abs() <= 1e-12 * b.d5.abs().max(1.0),
            "{a:?} {b:?}"
        );
        assert_eq!(a.d55, b.d55);
    }
    assert_eq!(f.fibre_params(), [("mu".to_string(), 40.0)]);
    let f2 = load_fibre_part::<2>(library("fibre_stvk.psi"), &[]).unwrap();
    assert_eq!(f2.fibre(0.5, 2.0).psi, 0.5);
}

#[test]
fn both_parts_share_the_parameters() {
    let p = scratch("muscle.psi", MUSCLE);
    let parts = load_parts::<3>(&p, &[("k".to_string(), 6.0)]).unwrap();
    std::fs::remove_file(&p).unwrap();
    let fib = parts.fibre.expect("the fibre part");
    // ψ = k/2 (I5 − 1)² with the override, Ψ_iso = μ (I2 − 3) without ψ
    assert_eq!(fib.fibre(1.0, 2.0).psi, 3.0);
    assert_eq!(fib.fibre_params(), [("mu".into(), 1.0), ("k".into(), 6.0)]);
    let psi = parts.iso.psi(&[1.0, 1.0, 2.0]);
    assert!((psi - 3.0).abs() < 1e-12, "{psi}");
    // an isotropic file: no fibre part
    let snh = load_parts::<3>(library("snh.psi"), &[]).unwrap();
    assert!(snh.fibre.is_none());
}

#[test]
fn a_fibre_part_alone_is_refused_when_it_would_drop_something() {
    let p = scratch("muscle2.psi", MUSCLE);
    let err = load_fibre_part::<3>(&p, &[]).unwrap_err();
    std::fs::remove_file(&p).unwrap();
    assert!(matches!(err, LoadError::IsoBesideFibre { .. }), "{err}");
    let text = err.to_string();
    assert!(
        text.contains("fiber a") && text.contains("[energy] psi"),
        "{text}"
    );
    let err = load_fibre_part::<3>(library("snh.psi"), &[]).unwrap_err();
    assert!(
        matches!(err, LoadError::NoFibrePart { dim: 3, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("no fibre part in 3D"), "{err}");
    let err = load_fibre_part::<3>(library("fibre_stvk.psi"), &[("k9".into(), 1.0)]).unwrap_err();
    assert!(matches!(err, LoadError::Param { .. }), "{err}");
}

#[test]
fn the_isotropic_part_is_zero_only_for_pure_fibre_files() {
    for stem in ["fibre_stvk", "fibre_arap", "fibre_fung"] {
        let m = ecc_dsl::load_file(library(&format!("{stem}.psi"))).unwrap();
        assert!(
            iso_part_is_zero(&m.module, 3) && iso_part_is_zero(&m.module, 2),
            "{stem}"
        );
    }
    let m = ecc_dsl::load_text(MUSCLE, "muscle.psi").unwrap();
    assert!(!iso_part_is_zero(&m.module, 3));
    // a constant isotropic part is not 0 either (it would be dropped)
    let m = ecc_dsl::load_text("fiber a\npsi = 1 + (I5 - 1)^2", "c.psi").unwrap();
    assert!(!iso_part_is_zero(&m.module, 3));
    assert!(!iso_part_is_zero(&m.module, 4));
}
