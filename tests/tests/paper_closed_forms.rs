//! Generated energies against the paper's closed forms (Smith, de Goes,
//! Kim 2019): ARAP eqs. 28–30, Symmetric Dirichlet eqs. 31 and 33–35, MIPS
//! eqs. 36–37 (with the 1/I3³ factor and β = I3/(σ2² − σ1² + α) that the
//! printed eq. 37 lost; see the runtime's `tests/paper.rs`).

use ecc_energies::{Arap, Mips2, SymmetricDirichlet2, SymmetricDirichlet3};
use ecc_runtime::{Energy, PAIRS_3D, ScaleBlock};
use ecc_tests::cases::*;
use ecc_tests::close;
use nalgebra::{Matrix2, Vector2};

const TOL: f64 = 1e-12;

fn sigmas() -> Vec<[f64; 3]> {
    let mut r = rng(61);
    let mut v: Vec<[f64; 3]> = hard_cases_3d().iter().map(|c| c.sigma).collect();
    v.extend((0..100).map(|_| random_sigma::<3>(&mut r)));
    v
}

/// Eqs. 28/30, t = 2 − 4/(σi + σj); on the pole σi + σj = 0 itself every
/// back end returns +∞ (the one-sided limits are ∓∞).
fn arap_twist(sum: f64) -> f64 {
    if sum == 0.0 {
        f64::INFINITY
    } else {
        2.0 - 4.0 / sum
    }
}

#[test]
fn arap_eqs_28_to_30() {
    let e = Arap::new();
    for s in sigmas() {
        let sp = Energy::<3>::spectral(&e, &s);
        for (k, &(i, j)) in PAIRS_3D.iter().enumerate() {
            let want = arap_twist(s[i] + s[j]); // eq. 30: t_k
            assert!(
                close(sp.twist[k], want, TOL),
                "twist {k} at {s:?}: {} vs {want}",
                sp.twist[k]
            );
            assert_eq!(sp.flip[k], 2.0, "eq. 30: flips are 2");
        }
        assert_eq!(
            sp.scale,
            ScaleBlock::Diagonal([2.0; 3]),
            "eq. 30: decoupled, 2"
        );
        let s2 = [s[0], s[2]];
        let sp2 = Energy::<2>::spectral(&e, &s2);
        let want = arap_twist(s2[0] + s2[1]);
        assert!(close(sp2.twist[0], want, TOL), "eq. 28 at {s2:?}");
        assert_eq!(sp2.flip[0], 2.0, "eq. 28");
        assert_eq!(sp2.scale, ScaleBlock::Diagonal([2.0; 2]), "eq. 29");
    }
}

#[test]
fn symmetric_dirichlet_3d_eqs_33_to_35() {
    let e = SymmetricDirichlet3::new();
    for s in sigmas() {
        let i2 = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
        let i3 = s[0] * s[1] * s[2];
        if i3.abs() < 1e-3 {
            continue; // the printed forms cancel catastrophically near I3 = 0
        }
        let sp = Energy::<3>::spectral(&e, &s);
        assert!(matches!(sp.scale, ScaleBlock::Diagonal(_)), "decoupled");
        for k in 0..3 {
            let sk = s[k];
            let scale = 1.0 + 3.0 / sk.powi(4); // eq. 33
            let t = (i2 - sk * sk) * sk.powi(3) / i3.powi(3);
            let twist = 1.0 + sk * sk / (i3 * i3) - t; // eq. 34
            let flip = 1.0 + sk * sk / (i3 * i3) + t; // eq. 35
            let tol = 1e-10; // the printed forms lose digits to cancellation
            assert!(
                close(sp.scale.get(k, k), scale, tol),
                "eq. 33, {k} at {s:?}"
            );
            assert!(
                close(sp.twist[k], twist, tol),
                "eq. 34, {k} at {s:?}: {} vs {twist}",
                sp.twist[k]
            );
            assert!(
                close(sp.flip[k], flip, tol),
                "eq. 35, {k} at {s:?}: {} vs {flip}",
                sp.flip[k]
            );
        }
    }
}

#[test]
fn symmetric_dirichlet_2d_eq_31() {
    let e = SymmetricDirichlet2::new();
    for s in sigmas() {
        let s = [s[0], s[2]];
        let (i2, i3) = (s[0] * s[0] + s[1] * s[1], s[0] * s[1]);
        if i3.abs() < 1e-3 {
            continue;
        }
        let sp = Energy::<2>::spectral(&e, &s);
        assert!(matches!(sp.scale, ScaleBlock::Diagonal(_)));
        assert!(close(sp.scale.get(0, 0), 1.0 + 3.0 / s[0].powi(4), TOL)); // 31a
        assert!(close(sp.scale.get(1, 1), 1.0 + 3.0 / s[1].powi(4), TOL)); // 31b
        assert!(close(
            sp.flip[0],
            1.0 + 1.0 / (i3 * i3) + i2 / i3.powi(3),
            TOL
        )); // 31c
        assert!(close(
            sp.twist[0],
            1.0 + 1.0 / (i3 * i3) - i2 / i3.powi(3),
            TOL
        )); // 31d
    }
}

#[test]
fn mips_eqs_36_37() {
    let e = Mips2::new();
    for s in sigmas() {
        let s = [s[0], s[2]];
        let (i2, i3) = (s[0] * s[0] + s[1] * s[1], s[0] * s[1]);
        if i3.abs() < 1e-2 {
            continue;
        }
        let sp = Energy::<2>::spectral(&e, &s);
        assert!(
            close(sp.twist[0], 2.0 / i3 - i2 / (i3 * i3), TOL),
            "eq. 36a at {s:?}"
        );
        assert!(
            close(sp.flip[0], 2.0 / i3 + i2 / (i3 * i3), TOL),
            "eq. 36b at {s:?}"
        );
        assert!(
            matches!(sp.scale, ScaleBlock::Full(_)),
            "MIPS scaling modes are coupled"
        );
        let alpha = (i2 * i2 - 3.0 * i3 * i3).sqrt();
        let l3 = (i2 * (i2 - alpha) - 2.0 * i3 * i3) / i3.powi(3); // eq. 37a
        let l4 = (i2 * (i2 + alpha) - 2.0 * i3 * i3) / i3.powi(3); // eq. 37b
        let a = Matrix2::from_fn(|i, j| sp.scale.get(i, j));
        let beta = i3 / (s[1] * s[1] - s[0] * s[0] + alpha);
        let gamma = (1.0 + beta * beta).sqrt();
        let (e3, e4) = (
            Vector2::new(beta, 1.0) / gamma,
            Vector2::new(1.0, -beta) / gamma,
        );
        let tol = 1e-11 * a.abs().max();
        let (r3, r4) = ((a * e3 - e3 * l3).amax(), (a * e4 - e4 * l4).amax());
        assert!(
            r3 < tol && r4 < tol,
            "eq. 37 eigenpairs at {s:?}: residuals {r3:e} {r4:e}"
        );
    }
}
