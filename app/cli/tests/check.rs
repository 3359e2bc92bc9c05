//! `ecc check`: passes (exit 0) on correct energies, with a per-case table.

mod common;

use common::{lib, ok};

#[test]
fn check_passes_and_reports_every_case() {
    for name in ["arap", "sd3", "ogden2"] {
        let text = ok(&["check", &lib(name), "--samples", "4"]);
        for part in [
            "rest",
            "rotation",
            "uniform scale",
            "repeated sigma",
            "sigma 1e-9 apart",
            "sigma_i+sigma_j~0",
            "sigma = 1e-6",
            "inverted",
            "sigma = 1e3",
            "random (4)",
            "worst",
            "result: PASS",
        ] {
            assert!(text.contains(part), "{name}: missing `{part}`:\n{text}");
        }
    }
    let both = ok(&["check", &lib("snh"), "--samples", "2"]);
    assert!(both.contains("2D") && both.contains("3D"), "{both}");
    let one = ok(&[
        "check",
        &lib("snh"),
        "--samples",
        "2",
        "--dim",
        "3",
        "--param",
        "lambda=1000",
    ]);
    assert!(!one.contains("2D") && one.contains("3D"), "{one}");
}
