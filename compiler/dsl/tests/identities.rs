//! Exact polynomial machinery: identity proofs and exact division.

use ecc_dsl::poly::Converter;
use ecc_dsl::testing::{divide, prove_zero};
use ecc_dsl::{DimIr, PairIr, Proof, ScaleIr, Sym, compile_dim};

fn zero(src: &str, dim: u8) -> Proof {
    prove_zero(src, dim).unwrap_or_else(|e| panic!("{src}: {e}"))
}

fn div(src: &str, dim: u8, i: usize, j: usize, s: i64) -> Option<String> {
    divide(src, dim, i, j, s).unwrap_or_else(|e| panic!("{src}: {e}"))
}

fn library(name: &str, dim: u8) -> DimIr {
    let path = format!(
        "{}/../../energies/psi/{name}.psi",
        env!("CARGO_MANIFEST_DIR")
    );
    let src = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    compile_dim(&src, name, dim).unwrap_or_else(|d| panic!("{}", d.render(name, &src)))
}

/// The Appendix D off-diagonal a_01 of an invariant energy, built from its
/// invariant derivatives exactly as the paper writes it.
fn appendix_d_a01(ir: &DimIr) -> (ecc_dsl::Graph, ecc_dsl::Id) {
    let mut g = ir.graph.clone();
    let d = ir.d_inv.as_ref().expect("invariant path");
    let [_, _, p3] = d.d1;
    let [p11, p22, p33, p12, p13, p23] = d.d2;
    let (s0, s1) = (g.sym(Sym::Sigma(0)), g.sym(Sym::Sigma(1)));
    let (i1, i2, i3) = (g.sym(Sym::I1), g.sym(Sym::I2), g.sym(Sym::I3));
    let (two, four) = (g.int(2), g.int(4));
    let terms = if ir.dim == 2 {
        // Ψ3 + Ψ11 + 4 I3 Ψ22 + I3 Ψ33 + 2 I1 Ψ12 + 2 I2 Ψ23 + I1 Ψ13
        vec![
            p3,
            p11,
            g.product(&[four, i3, p22]),
            g.product(&[i3, p33]),
            g.product(&[two, i1, p12]),
            g.product(&[two, i2, p23]),
            g.product(&[i1, p13]),
        ]
    } else {
        // σk Ψ3 + Ψ11 + 4σiσj Ψ22 + σk I3 Ψ33 + 2(I1 − σk) Ψ12 + 2σk(I2 − σk²) Ψ23 + σk(I1 − σk) Ψ13, k = 2
        let sk = g.sym(Sym::Sigma(2));
        let i1_sk = g.sub(i1, sk);
        let sk2 = g.powi(sk, 2);
        let i2_sk2 = g.sub(i2, sk2);
        vec![
            g.mul2(sk, p3),
            p11,
            g.product(&[four, s0, s1, p22]),
            g.product(&[sk, i3, p33]),
            g.product(&[two, i1_sk, p12]),
            g.product(&[two, sk, i2_sk2, p23]),
            g.product(&[sk, i1_sk, p13]),
        ]
    };
    let a01 = g.sum(&terms);
    (g, a01)
}

#[test]
fn arap_and_sd_scaling_modes_decouple_but_mips_does_not() {
    for (name, dim, expect) in [
        ("arap", 2, Proof::Zero),
        ("arap", 3, Proof::Zero),
        ("sd2", 2, Proof::Zero),
        ("sd3", 3, Proof::Zero),
        ("sarap2", 2, Proof::Zero),
        ("sarap3", 3, Proof::Zero),
        ("mips2", 2, Proof::NonZero),
        ("stvk", 3, Proof::NonZero),
        ("corotational", 3, Proof::NonZero),
    ] {
        let ir = library(name, dim);
        let (mut g, a01) = appendix_d_a01(&ir);
        let mut c = Converter::new(&g, dim);
        assert_eq!(
            c.is_zero(&mut g, a01),
            expect,
            "{name} {dim}D: a01 of Appendix D"
        );
        assert_eq!(
            ir.decoupled,
            expect == Proof::Zero,
            "{name} {dim}D decoupled flag"
        );
        assert_eq!(
            matches!(ir.spectral.scale, ScaleIr::Diagonal(_)),
            ir.decoupled
        );
    }
}

#[test]
fn invariant_path_a_equals_the_stretch_hessian_symbolically() {
    // A built by the chain rule (Appendix D) minus ∂²Ψ(σ)/∂σ² ≡ 0, exactly.
    for (name, dim) in [
        ("arap", 3),
        ("sd2", 2),
        ("sd3", 3),
        ("mips2", 2),
        ("stvk", 2),
        ("stvk", 3),
        ("sarap3", 3),
    ] {
        let ir = library(name, dim);
        let mut g = ir.graph.clone();
        let mut c = Converter::new(&g, dim);
        let psi_s = c.to_sigma(&mut g, ir.psi);
        for i in 0..dim as usize {
            let gi = g.diff(psi_s, Sym::Sigma(i as u8));
            let e = g.sub(ir.d_sigma[i], gi);
            assert_eq!(c.is_zero(&mut g, e), Proof::Zero, "{name} grad[{i}]");
            for j in 0..dim as usize {
                let h = g.diff(gi, Sym::Sigma(j as u8));
                let e = g.sub(ir.h_sigma[i][j], h);
                assert_eq!(c.is_zero(&mut g, e), Proof::Zero, "{name} A[{i}][{j}]");
            }
        }
    }
}

#[test]
fn cauchy_green_aliases_follow_appendix_a() {
    // II_C = ‖FᵀF‖² = Σσ⁴ (the paper's line labelled III_C,3D is II_C).
    assert_eq!(zero("IIC - (s1^4 + s2^4 + s3^4)", 3), Proof::Zero);
    assert_eq!(zero("IIC - (s1^4 + s2^4)", 2), Proof::Zero);
    assert_eq!(zero("IIIC - (s1*s2*s3)^2", 3), Proof::Zero);
    assert_eq!(zero("IC - (s1^2 + s2^2 + s3^2)", 3), Proof::Zero);
    // Characteristic polynomials (eq. 7): each σ is a root.
    assert_eq!(zero("s1^2 - I1*s1 + I3", 2), Proof::Zero);
    assert_eq!(
        zero("s2^3 - I1*s2^2 + (I1^2 - I2)/2*s2 - I3", 3),
        Proof::Zero
    );
    // 2D redundancy I2 = I1² − 2 I3.
    assert_eq!(zero("I2 - I1^2 + 2*I3", 2), Proof::Zero);
    assert_eq!(zero("I2 - I1^2 + 2*I3", 3), Proof::NonZero);
}

#[test]
fn identity_test_answers_unknown_for_non_rational_expressions() {
    assert_eq!(zero("log(I3) - log(s1*s2*s3)", 3), Proof::Zero);
    assert_eq!(zero("exp(I1) - exp(s1 + s2 + s3)", 3), Proof::Zero);
    assert_eq!(zero("sqrt(I2)^2 - I2", 3), Proof::Zero);
    assert_eq!(zero("s1^1.5*s1^0.5 - s1^2", 3), Proof::Zero);
    // log(ab) = log a + log b only for positive a, b: not claimed.
    assert_eq!(zero("log(s1*s2) - log(s1) - log(s2)", 3), Proof::Unknown);
    assert_eq!(zero("log(s1) + 1", 3), Proof::Unknown);
    assert_eq!(zero("1/(I1 - s1 - s2 - s3)", 3), Proof::Unknown);
    // Rational and non-zero: proved non-zero, also with parameters.
    assert_eq!(zero("mu*I2 - I2", 3), Proof::NonZero);
    assert_eq!(zero("(s1^2 - s2^2)/(s1 - s2) - s1 - s2", 3), Proof::Zero);
}

#[test]
fn exact_division() {
    assert_eq!(div("s1^2 - s2^2", 3, 0, 1, -1).as_deref(), Some("s1 + s2"));
    assert_eq!(
        div("s1^3 + s2^3", 3, 0, 1, 1).as_deref(),
        Some("s1^2 - s1*s2 + s2^2")
    );
    assert_eq!(
        div("(s1^4 - s2^4)/(s1*s2)", 2, 0, 1, -1).as_deref(),
        Some("(s1^3 + s1^2*s2 + s1*s2^2 + s2^3)/I3")
    );
    assert_eq!(div("mu*(s2 - s3)", 3, 1, 2, -1).as_deref(), Some("mu"));
    // Not divisible, or not rational: no quotient.
    assert_eq!(div("s1^2 + s2^2", 3, 0, 1, -1), None);
    assert_eq!(div("log(s1) - log(s2)", 3, 0, 1, -1), None);
    // Zhu's divided differences of a rational energy come out singularity-free.
    let ir = library("polyneg", 3);
    for p in ir.spectral.flip.iter().chain(&ir.spectral.twist) {
        assert!(matches!(p, PairIr::Exact(_)), "{p:?}");
    }
    assert_eq!(
        ir.graph.to_text(match ir.spectral.flip[2] {
            PairIr::Exact(x) => x,
            _ => unreachable!(),
        }),
        "2*(s1^3*s2^3 + s1^2 + s1*s2 + s2^2)/(s1^3*s2^3)"
    );
}

#[test]
fn sd3_twist_is_the_papers_eq_34() {
    // λ_twist(slot k) = 1 + σk²/I3² − (I2 − σk²) σk³/I3³, exactly (eq. 34).
    let ir = library("sd3", 3);
    let mut g = ir.graph.clone();
    let mut c = Converter::new(&g, 3);
    for k in 0..3u8 {
        let PairIr::Exact(t) = ir.spectral.twist[k as usize] else {
            panic!("SD3 twist must be exact")
        };
        let sk = g.sym(Sym::Sigma(k));
        let (i2, i3) = (g.sym(Sym::I2), g.sym(Sym::I3));
        let one = g.one();
        let sk2 = g.powi(sk, 2);
        let i3sq = g.powi(i3, 2);
        let a = g.div(sk2, i3sq);
        let i2m = g.sub(i2, sk2);
        let sk3 = g.powi(sk, 3);
        let i3c = g.powi(i3, 3);
        let num = g.mul2(i2m, sk3);
        let b = g.div(num, i3c);
        let s = g.add2(one, a);
        let paper = g.sub(s, b);
        let e = g.sub(t, paper);
        assert_eq!(c.is_zero(&mut g, e), Proof::Zero, "slot {k}");
    }
}

#[test]
fn guarded_pairs_for_non_rational_sign_symmetric_energies() {
    // Stretch path: twist and flip both need guards.
    let ir = compile_dim(
        "psi = sqrt(1 + s1^2) + sqrt(1 + s2^2) + sqrt(1 + s3^2)",
        "x",
        3,
    )
    .unwrap_or_else(|d| panic!("{d}"));
    assert!(ir.sign_symmetric);
    assert!(
        ir.spectral
            .twist
            .iter()
            .chain(&ir.spectral.flip)
            .all(|p| matches!(p, PairIr::Guarded { .. }))
    );
    // Invariant path with Ψ1 ≠ 0 that is sign-symmetric (a function of Σσ⁴).
    let ir = compile_dim("psi = log(IIC + 1)", "x", 3).unwrap_or_else(|d| panic!("{d}"));
    assert!(ir.sign_symmetric);
    assert!(
        ir.spectral
            .twist
            .iter()
            .all(|p| matches!(p, PairIr::Guarded { .. }))
    );
    assert!(
        ir.spectral
            .flip
            .iter()
            .all(|p| matches!(p, PairIr::Exact(_)))
    );
    // Not sign-symmetric: the singularity is genuine and stays visible.
    let ir = library("arap", 2);
    assert!(!ir.sign_symmetric);
    let PairIr::Exact(t) = ir.spectral.twist[0] else {
        panic!()
    };
    assert_eq!(ir.graph.to_text(t), "-4/(s1 + s2) + 2");
}
