//! `element_curvature` (the raw dxᵀ ∇²ψ_e dx from the eigensystem, without
//! the element Hessian) against dlᵀ · element_eval(Filter::None).hess · dl
//! (+∞ where ψ is not finite: the trust-region pass it replaces) for every
//! energy of the registry, in 2D and 3D, at every hard case (rest, uniform
//! scale, repeated σ, σi + σj ≈ 0, tiny σ, inversion, huge stretch) with
//! random directions:
//!
//! * under random rotations on a skewed rest simplex: equal to 1e-12 of
//!   |q|‖H‖max‖dl‖² wherever the reference is finite, non-finite exactly
//!   where it is not;
//! * with F = diag(σ) on the unit simplex (no rounding in F or its SVD, so
//!   σi + σj = 0 and σ = 0 are hit exactly): the same two rules.

use ecc_runtime::reference::cases::{compose, hard_cases_2d, hard_cases_3d, rng, rotation};
use ecc_runtime::reference::curvature_reference as reference;
use ecc_runtime::{Dim, Energy, Nodes, Rest, Space, element_curvature};
use nalgebra::SVector;

/// Counts of the comparisons made.
#[derive(Default, Debug)]
struct Seen {
    finite: usize,
    not_finite: usize,
}

/// Deterministic pseudo-random numbers in [−1, 1).
fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

/// x = F p (node by node) and a random dx, as simplex node arrays.
fn deform<const D: usize>(
    p: &[[f64; D]],
    f: &nalgebra::SMatrix<f64, D, D>,
    r: &mut u64,
) -> (Nodes<D>, Nodes<D>)
where
    Space<D>: Dim<D>,
{
    let x: Vec<[f64; D]> = p
        .iter()
        .map(|q| {
            let y = f * SVector::<f64, D>::from(*q);
            std::array::from_fn(|i| y[i])
        })
        .collect();
    let dx: Vec<[f64; D]> = p.iter().map(|_| std::array::from_fn(|_| lcg(r))).collect();
    let idx: Vec<usize> = (0..p.len()).collect();
    (
        <Space<D> as Dim<D>>::gather(&x, &idx),
        <Space<D> as Dim<D>>::gather(&dx, &idx),
    )
}

/// One comparison (see the module docs).
fn check_one<const D: usize>(
    e: &dyn Energy<D>,
    rest: &Rest<D>,
    (x, dx): (Nodes<D>, Nodes<D>),
    what: &str,
    seen: &mut Seen,
) where
    Space<D>: Dim<D>,
{
    let got = element_curvature(e, rest, &x, &dx);
    let (want, scale) = reference(e, rest, &x, &dx);
    assert_eq!(
        got.is_finite(),
        want.is_finite(),
        "{} {what}: {got} vs {want}",
        e.name()
    );
    if want.is_finite() {
        assert!(
            (got - want).abs() <= 1e-12 * scale,
            "{} {what}: {got} vs {want} (scale {scale:e})",
            e.name()
        );
        seen.finite += 1;
    } else {
        seen.not_finite += 1;
    }
}

/// Every registry energy in dimension D at every hard case: rotated on the
/// skewed simplex `skewed`, and diagonal on the unit simplex.
fn check_all<const D: usize>(skewed: &[[f64; D]], cases: &[(&str, [f64; D])], seed: u64) -> Seen
where
    Space<D>: Dim<D>,
{
    let unit: Vec<[f64; D]> = (0..=D)
        .map(|n| std::array::from_fn(|i| if n == i + 1 { 1.0 } else { 0.0 }))
        .collect();
    let idx: Vec<usize> = (0..=D).collect();
    let rest_of =
        |p: &[[f64; D]]| <Space<D> as Dim<D>>::rest(&<Space<D> as Dim<D>>::gather(p, &idx));
    let (skewed_rest, unit_rest) = (rest_of(skewed).unwrap(), rest_of(&unit).unwrap());
    let mut r = rng(seed);
    let mut state = seed;
    let mut seen = Seen::default();
    let mut energies = 0;
    for name in ecc_energies::names() {
        let Some(e) = ecc_energies::by_name::<D>(name) else {
            continue;
        };
        energies += 1;
        for (case, sigma) in cases {
            for k in 0..3 {
                let f = compose(&rotation::<D>(&mut r), sigma, &rotation::<D>(&mut r));
                let nodes = deform(skewed, &f, &mut state);
                check_one(
                    &*e,
                    &skewed_rest,
                    nodes,
                    &format!("{case} rotated {k}"),
                    &mut seen,
                );
            }
            let f =
                nalgebra::SMatrix::<f64, D, D>::from_fn(|i, j| if i == j { sigma[i] } else { 0.0 });
            let nodes = deform(&unit, &f, &mut state);
            check_one(
                &*e,
                &unit_rest,
                nodes,
                &format!("{case} diagonal"),
                &mut seen,
            );
        }
    }
    assert!(energies >= 10, "only {energies} energies in {D}D");
    seen
}

#[test]
fn every_energy_matches_the_raw_element_hessian_2d() {
    let mut cases: Vec<(&str, [f64; 2])> =
        hard_cases_2d().iter().map(|c| (c.name, c.sigma)).collect();
    // the boundary σ = 0 of the barrier energies' domain
    cases.push(("sigma 0", [1.1, 0.0]));
    let skewed = [[0.3, -0.2], [1.7, 0.4], [-0.5, 0.9]];
    let seen = check_all(&skewed, &cases, 41);
    // inverted cases are outside the barriers' domains; ARAP has a pole at σ1 + σ2 = 0
    assert!(seen.finite > 200 && seen.not_finite > 10, "{seen:?}");
}

#[test]
fn every_energy_matches_the_raw_element_hessian_3d() {
    let mut cases: Vec<(&str, [f64; 3])> =
        hard_cases_3d().iter().map(|c| (c.name, c.sigma)).collect();
    cases.push(("sigma 0", [1.1, 0.8, 0.0]));
    let skewed = [
        [0.2, 0.1, 0.0],
        [1.3, -0.4, 0.2],
        [0.1, 1.1, -0.3],
        [0.5, 0.4, 1.6],
    ];
    let seen = check_all(&skewed, &cases, 42);
    assert!(seen.finite > 300 && seen.not_finite > 10, "{seen:?}");
}
