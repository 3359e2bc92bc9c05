//! Issue 16: the fibre partials' poles at I5 = 0 / I4 = 0 evaluate to ±∞
//! with the limit's sign, never ∞ − ∞ = NaN (`compile::poles`, eq. P2), and
//! the collected form equals the plain derivative everywhere else.

use ecc_dsl::{Env, FibreIr, Sym, compile_dim, eval};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const LIBRARY: [&str; 3] = ["fibre_arap", "fibre_stvk", "fibre_fung"];

fn library(stem: &str, dim: u8) -> FibreIr {
    let path = format!(
        "{}/../../energies/psi/{stem}.psi",
        env!("CARGO_MANIFEST_DIR")
    );
    let src = std::fs::read_to_string(&path).unwrap();
    let ir = compile_dim(&src, stem, dim).unwrap_or_else(|d| panic!("{stem}: {d}"));
    ir.fibre.expect("a fibre part")
}

/// [ψ, ψ4, ψ5, ψ44, ψ45, ψ55] at (I4, I5) with parameters `params`.
fn partials(f: &FibreIr, params: &[f64], i4: f64, i5: f64) -> [f64; 6] {
    let env = Env::new(3, &[], params).with_fibre(i4, i5);
    f.roots().map(|r| eval(&f.graph, r, &env))
}

/// ψ55 of anisotropic ARAP at F a = 0 is the pole μ s / (4 I5^{3/2}):
/// −∞ for an inverted or degenerate fibre (I4 ≤ 0, s = −1), +∞ for I4 > 0;
/// ψ5 = μ (√I5 − s) / (2 √I5) is the opposite pole.
#[test]
fn arap_d55_at_fa_zero_is_a_signed_pole() {
    for dim in [2, 3] {
        let f = library("fibre_arap", dim);
        for (mu, i4, s) in [(1.0, 0.0, -1.0), (2.5, -0.3, -1.0), (1.0, 0.4, 1.0)] {
            let [psi, d4, d5, d44, d45, d55] = partials(&f, &[mu], i4, 0.0);
            assert_eq!(psi, mu / 2.0, "(I4, I5) = ({i4}, 0)");
            assert_eq!((d4, d44, d45), (0.0, 0.0, 0.0));
            assert_eq!(d55, s * f64::INFINITY, "ψ55 at I4 = {i4}");
            assert_eq!(d5, -s * f64::INFINITY, "ψ5 at I4 = {i4}");
        }
        // Approaching the pole, ψ55 follows μ s / (4 I5^{3/2}).
        for i5 in [1e-6, 1e-12, 1e-20] {
            let [.., d55] = partials(&f, &[1.0], -1.0, i5);
            let want = -0.25 / (i5 * i5.sqrt());
            assert!(
                (d55 - want).abs() <= 1e-12 * want.abs(),
                "{i5}: {d55} vs {want}"
            );
        }
    }
}

/// No library fibre energy has a NaN partial where I5 = 0 or I4 = 0.
#[test]
fn library_fibre_partials_are_never_nan_at_zero_invariants() {
    for stem in LIBRARY {
        for dim in [2, 3] {
            let f = library(stem, dim);
            let params: Vec<f64> = vec![1.0; f.graph.param_names().len()];
            for (i4, i5) in [(0.0, 0.0), (0.5, 0.0), (-0.5, 0.0), (0.0, 1.0), (0.0, 0.25)] {
                let p = partials(&f, &params, i4, i5);
                assert!(
                    p.iter().all(|x| !x.is_nan()),
                    "{stem} {dim}D ({i4}, {i5}): {p:?}"
                );
            }
        }
    }
}

/// Away from the poles the collected partials equal the plain derivatives
/// of ψ (differentiated afresh, without the rewrite) to 1e-12 relative.
#[test]
fn collected_partials_equal_the_plain_derivatives() {
    let mut rng = ChaCha8Rng::seed_from_u64(1616);
    for stem in LIBRARY {
        let f = library(stem, 3);
        let mut g = f.graph.clone();
        let d4 = g.diff(f.psi, Sym::I4);
        let d5 = g.diff(f.psi, Sym::I5);
        let plain = [
            f.psi,
            d4,
            d5,
            g.diff(d4, Sym::I4),
            g.diff(d4, Sym::I5),
            g.diff(d5, Sym::I5),
        ];
        for _ in 0..200 {
            let (i4, i5) = (rng.gen_range(-2.0..2.0), rng.gen_range(1e-3..4.0));
            let params: Vec<f64> = f
                .graph
                .param_names()
                .iter()
                .map(|_| rng.gen_range(0.2..3.0))
                .collect();
            let new = partials(&f, &params, i4, i5);
            let env = Env::new(3, &[], &params).with_fibre(i4, i5);
            for (k, (&root, got)) in plain.iter().zip(new).enumerate() {
                let want = eval(&g, root, &env);
                let tol = 1e-12 * want.abs().max(got.abs()).max(1e-300);
                assert!(
                    (got - want).abs() <= tol,
                    "{stem} partial {k} at ({i4}, {i5}): {got} vs {want}"
                );
            }
        }
    }
}

/// The rewrite collects only distinct negative powers: ARAP's ψ55 becomes
/// one pole times a sum, and the partials without poles keep their form.
#[test]
fn only_mixed_negative_powers_are_collected() {
    let text = |stem: &str, k: usize| {
        let f = library(stem, 3);
        f.graph.to_text(f.roots()[k])
    };
    let d55 = text("fibre_arap", 5);
    assert_eq!(
        d55,
        "(-mu*(-sign(I4) + sqrt(I5)) + mu*sqrt(I5))/(4*I5^(3/2))"
    );
    assert_eq!(
        text("fibre_arap", 2),
        "mu*(-sign(I4) + sqrt(I5))/(2*sqrt(I5))"
    );
    assert_eq!(text("fibre_stvk", 2), "mu*(I5 - 1)");
    assert_eq!(text("fibre_stvk", 5), "mu");
}

/// A user pole in I4 with odd-denominator powers (defined for I4 < 0):
/// ψ = (∛I4 + 1)², ψ44 = (2/9) I4^{-4/3} − (4/9)(∛I4 + 1) I4^{-5/3} is
/// ∞ − ∞ at I4 = 0 unless collected; collected it is −∞ (the limit
/// −(4/9) I4^{-5/3} from above), and it equals the plain derivative at
/// negative and positive I4.
#[test]
fn i4_poles_with_odd_roots_are_collected_on_both_sides() {
    let ir = compile_dim("fiber a\npsi = (I4^(1/3) + 1)^2", "t", 3).unwrap();
    let f = ir.fibre.unwrap();
    let [.., d44, _, _] = partials(&f, &[], 0.0, 1.0);
    assert_eq!(d44, f64::NEG_INFINITY);
    let mut g = f.graph.clone();
    let d4 = g.diff(f.psi, Sym::I4);
    let plain = g.diff(d4, Sym::I4);
    for i4 in [-2.0, -0.3, -1e-6, 1e-6, 0.3, 2.0] {
        let [.., got, _, _] = partials(&f, &[], i4, 1.0);
        let env = Env::new(3, &[], &[]).with_fibre(i4, 1.0);
        let want = eval(&g, plain, &env);
        assert!(
            (got - want).abs() <= 1e-12 * want.abs(),
            "{i4}: {got} vs {want}"
        );
    }
}
