//! Fibre energies in the language (issue 16): `fiber a`, I4, I5, sign(I4),
//! the additive split Ψ = Ψ_iso + ψ(I4, I5), ψ's exact partials, which
//! invariants ψ reads, and the located errors.

use ecc_dsl::{Env, FibreIr, FibreUses, compile, compile_dim, eval};

fn fibre(src: &str, dim: u8) -> FibreIr {
    let ir = compile_dim(src, "t", dim).unwrap_or_else(|d| panic!("{src}: {d}"));
    ir.fibre.unwrap_or_else(|| panic!("{src}: no fibre part"))
}

fn texts(f: &FibreIr) -> [String; 6] {
    f.roots().map(|r| f.graph.to_text(r))
}

/// The rendered errors of `src`.
fn errors(src: &str) -> String {
    match compile(src, "t") {
        Ok(_) => panic!("{src}: compiled"),
        Err(d) => d.render("t.psi", src),
    }
}

#[test]
fn stvk_fibre_partials_are_exact() {
    let f = fibre("fiber a\nparam mu = 2\npsi = mu/2*(I5 - 1)^2", 3);
    let [_, d4, d5, d44, d45, d55] = texts(&f);
    assert_eq!((d4.as_str(), d44.as_str(), d45.as_str()), ("0", "0", "0"));
    assert_eq!(d5, "mu*(I5 - 1)");
    assert_eq!(d55, "mu");
    assert_eq!(f.uses, FibreUses::I5);
    assert!(f.closed_form);
}

#[test]
fn arap_reads_i4_through_its_sign_but_keeps_the_closed_form() {
    let f = fibre(
        "fibre a\nparam mu = 1\npsi = mu/2*(sqrt(I5) - sign(I4))^2",
        2,
    );
    assert_eq!(f.uses, FibreUses::Both);
    assert!(f.closed_form, "sign(I4) has derivative 0");
    let env = |i4: f64, i5: f64| Env::new(3, &[], &[1.0]).with_fibre(i4, i5);
    for (i4, i5) in [(0.7, 1.3), (-0.4, 0.8), (0.0, 2.0)] {
        let s: f64 = if i4 > 0.0 { 1.0 } else { -1.0 };
        let r = f64::sqrt(i5);
        let want = [
            0.5 * (r - s) * (r - s),
            0.0,
            0.5 * (1.0 - s / r),
            0.0,
            0.0,
            0.25 * s / (r * i5),
        ];
        for (k, root) in f.roots().iter().enumerate() {
            let got = eval(&f.graph, *root, &env(i4, i5));
            assert!((got - want[k]).abs() < 1e-14, "{k}: {got} vs {}", want[k]);
        }
    }
    // sqrt(I5) needs I5 ≥ 0, which always holds: no condition is listed.
    assert!(f.domain.is_empty(), "{:?}", f.domain);
}

#[test]
fn i4_terms_leave_the_closed_form() {
    let f = fibre("fiber a\npsi = (I4 - 1)^2 + I4*I5", 3);
    assert_eq!(f.uses, FibreUses::Both);
    assert!(!f.closed_form);
    let [_, d4, d5, d44, d45, d55] = texts(&f);
    assert_eq!(d4, "2*I4 + I5 - 2");
    assert_eq!(d5, "I4");
    assert_eq!((d44.as_str(), d45.as_str(), d55.as_str()), ("2", "1", "0"));
    assert_eq!(fibre("fiber a\npsi = I4^2", 3).uses, FibreUses::I4);
    assert_eq!(fibre("fiber a\npsi = I2", 3).uses, FibreUses::None);
}

#[test]
fn the_isotropic_part_is_what_remains() {
    let src = "fiber a\nparam mu = 1\nparam k = 3\npsi = mu*(I2 - d) + k/2*(I5 - 1)^2";
    let ir = compile_dim(src, "t", 3).unwrap();
    assert_eq!(ir.graph.to_text(ir.psi), "mu*(I2 - 3)");
    let f = ir.fibre.unwrap();
    assert_eq!(f.graph.to_text(f.psi), "k*(I5 - 1)^2/2");
    // A pure fibre energy has Ψ_iso = 0; a product over a mixed sum splits.
    let ir = compile_dim("fiber a\npsi = I5^2", "t", 2).unwrap();
    assert_eq!(ir.graph.to_text(ir.psi), "0");
    let ir = compile_dim("fiber a\nparam k = 1\npsi = k*(I2 - 2 + I5 - 1)", "t", 2).unwrap();
    // (constants of a split sum stay with the isotropic part)
    assert_eq!(ir.graph.to_text(ir.psi), "k*I2 - 3*k");
    let f = ir.fibre.unwrap();
    assert_eq!(f.graph.to_text(f.psi), "k*I5");
}

#[test]
fn fibre_domain_conditions_are_kept() {
    let f = fibre("fiber a\npsi = log(I5)^2", 3);
    let conds: Vec<(String, &str)> = f
        .domain
        .iter()
        .map(|d| (f.graph.to_text(d.arg), d.cond.relation()))
        .collect();
    assert_eq!(conds, [("I5".to_string(), ">")]);
    // exp(log(I4)) is I4 only where I4 > 0: the condition is active.
    let f = fibre("fiber a\npsi = exp(log(I4))", 3);
    assert_eq!(f.graph.to_text(f.psi), "I4");
    assert_eq!(f.active_guards().count(), 1);
}

#[test]
fn fibre_without_declaration_is_a_located_error() {
    let r = errors("psi = I2 + (I5 - 1)^2");
    assert!(
        r.contains("`I5` is a fibre invariant, but no fibre direction is declared"),
        "{r}"
    );
    assert!(r.contains("t.psi:1:13"), "{r}");
    assert!(r.contains("help: add `fiber a`"), "{r}");
}

#[test]
fn coupled_terms_are_located_errors() {
    let src = "fiber a\npsi = I2 - 3 + I3*I5";
    let r = errors(src);
    assert!(r.contains("the term `I3*I5` couples"), "{r}");
    assert!(r.contains("t.psi:2:16"), "{r}");
    assert!(
        r.contains("projects the two parts to PSD separately"),
        "{r}"
    );
    let r = errors("fiber a\nlet x = I5*J\npsi = I2 + x");
    assert!(r.contains("couples"), "{r}");
}

#[test]
fn holzapfel_c_squared_and_sign_misuse_are_explained() {
    let r = errors("fiber a\npsi = (VC - 1)^2");
    assert!(
        r.contains("`VC` = aᵀ C² a (Holzapfel's I5) is not supported"),
        "{r}"
    );
    assert!(r.contains("Cayley–Hamilton"), "{r}");
    let r = errors("fiber a\npsi = sign(I5)*I5");
    assert!(r.contains("`sign` is only defined for I4"), "{r}");
    let r = errors("fiber a\npsi = a*I5");
    assert!(r.contains("`a` is the fibre direction (a vector)"), "{r}");
    let r = errors("fiber a\nfibre b\npsi = I5");
    assert!(r.contains("`fiber` is defined more than once"), "{r}");
    let r = errors("fiber a\nlet I5 = 2\npsi = I5");
    assert!(r.contains("`I5` is a built-in variable"), "{r}");
    let r = errors("fiber a\nparam k = I4\npsi = k*I5");
    assert!(r.contains("k"), "{r}");
}

#[test]
fn ivc_is_i5_and_may_be_shadowed() {
    let f = fibre("fiber a\npsi = (IVC - 1)^2", 3);
    assert_eq!(f.graph.to_text(f.psi), "(I5 - 1)^2");
    let ir = compile_dim("param IVC = 2\npsi = IVC*(I2 - 3)", "t", 3).unwrap();
    assert!(ir.fibre.is_none());
}

#[test]
fn fibre_energies_compile_for_both_dimensions() {
    let m = compile("fiber a\nparam mu = 1\npsi = mu/2*(sqrt(I5) - 1)^2", "t").unwrap();
    assert_eq!(m.dims.len(), 2);
    assert!(m.dims.iter().all(|d| d.fibre.is_some()));
}
