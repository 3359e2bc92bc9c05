//! Rewrites never change an energy's domain (issue 12, item 2): the
//! conditions of what was written are recorded before the CAS simplifies,
//! proved ones are dropped, and the ones Ψ's own evaluation enforces (a log
//! barrier's `log(J)`) are marked so that evaluators do not test them twice.

use ecc_dsl::{DimIr, DomainCond, compile, compile_dim};

fn ir(src: &str, dim: u8) -> DimIr {
    compile_dim(src, "t", dim).unwrap_or_else(|d| panic!("{src}: {d}"))
}

/// (argument as text, relation, enforced by Ψ) of every condition.
fn domain(src: &str, dim: u8) -> Vec<(String, &'static str, bool)> {
    let ir = ir(src, dim);
    ir.domain
        .iter()
        .map(|d| {
            let rel = d.cond.relation();
            (ir.graph.to_text(d.arg), rel, d.enforced_by_psi)
        })
        .collect()
}

fn cond(arg: &str, rel: &'static str, enforced: bool) -> (String, &'static str, bool) {
    (arg.to_string(), rel, enforced)
}

#[test]
fn simplified_away_conditions_are_kept_and_tested() {
    for (src, rel) in [
        ("psi = exp(log(I3))", ">"),
        ("psi = sqrt(I3)^2", "≥"),
        ("psi = I3^(1/2)*I3^(1/2)", "≥"),
        ("psi = log(I3) - log(I3)", ">"),
        ("psi = I3/I3 + I2", "≠"),
    ] {
        for dim in [2, 3] {
            let ir = ir(src, dim);
            assert!(!ir.graph.to_text(ir.psi).contains("log"), "{src}");
            assert_eq!(domain(src, dim), vec![cond("I3", rel, false)], "{src}");
            assert_eq!(ir.active_guards().count(), 1, "{src}");
        }
    }
}

#[test]
fn conditions_that_psi_enforces_are_marked() {
    for (src, arg, rel) in [
        ("psi = -log(I3) + I2", "I3", ">"),
        ("psi = log(I3)^2", "I3", ">"),
        ("psi = I2/I3", "I3", "≠"),
        ("psi = I2/I3^2", "I3", "≠"),
        ("psi = sqrt(I3) + I2", "I3", "≥"),
        ("psi = log(s1)^2 + log(s2)^2 + log(s3)^2", "s1", ">"),
    ] {
        let d = domain(src, 3);
        assert!(d.contains(&cond(arg, rel, true)), "{src}: {d:?}");
        assert!(d.iter().all(|c| c.2), "{src}: {d:?}");
        assert_eq!(ir(src, 3).active_guards().count(), 0, "{src}");
    }
}

#[test]
fn conditions_psi_cannot_enforce_stay_active() {
    // log(0) = −∞ is mapped to 0 by exp: the condition at I3 = 0 needs a test.
    let d = domain("psi = exp(log(I3)*2) + I2", 2);
    assert_eq!(d, vec![cond("I3", ">", false)]);
    // sqrt(I3) ≥ 0 is NaN-enforced, but 1/sqrt(I3) at I3 = 0 is 1/0 = ∞ → exp(−∞) = 0.
    let d = domain("psi = exp(-1/sqrt(I3))", 2);
    assert_eq!(d, vec![cond("I3", ">", false)]);
    // A non-constant exponent: x^y = exp(y·log x) needs x > 0.
    let d = domain("param a = 2\npsi = I2^a + s1^a + s2^a", 2);
    assert!(d.contains(&cond("s1", ">", false)), "{d:?}");
}

#[test]
fn proved_conditions_are_dropped() {
    for src in [
        "psi = log(IC + 1)",
        "psi = sqrt(s1^2) + sqrt(s2^2)",
        "psi = log(exp(I1))",
        "psi = I2/(I2 + 1)",
        "psi = 1/exp(I1) + 2^I1",
        "psi = I2^(3/2)",
        "psi = (I1^2 + I3^4)^(1/4)",
        "psi = I3^(1/3) + I3^(2/3) + I3^3",
        "psi = I2/4",
    ] {
        assert_eq!(domain(src, 2), vec![], "{src}");
    }
}

#[test]
fn conditions_of_lets_count_only_when_used() {
    let used = "let a = log(I3)\npsi = exp(a)";
    assert_eq!(domain(used, 2), vec![cond("I3", ">", false)]);
    let unused = "let a = log(I3)\npsi = I2";
    assert_eq!(domain(unused, 2), vec![]);
}

#[test]
fn conditions_merge_and_split() {
    // x ≥ 0 and x ≠ 0 is x > 0; a division by a product splits.
    let d = domain("psi = sqrt(I3)^2 + I2/I3^2*I3^2", 2);
    assert_eq!(d, vec![cond("I3", ">", false)]);
    let d = domain("psi = I2/(s1*s2)*s1*s2", 2);
    assert_eq!(d, vec![cond("s1", "≠", false), cond("s2", "≠", false)]);
    assert!(DomainCond::Positive.holds(1.0) && !DomainCond::Positive.holds(0.0));
    assert!(DomainCond::NonNegative.holds(0.0) && !DomainCond::NonNegative.holds(-1e-300));
    assert!(DomainCond::NonZero.holds(-1.0) && !DomainCond::NonZero.holds(-0.0));
    assert!(
        [
            DomainCond::Positive,
            DomainCond::NonNegative,
            DomainCond::NonZero
        ]
        .iter()
        .all(|c| !c.holds(f64::NAN))
    );
}

#[test]
fn standard_library_is_not_double_guarded() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../energies/psi");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let src = std::fs::read_to_string(&path).unwrap();
        let m = compile(&src, "lib").unwrap_or_else(|d| panic!("{path:?}: {d}"));
        for ir in &m.dims {
            let active: Vec<String> = ir
                .active_guards()
                .map(|d| ir.graph.to_text(d.arg))
                .collect();
            assert!(active.is_empty(), "{path:?} {}D: {active:?}", ir.dim);
            n += 1;
        }
    }
    assert!(n >= 18, "{n} library energies");
}

#[test]
fn barrier_follows_the_written_formula() {
    let barrier = |src: &str| ir(src, 3).barrier;
    assert!(!barrier("psi = log(I3) - log(I3) + I2"));
    assert!(!barrier("psi = exp(log(I3))"));
    assert!(!barrier("psi = sqrt(I3)^2"));
    assert!(barrier("psi = -log(sqrt(I3)^2)"));
    assert!(barrier("psi = 1/(sqrt(I3)^2)"));
}
