//! Removable singularities through the command line (issue 12, item 1):
//! `ecc eval` returns the twist's limit on σ1 = −σ2 for an energy that is
//! neither rational nor sign-symmetric, a genuine pole gives +∞ (never NaN),
//! and `ecc check` visits σi = ±σj exactly and 1e-3…1e-12 away for every
//! energy and passes on removable ones.

mod common;

use common::{ecc, ok};

/// Write `text` to a fresh `.psi` file and return its path.
fn psi_file(name: &str, text: &str) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
    let path = dir.path().join(format!("{name}.psi"));
    std::fs::write(&path, text).unwrap_or_else(|e| panic!("{e}"));
    let p = path.to_string_lossy().into_owned();
    (dir, p)
}

fn eigenvalues(json: &str) -> Vec<f64> {
    let v: serde_json::Value = serde_json::from_str(json).unwrap_or_else(|e| panic!("{e}: {json}"));
    v["eigenvalues"]
        .as_array()
        .unwrap_or_else(|| panic!("no eigenvalues: {json}"))
        .iter()
        .map(|x| x.as_f64().unwrap_or(f64::NAN))
        .collect()
}

#[test]
fn eval_takes_the_twist_limit_of_a_removable_singularity() {
    let (_d, f) = psi_file("iexp", "dim 2\npsi = I1^2/2*exp(I1)\n");
    // σ = (0.625, −0.625): the twist (Ψ1 + Ψ2)/(σ1 + σ2) is 0/0, its limit 2.
    let text = ok(&["eval", &f, "--F", "0.375 0.5; 0.5 -0.375", "--json"]);
    let ev = eigenvalues(&text);
    let want = [0.0, 0.0, 2.0, 2.0];
    for (g, w) in ev.iter().zip(want) {
        assert!((g - w).abs() < 1e-12, "{ev:?} vs {want:?}\n{text}");
    }
    // 1e-9 away from the plane: (σ1 + σ2 + 2)·e^(σ1+σ2) ≈ 2.
    let text = ok(&["eval", &f, "--F", "0.625 0; 0 -0.6249999994", "--json"]);
    let ev = eigenvalues(&text);
    assert!(ev.iter().any(|x| (x - 2.0).abs() < 1e-8), "{ev:?}");
}

#[test]
fn eval_gives_plus_infinity_at_a_genuine_pole() {
    // Ψ1 = 2(I1 − 1) does not vanish on σ1 = −σ2: a pole, +∞ exactly there.
    let (_d, f) = psi_file("kink", "dim 2\npsi = (I1 - 1)^2 + I2\n");
    let text =
        String::from_utf8_lossy(&ecc(&["eval", &f, "--F", "0.5 0; 0 -0.5"]).stdout).into_owned();
    let line = text
        .lines()
        .skip_while(|l| !l.starts_with("eigenvalues"))
        .nth(1)
        .unwrap_or_else(|| panic!("no eigenvalues:\n{text}"))
        .to_string();
    let ev: Vec<&str> = line.split_whitespace().collect();
    assert_eq!(ev.len(), 4, "{line}");
    assert_eq!(ev[3], "inf", "the pole is +inf: {line}");
    assert!(!line.contains("NaN"), "{line}");
    let json = ok(&["eval", &f, "--F", "0.5 0; 0 -0.5", "--json"]);
    assert!(json.contains("\"finite\": false"), "{json}");
}

#[test]
fn check_visits_the_singular_sets_and_passes_on_removable_twists() {
    let (_d, f) = psi_file("iexp", "dim 2\npsi = I1^2/2*exp(I1)\n");
    let text = ok(&["check", &f, "--samples", "2"]);
    for row in [
        "si = -sj ",
        "si = -sj + 1e-12",
        "si = sj ",
        "si = sj + 1e-12",
        "result: PASS",
    ] {
        assert!(text.contains(row), "missing `{row}`:\n{text}");
    }
    let (_d3, f3) = psi_file(
        "p3",
        "dim 3\nlet p = I1*(I1^2 - I2)/2 - I3\npsi = log(1 + p^2) + I2\n",
    );
    let text = ok(&["check", &f3, "--samples", "2"]);
    assert!(
        text.contains("si = -sj + 1e-6 (2)") && text.contains("result: PASS"),
        "{text}"
    );
}
