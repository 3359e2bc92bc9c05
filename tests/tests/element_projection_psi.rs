//! The exact element projection (`element_eval_projected`: the d²×d²
//! congruence C, eigensolved by the runtime's fixed-size Jacobi) with energies
//! generated from `.psi` files that have σ-terms (ogden, hencky, poly, and sd
//! for a barrier), against the numeric clamp projection of the full 6×6 /
//! 12×12 element Hessian (`reference::project_psd_numeric`), at every hard
//! case × rotations on a skewed rest shape.

use ecc_runtime::reference::cases::{compose, hard_cases_2d, hard_cases_3d, rng, rotation};
use ecc_runtime::reference::project_psd_numeric;
use ecc_runtime::{Energy, Filter, Rest, element_eval, element_eval_projected};
use nalgebra::SMatrix;

const NAMES: [&str; 4] = ["ogden", "hencky", "poly", "sd"];

/// |P_exact − P_numeric|max / max(1, |K|max), or `None` when K is not finite
/// (then P_exact must be finite and PSD).
fn compare<const N: usize>(
    raw: &SMatrix<f64, N, N>,
    got: &SMatrix<f64, N, N>,
    numeric: fn(&SMatrix<f64, N, N>, Filter) -> SMatrix<f64, N, N>,
) -> Option<f64> {
    assert!(got.iter().all(|v| v.is_finite()), "{got}");
    if !raw.iter().all(|v| v.is_finite()) {
        let min = nalgebra::DMatrix::from_fn(N, N, |i, j| got[(i, j)])
            .symmetric_eigenvalues()
            .min();
        assert!(min > -1e-9 * got.amax(), "pole: min eigenvalue {min}");
        return None;
    }
    let want = numeric(raw, Filter::Clamp);
    Some((got - want).amax() / raw.amax().max(1.0))
}

#[test]
fn generated_energies_match_the_numeric_element_projection_2d() {
    let p = [[0.3, -0.2], [1.7, 0.4], [-0.5, 0.9]];
    let rest = Rest::<2>::new(p).unwrap();
    let cg = rest.congruence();
    let mut r = rng(21);
    let mut compared = 0;
    for name in NAMES {
        let e: Box<dyn Energy<2>> = ecc_energies::by_name::<2>(name).unwrap();
        for case in hard_cases_2d() {
            for _ in 0..4 {
                let f = compose(&rotation::<2>(&mut r), &case.sigma, &rotation::<2>(&mut r));
                let x = p.map(|q| {
                    let y = f * nalgebra::Vector2::new(q[0], q[1]);
                    [y[0], y[1]]
                });
                let raw = element_eval(&*e, &rest, &x, Filter::None, true);
                if !raw.psi.is_finite() {
                    continue; // outside the energy's domain
                }
                let got = element_eval_projected(&*e, &rest, &cg, &x, Filter::Clamp, true);
                if let Some(err) = compare::<6>(&raw.hess, &got.hess, project_psd_numeric::<6>) {
                    assert!(err < 1e-9, "{name} {}: {err:e}", case.name);
                    compared += 1;
                }
            }
        }
    }
    assert!(compared > 100, "only {compared} comparisons");
}

#[test]
fn generated_energies_match_the_numeric_element_projection_3d() {
    let p = [
        [0.2, 0.1, 0.0],
        [1.3, -0.4, 0.2],
        [0.1, 1.1, -0.3],
        [0.5, 0.4, 1.6],
    ];
    let rest = Rest::<3>::new(p).unwrap();
    let cg = rest.congruence();
    let mut r = rng(22);
    let mut compared = 0;
    for name in NAMES {
        let e: Box<dyn Energy<3>> = ecc_energies::by_name::<3>(name).unwrap();
        for case in hard_cases_3d() {
            for _ in 0..4 {
                let f = compose(&rotation::<3>(&mut r), &case.sigma, &rotation::<3>(&mut r));
                let x = p.map(|q| {
                    let y = f * nalgebra::Vector3::new(q[0], q[1], q[2]);
                    [y[0], y[1], y[2]]
                });
                let raw = element_eval(&*e, &rest, &x, Filter::None, true);
                if !raw.psi.is_finite() {
                    continue;
                }
                let got = element_eval_projected(&*e, &rest, &cg, &x, Filter::Clamp, true);
                if let Some(err) = compare::<12>(&raw.hess, &got.hess, project_psd_numeric::<12>) {
                    assert!(err < 1e-9, "{name} {}: {err:e}", case.name);
                    compared += 1;
                }
            }
        }
    }
    assert!(compared > 100, "only {compared} comparisons");
}
