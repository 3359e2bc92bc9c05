//! Rewrites never change an energy's domain (issue 12, item 2), end to end:
//! `ecc eval --json` says `domain: outside` (Ψ = +∞) for the simplified
//! formulas at det F < 0 and is unchanged for the control `psi = I3`; the
//! report lists the written conditions and a barrier flag that is the limit
//! of Ψ as det F → 0⁺.

mod common;

use common::ok;
use serde_json::Value;

/// The four formulas of the issue.
const REDUCED: [&str; 4] = [
    "psi = exp(log(I3))",
    "psi = sqrt(I3)^2",
    "psi = I3^(1/2)*I3^(1/2)",
    "psi = log(I3) - log(I3)",
];

fn write(dir: &tempfile::TempDir, name: &str, src: &str) -> String {
    let p = dir.path().join(name);
    std::fs::write(&p, src).unwrap();
    p.to_string_lossy().into_owned()
}

fn eval(path: &str, f: &str) -> Value {
    let text = ok(&["eval", path, "--F", f, "--json"]);
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}:\n{text}"))
}

#[test]
fn reduced_formulas_are_outside_at_negative_det() {
    let dir = tempfile::tempdir().unwrap();
    for (k, src) in REDUCED.iter().enumerate() {
        let path = write(&dir, &format!("r{k}.psi"), src);
        for f in ["-0.6 0; 0 1", "1 0 0; 0 -0.6 0; 0 0 1"] {
            let v = eval(&path, f);
            assert_eq!(v["domain"], "outside", "{src} at {f}");
            assert_eq!(v["psi"], Value::Null, "{src} at {f}");
            assert_eq!(v["finite"], false, "{src} at {f}");
        }
        let v = eval(&path, "0.6 0; 0 1");
        assert_eq!(v["domain"], "inside", "{src}");
        let want = if k == 3 { 0.0 } else { 0.6 };
        assert!((v["psi"].as_f64().unwrap() - want).abs() < 1e-15, "{src}");
    }
    let control = write(&dir, "control.psi", "psi = I3");
    let v = eval(&control, "-0.6 0; 0 1");
    assert_eq!(v["domain"], "inside");
    assert!((v["psi"].as_f64().unwrap() + 0.6).abs() < 1e-15);
}

fn report(dir: &tempfile::TempDir, src: &str) -> String {
    let path = write(dir, "rep.psi", src);
    ok(&[&path, "--emit", "report"])
}

#[test]
fn report_lists_the_domain_and_the_barrier() {
    let dir = tempfile::tempdir().unwrap();
    let r = report(&dir, "psi = exp(log(I3))");
    assert!(
        r.contains("| domain (Ψ = +∞ elsewhere) | `I3 > 0` |"),
        "{r}"
    );
    assert!(r.contains("| barrier (keep det F > 0) | no |"), "{r}");
    let r = report(&dir, "psi = sqrt(I3)^2 + I2/I3");
    assert!(r.contains("`I3 > 0`"), "{r}");
    let r = report(&dir, "psi = I2 - 2*I1 + d");
    assert!(r.contains("| domain (Ψ = +∞ elsewhere) | all F |"), "{r}");
    let r = report(&dir, "psi = -log(I3) + I2");
    assert!(
        r.contains("| `I3 > 0` (Ψ itself is +∞ or NaN outside) |"),
        "{r}"
    );
    for (src, yes) in [
        ("psi = I3^(1/3)", false),
        ("dim 2\npsi = sqrt(s1^2) + sqrt(s2^2)", false),
        ("psi = log(I3)", false),
        ("psi = -log(I3)", true),
        ("psi = 1/I3", true),
        ("dim 2\npsi = (I2 + I2/I3^2)/2", true),
    ] {
        let r = report(&dir, src);
        let want = format!(
            "| barrier (keep det F > 0) | {} |",
            if yes { "yes" } else { "no" }
        );
        assert!(r.contains(&want), "{src}:\n{r}");
    }
}
