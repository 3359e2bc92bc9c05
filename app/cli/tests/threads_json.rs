//! `ecc sim --json` reports the Cholesky factor's thread policy, fill
//! ordering and whether it was split under `linear` (`[solver] threads`,
//! `[solver] ordering`), and the policy does not change the solution's
//! convergence.

use std::process::Command;

fn sim_json(solver: &str, name: &str, threads: &str, dir: &std::path::Path) -> serde_json::Value {
    let scene = dir.join(format!("{name}.toml"));
    std::fs::write(
        &scene,
        format!(
            "[mesh]\ngenerate = \"disk\"\nrings = 5\n[energy]\nname = \"sd\"\n\
             [effects.parameterize]\ntutte = \"uniform\"\n[output]\nformats = []\n\
             pictures = false\n[solver]\ntol = 1e-8\nlinear = \"cholesky\"\n{solver}\n"
        ),
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_ecc"))
        .env("RAYON_NUM_THREADS", threads)
        .args(["sim", scene.to_str().unwrap(), "--quiet", "--json", "-o"])
        .arg(dir.join(name))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn sim_json_reports_the_thread_policy_and_ordering() {
    let dir = tempfile::tempdir().unwrap();
    let s = sim_json("", "default", "1", dir.path());
    assert_eq!(s["linear"]["threads"], "split", "{}", s["linear"]);
    assert_eq!(s["linear"]["ordering"], "block-amd", "{}", s["linear"]);
    assert_eq!(s["linear"]["split"], false, "{}", s["linear"]);
    for (policy, ordering) in [("split", "amd"), ("parallel", "block-amd")] {
        let keys = format!("threads = \"{policy}\"\nordering = \"{ordering}\"");
        let t = sim_json(&keys, policy, "2", dir.path());
        assert_eq!(t["linear"]["threads"], policy);
        assert_eq!(t["linear"]["ordering"], ordering);
        // a 5-ring disk is far below the size where a split pays
        assert_eq!(t["linear"]["split"], false);
        assert_eq!(t["frames"][1]["converged"], true, "{policy}");
    }
}

#[test]
fn a_bad_policy_is_a_located_error_with_a_failing_exit_code() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bad.toml");
    std::fs::write(
        &scene,
        "[mesh]\ngenerate = \"disk\"\nrings = 3\n[energy]\nname = \"sd\"\n\
         [effects.parameterize]\n[solver]\nthreads = \"four\"\n",
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args(["sim", scene.to_str().unwrap(), "--quiet", "-o"])
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.toml:8"), "{err}");
}

/// `ordering = "geometric"` (nested dissection from the rest positions)
/// runs in a parameterisation and in a simulation scene, is reported under
/// `linear`, and reaches the same minimum as the default ordering.
#[test]
fn the_geometric_ordering_runs_in_both_kinds_of_scene() {
    let dir = tempfile::tempdir().unwrap();
    let base = sim_json("", "geo_base", "2", dir.path());
    let geo = sim_json("ordering = \"geometric\"", "geo", "2", dir.path());
    assert_eq!(geo["linear"]["ordering"], "geometric", "{}", geo["linear"]);
    assert_eq!(geo["frames"][1]["converged"], true);
    let e = |s: &serde_json::Value| s["frames"][1]["elastic_energy"].as_f64().unwrap();
    assert!(
        (e(&base) - e(&geo)).abs() <= 1e-9 * e(&base),
        "{} vs {}",
        e(&base),
        e(&geo)
    );

    // a hanging 2D disk (the simulation path of `sim::build`)
    let scene = dir.path().join("hang.toml");
    std::fs::write(
        &scene,
        "frames = 2\n[mesh]\ngenerate = \"disk\"\nrings = 4\n[energy]\nname = \"arap\"\n\
         [effects]\ngravity = [0, -0.1]\n[[effects.handles]]\nids = [0]\n\
         [output]\nformats = []\npictures = false\n\
         [solver]\nlinear = \"cholesky\"\nordering = \"geometric\"\n",
    )
    .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args(["sim", scene.to_str().unwrap(), "--quiet", "--json", "-o"])
        .arg(dir.path().join("hang"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(s["linear"]["ordering"], "geometric", "{}", s["linear"]);
}
