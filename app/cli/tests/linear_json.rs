//! `ecc sim --json` (the summary) reports the linear-solver work of the run
//! (`linear`: symbolic analyses, numeric factorisations, CG iterations,
//! reused-factor steps) and of each solve, consistently with the Newton
//! iterations; `--stats` prints the same counts.

use std::process::Command;

fn sim_json(linear: &str, dir: &std::path::Path) -> (serde_json::Value, String) {
    let scene = dir.join(format!("{linear}.toml"));
    std::fs::write(
        &scene,
        format!(
            "[mesh]\ngenerate = \"disk\"\nrings = 5\n[energy]\nname = \"sd\"\n\
             [effects.parameterize]\ntutte = \"uniform\"\n[output]\nformats = []\n\
             pictures = false\n[solver]\ntol = 1e-8\nlinear = \"{linear}\"\n"
        ),
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args([
            "sim",
            scene.to_str().unwrap(),
            "--quiet",
            "--stats",
            "--json",
            "-o",
        ])
        .arg(dir.join(linear))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{stderr}");
    (serde_json::from_slice(&o.stdout).unwrap(), stderr)
}

#[test]
fn sim_json_has_consistent_linear_counts() {
    let dir = tempfile::tempdir().unwrap();
    for linear in ["cholesky", "pcg", "auto"] {
        let (s, stats) = sim_json(linear, dir.path());
        let n = s["newton_iterations"].as_u64().unwrap();
        let key = |k: &str| {
            s["linear"][k]
                .as_u64()
                .unwrap_or_else(|| panic!("linear.{k}"))
        };
        let (sym, fac, cg) = (
            key("symbolic_analyses"),
            key("numeric_factorizations"),
            key("cg_iterations"),
        );
        assert_eq!(key("reused_factor_steps"), 0);
        assert!(n > 0);
        let solve = &s["solves"][0]["linear"];
        assert_eq!(solve["numeric_factorizations"].as_u64(), Some(fac));
        assert_eq!(solve["cg_iterations"].as_u64(), Some(cg));
        // each step factorises (≤ 12 shift attempts) or runs CG
        assert!(fac <= 12 * n && fac + cg >= n, "{linear}: {}", s["linear"]);
        match linear {
            "cholesky" => assert!(sym == 1 && fac >= n && cg == 0, "{}", s["linear"]),
            "pcg" => assert!(sym == 0 && fac == 0 && cg >= n, "{}", s["linear"]),
            _ => assert_eq!(sym, 1),
        }
        let line = format!(
            "linear: {sym} symbolic analyses, {fac} numeric factorisations, {cg} CG iterations"
        );
        assert!(stats.contains(&line), "{stats}");
    }
}
