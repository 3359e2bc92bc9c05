//! Removable singularities of energies that are neither rational nor
//! sign-symmetric (issue 12, item 1): exactly on σi = −σj (twist) and
//! σi = σj (flip), and 10⁻³, 10⁻⁶, 10⁻⁹, 10⁻¹² (relative) away from them,
//! for every pair slot, the generated code (`energy!`) and the interpreter
//! (what `ecc eval` runs) return the divided difference's value, checked
//! against a double-double reference computed from Ψ alone:
//!
//! * ∂Ψ/∂σ by fourth-order central differences of Ψ(σ) in double-double
//!   (the CAS graph of the macro's own source text, `Type::SOURCE`);
//! * along the line σi = b + t, σj = ∓b + t through the actual point, the
//!   quotient λ(t) itself when |t| ≥ 10⁻⁴|b|, else λ0 + λ1 t + λ2 t² from
//!   Richardson extrapolations of the even and odd parts of λ at
//!   t0 = 2⁻¹⁴|b| (the twist of these energies is not even in t).
//!
//! Before the fix the twist of every one of these energies was taken as a
//! pole: the interpreter dropped it (Ψ1 = 0 shortcut), generated code gave
//! NaN, and near the plane the first-order limit was off by O(δ).
//! Genuine poles (ARAP's twist, and one where Ψ1 happens to vanish on the
//! plane) give +∞ there, never NaN.

// `!(err <= tol)` on purpose: a NaN error must fail.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod hard_ref;

use ecc_dsl::PairKind;
use ecc_runtime::{Energy, pair_indices};
use hard_ref::dd::Dd;
use hard_ref::graph::PsiGraph;

/// Relative tolerance: theory ≈ ε^{2/3}·C (C a few units) on both sides of
/// the ε^{1/3} switch; a dropped mode or an O(δ) limit error is ≥ 1e-6.
const TOL: f64 = 1e-9;

/// Relative offsets from the singular set.
const OFFSETS: [f64; 5] = [0.0, 1e-3, 1e-6, 1e-9, 1e-12];

ecc_macros::energy! { pub struct E1; dim 2; psi = I1^2/2*exp(I1); }
ecc_macros::energy! { pub struct E2; dim 2; psi = log(1 + I1^2) + I1^3 + I2; }
ecc_macros::energy! { pub struct E3; dim 2; psi = sqrt(1 + I1^2)*I2*exp(I1^3/5); }
ecc_macros::energy! { pub struct E4; dim 2; psi = I1^2*exp(I1 - I2/4) + I2; }
ecc_macros::energy! { pub struct E5; dim 2; psi = (s1 + s2)^2*exp((s1 + s2)/3) + s1^2 + s2^2; }
ecc_macros::energy! {
    pub struct E6;
    dim 2;
    psi = (1 + (s1 + s2)^2)^(1/3)*exp((s1 + s2)^3) + s1^2 + s2^2;
}
ecc_macros::energy! {
    pub struct E7;
    dim 3;
    let p = I1*(I1^2 - I2)/2 - I3;
    psi = p^2*exp(I1/3) + I2;
}
ecc_macros::energy! {
    pub struct E8;
    dim 3;
    let p = I1*(I1^2 - I2)/2 - I3;
    psi = log(1 + p^2) + I2;
}
ecc_macros::energy! {
    pub struct E9;
    dim 3;
    let p = I1*(I1^2 - I2)/2 - I3;
    psi = (1 + p^2)^(2/3) + I2;
}
ecc_macros::energy! {
    pub struct E10;
    dim 3;
    psi = ((s1 + s2)*(s2 + s3)*(s3 + s1))^2*exp((s1 + s2 + s3)/3) + s1^2 + s2^2 + s3^2;
}
ecc_macros::energy! {
    pub struct E11;
    dim 3;
    psi = sqrt(1 + ((s1 + s2)*(s2 + s3)*(s3 + s1))^2) + s1^2 + s2^2 + s3^2;
}
ecc_macros::energy! { pub struct Arap3; dim 3; psi = I2 - 2*I1 + 3; }
ecc_macros::energy! { pub struct Kink3; dim 3; psi = (I1 - 1)^2; }

/// One energy: its name, source (the macro's) and its implementations.
struct Case<const D: usize> {
    name: &'static str,
    graph: PsiGraph,
    impls: Vec<(&'static str, Box<dyn Energy<D>>)>,
}

fn case<const D: usize>(name: &'static str, src: &str, generated: Box<dyn Energy<D>>) -> Case<D> {
    let graph = PsiGraph::new(src, D as u8, &[]).unwrap_or_else(|| panic!("{name}: {src}"));
    let interp = ecc_interp::load_source::<D>(src, &format!("{name}.psi"), &[])
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    Case {
        name,
        graph,
        impls: vec![("generated", generated), ("interpreted", Box::new(interp))],
    }
}

fn cases2() -> Vec<Case<2>> {
    vec![
        case("e1", E1::SOURCE, Box::new(E1)),
        case("e2", E2::SOURCE, Box::new(E2)),
        case("e3", E3::SOURCE, Box::new(E3)),
        case("e4", E4::SOURCE, Box::new(E4)),
        case("e5", E5::SOURCE, Box::new(E5)),
        case("e6", E6::SOURCE, Box::new(E6)),
    ]
}

fn cases3() -> Vec<Case<3>> {
    vec![
        case("e7", E7::SOURCE, Box::new(E7)),
        case("e8", E8::SOURCE, Box::new(E8)),
        case("e9", E9::SOURCE, Box::new(E9)),
        case("e10", E10::SOURCE, Box::new(E10)),
        case("e11", E11::SOURCE, Box::new(E11)),
    ]
}

/// ∂Ψ/∂σ_i in double-double (fourth-order central differences, step h).
fn dpsi(g: &PsiGraph, s: &[Dd], i: usize, h: f64) -> Dd {
    let at = |t: f64| {
        let mut x = s.to_vec();
        x[i] = x[i] + Dd::from_f64(t);
        g.psi(&x)
    };
    ((at(h) - at(-h)).scale(8.0) - (at(2.0 * h) - at(-2.0 * h))) / Dd::from_f64(12.0 * h)
}

/// (Ψi ± Ψj)/(σi ± σj) at `base` moved by t along the line that changes
/// σi ± σj (σi += t, σj ± = t).
fn lambda(g: &PsiGraph, base: &[Dd], (i, j): (usize, usize), plus: bool, t: Dd) -> Dd {
    let m = base[i].abs().to_f64();
    let h = 2f64.powi((m * 2f64.powi(-30)).log2().floor() as i32);
    let mut s = base.to_vec();
    s[i] = s[i] + t;
    s[j] = if plus { s[j] + t } else { s[j] - t };
    let (gi, gj) = (dpsi(g, &s, i, h), dpsi(g, &s, j, h));
    if plus {
        (gi + gj) / (s[i] + s[j])
    } else {
        (gi - gj) / (s[i] - s[j])
    }
}

/// The reference value of the twist (`plus`) or flip of pair (i, j) at σ.
fn reference(g: &PsiGraph, sigma: &[f64], ij: (usize, usize), plus: bool) -> f64 {
    let (i, j) = ij;
    let s: Vec<Dd> = sigma.iter().map(|x| Dd::from_f64(*x)).collect();
    let half = Dd::from_f64(0.5);
    // σi = b_i + t, σj = b_j ± t with b on the singular set.
    let (t, bi) = if plus {
        ((s[i] + s[j]) * half, (s[i] - s[j]) * half)
    } else {
        ((s[i] - s[j]) * half, (s[i] + s[j]) * half)
    };
    let mut base = s.clone();
    base[i] = bi;
    base[j] = if plus { -bi } else { bi };
    let m = bi.abs().to_f64();
    if t.abs().to_f64() >= 1e-4 * m {
        return lambda(g, &base, ij, plus, t).to_f64();
    }
    let lam = |x: f64| lambda(g, &base, ij, plus, Dd::from_f64(x));
    let even = |x: f64| (lam(x) + lam(-x)) * half;
    let odd = |x: f64| (lam(x) - lam(-x)) / Dd::from_f64(2.0 * x);
    let t0 = m * 2f64.powi(-14);
    let rich = |f: &dyn Fn(f64) -> Dd| (f(0.5 * t0).scale(4.0) - f(t0)) / Dd::from_f64(3.0);
    let l0 = rich(&even);
    let l1 = rich(&odd);
    let l2 = (even(0.5 * t0) - l0) / Dd::from_f64(0.25 * t0 * t0);
    (l0 + l1 * t + l2 * t * t).to_f64()
}

/// Check every implementation of `c` at the points of slot `k`'s plane.
fn check<const D: usize>(c: &Case<D>, base: [f64; D], k: usize, plus: bool, out: &mut Report) {
    let (i, j) = pair_indices::<D>(k);
    for delta in OFFSETS {
        let mut s = base;
        let t = 0.5 * delta * base[i].abs();
        s[i] += t;
        s[j] += if plus { t } else { -t };
        let want = reference(&c.graph, &s, (i, j), plus);
        for (kind, e) in &c.impls {
            let sp = e.spectral(&s);
            let got = if plus { sp.twist[k] } else { sp.flip[k] };
            let a = sp.scale.to_dense();
            let scale = want.abs().max(a[i][i].abs()).max(a[j][j].abs()).max(1e-300);
            let err = (got - want).abs() / scale;
            out.worst = out.worst.max(err);
            out.checked += 1;
            if !(err <= TOL) {
                let what = if plus { "twist" } else { "flip" };
                out.failures.push(format!(
                    "{} ({kind}) {D}D {what} slot {k} at σ = {s:?} (offset {delta:e}): \
                     {got:e} vs {want:e} (relative {err:.1e})",
                    c.name
                ));
            }
        }
    }
}

#[derive(Default)]
struct Report {
    failures: Vec<String>,
    checked: usize,
    worst: f64,
}

impl Report {
    fn finish(self, min: usize) {
        println!(
            "{} values checked, worst relative error {:.1e} (tolerance {TOL:e})",
            self.checked, self.worst
        );
        assert!(
            self.failures.is_empty(),
            "{} wrong values:\n{}",
            self.failures.len(),
            self.failures.join("\n")
        );
        assert!(self.checked >= min, "only {} values checked", self.checked);
    }
}

#[test]
fn twists_are_classified_removable_by_the_cas() {
    for c in cases2() {
        assert_eq!(
            c.graph.ir().spectral.twist_kind,
            [PairKind::Removable],
            "{}",
            c.name
        );
        assert!(
            !c.graph.ir().sign_symmetric,
            "{} must not be sign-symmetric",
            c.name
        );
    }
    for c in cases3() {
        assert_eq!(
            c.graph.ir().spectral.twist_kind,
            [PairKind::Removable; 3],
            "{}",
            c.name
        );
        assert!(
            !c.graph.ir().sign_symmetric,
            "{} must not be sign-symmetric",
            c.name
        );
    }
}

#[test]
fn removable_limits_2d() {
    let mut out = Report::default();
    for c in cases2() {
        for a in [0.625, 1.3, 0.2] {
            check(&c, [a, -a], 0, true, &mut out);
            check(&c, [a, a], 0, false, &mut out);
        }
    }
    out.finish(6 * 3 * 2 * 5 * 2);
}

#[test]
fn removable_limits_3d_every_pair() {
    let mut out = Report::default();
    for c in cases3() {
        for k in 0..3 {
            let (i, j) = pair_indices::<3>(k);
            for (a, other) in [(0.7, 1.2), (1.1, 0.6)] {
                let mut twist = [other; 3];
                twist[i] = a;
                twist[j] = -a;
                check(&c, twist, k, true, &mut out);
                let mut flip = [other; 3];
                flip[i] = a;
                flip[j] = a;
                check(&c, flip, k, false, &mut out);
            }
        }
    }
    out.finish(5 * 3 * 2 * 2 * 5 * 2);
}

/// The interpreted and generated spectral data at σ.
fn both<const D: usize>(
    src: &str,
    generated: &dyn Energy<D>,
    s: &[f64; D],
) -> [ecc_runtime::Spectral<D>; 2] {
    let interp =
        ecc_interp::load_source::<D>(src, "pole.psi", &[]).unwrap_or_else(|e| panic!("{e}"));
    [generated.spectral(s), interp.spectral(s)]
}

#[test]
fn genuine_poles_are_plus_infinity_never_nan() {
    for (name, src, e) in [
        ("arap", Arap3::SOURCE, &Arap3 as &dyn Energy<3>),
        ("kink", Kink3::SOURCE, &Kink3 as &dyn Energy<3>),
    ] {
        let ir = PsiGraph::new(src, 3, &[]).map(|g| g.ir().spectral.twist_kind.clone());
        assert_eq!(ir, Some(vec![PairKind::Pole; 3]), "{name}");
        // Ψ1 = 2(I1 − 1) vanishes at I1 = 1 on the plane: 0/0 there, still +∞.
        for s in [[1.0, 0.5, -0.5], [1.3, 0.8, -0.8], [1.0, -0.5, 0.5]] {
            for sp in both::<3>(src, e, &s) {
                assert_eq!(
                    sp.twist[0],
                    f64::INFINITY,
                    "{name} at {s:?}: {:?}",
                    sp.twist
                );
                assert!(sp.twist.iter().all(|x| !x.is_nan()), "{name} at {s:?}");
            }
        }
    }
}
