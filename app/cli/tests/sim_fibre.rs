//! `ecc sim` with fibre energies (#16): `[fibers] energy` by library name
//! or as the fibre part of a `.psi`, and `[energy] psi` with `fiber a`
//! (its isotropic part on the body, its fibre part on the `[fibers]`
//! directions); the refusals are located errors with exit code 1.

use std::fs;
use std::path::Path;
use std::process::{Command, Output};

use serde_json::Value;

fn ecc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ecc"))
        .args(args)
        .output()
        .expect("the ecc binary runs")
}

fn lib(stem: &str) -> String {
    format!(
        "{}/../../energies/psi/{stem}.psi",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// Stable Neo-Hookean exactly as `energies/psi/snh.psi`, plus a fibre part
/// k/2 (I5 − 1)² (= `fibre_stvk.psi` with μ = k).
const MUSCLE: &str = "fiber a
param mu = 1.0
param lambda = 10.0
param k = 1.0
let alpha = 1 + mu/lambda - mu/((d+1)*lambda)
psi = mu/2*(IC - d) + lambda/2*(J - alpha)^2 - mu/2*log(IC + 1) + k/2*(I5 - 1)^2
";

/// A bar clamped at x = −2 under gravity, its other end pulled and lifted.
fn bar(energy: &str, fibres: &str) -> String {
    format!(
        r#"
frames = 2
[mesh]
generate = "bar"
resolution = 2
[energy]
{energy}
{fibres}
[effects]
gravity = [0, -0.05, 0]
[[effects.handles]]
plane = {{ point = [-1.99, 0, 0], normal = [-1, 0, 0] }}
[[effects.handles]]
plane = {{ point = [1.99, 0, 0], normal = [1, 0, 0] }}
keys = [ {{ frame = 2, translate = [0.3, 0, 0.2] }} ]
"#
    )
}

/// A planar strip clamped on its left edge, its right edge pulled and lifted.
fn strip(energy: &str, fibres: &str) -> String {
    format!(
        r#"
frames = 2
[mesh]
generate = "grid"
cells = [8, 2]
size = [4, 1]
[energy]
{energy}
{fibres}
[[effects.handles]]
box = {{ min = [-0.01, -0.01], max = [0.01, 1.01] }}
[[effects.handles]]
box = {{ min = [3.99, -0.01], max = [4.01, 1.01] }}
keys = [ {{ frame = 2, translate = [0.4, 0.3] }} ]
"#
    )
}

/// Write `text` as `dir/name.toml`, run it, return the output.
fn sim(dir: &Path, name: &str, text: &str) -> Output {
    let scene = dir.join(format!("{name}.toml"));
    fs::write(&scene, text).unwrap();
    let out = dir.join(format!("out-{name}"));
    ecc(&[
        "sim",
        scene.to_str().unwrap(),
        "-q",
        "--json",
        "--no-pictures",
        "-o",
        out.to_str().unwrap(),
    ])
}

/// The JSON summary of a successful run.
fn summary(dir: &Path, name: &str, text: &str) -> Value {
    let o = sim(dir, name, text);
    assert!(
        o.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

/// Per frame: Newton iterations and the elastic (body + fibre) and total energies.
fn frames(s: &Value) -> Vec<(u64, f64, f64)> {
    s["frames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| {
            (
                f["iterations"].as_u64().unwrap(),
                f["elastic_energy"].as_f64().unwrap(),
                f["total_energy"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// Equal iteration counts, energies equal to rounding; the fibre term ran.
fn assert_same_run(a: &Value, b: &Value, what: &str) {
    let (fa, fb) = (frames(a), frames(b));
    assert_eq!(fa.len(), 3, "{what}");
    for (x, y) in fa.iter().zip(&fb) {
        assert_eq!(x.0, y.0, "{what}: iterations {fa:?} vs {fb:?}");
        for (u, v) in [(x.1, y.1), (x.2, y.2)] {
            assert!(
                (u - v).abs() <= 1e-9 * u.abs().max(1.0),
                "{what}: {fa:?} vs {fb:?}"
            );
        }
    }
    assert_eq!(a["converged_frames"], 2, "{what}");
    let terms: Vec<&str> = a["terms"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["name"].as_str().unwrap())
        .collect();
    assert_eq!(terms[..2], ["elastic", "fibre"], "{what}");
}

#[test]
fn a_psi_fibre_energy_equals_the_library_one() {
    let dir = tempfile::tempdir().unwrap();
    let fibres = |energy: &str| {
        format!("[fibers]\nenergy = \"{energy}\"\nparams = {{ mu = 50.0 }}\ndirection = [1, 0, 1]")
    };
    let snh = "name = \"snh\"\nparams = { mu = 1.0, lambda = 10.0 }";
    let by_name = summary(dir.path(), "name", &bar(snh, &fibres("fibre-stvk")));
    let by_psi = summary(dir.path(), "psi", &bar(snh, &fibres(&lib("fibre_stvk"))));
    assert_same_run(&by_name, &by_psi, "fibre_stvk.psi vs fibre-stvk");
    // the fibres matter: without them the run differs
    let plain = summary(dir.path(), "plain", &bar(snh, ""));
    assert_ne!(frames(&plain), frames(&by_name));
    assert!(plain.get("fibre_energy").is_none(), "no fibre term, no key");
    assert_eq!(by_psi["fibre_energy"]["params"]["mu"], 50.0);
    // 2D: the same on a planar strip, fibres at 30°
    let fibres2 = |energy: &str| {
        format!(
            "[fibers]\nenergy = \"{energy}\"\nparams = {{ mu = 20.0 }}\ndirection = [0.866, 0.5]"
        )
    };
    let arap = "name = \"arap\"";
    let by_name = summary(dir.path(), "name2", &strip(arap, &fibres2("fibre_stvk")));
    let by_psi = summary(
        dir.path(),
        "psi2",
        &strip(arap, &fibres2(&lib("fibre_stvk"))),
    );
    assert_same_run(&by_name, &by_psi, "2D fibre_stvk.psi vs fibre_stvk");
}

/// `[energy] psi` with `fiber a`: Ψ_iso on the body, ψ on the `[fibers]`
/// directions, `[energy] params` in both parts (mu in Ψ_iso, k in ψ).
#[test]
fn energy_psi_with_a_fibre_part_is_both_parts() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("muscle.psi"), MUSCLE).unwrap();
    let whole = summary(
        dir.path(),
        "whole",
        &bar(
            "psi = \"muscle.psi\"\nparams = { mu = 1.5, k = 20.0 }",
            "[fibers]\ndirection = [1, 0, 1]",
        ),
    );
    let split = summary(
        dir.path(),
        "split",
        &bar(
            &format!("psi = \"{}\"\nparams = {{ mu = 1.5 }}", lib("snh")),
            "[fibers]\nenergy = \"fibre-stvk\"\nparams = { mu = 20.0 }\ndirection = [1, 0, 1]",
        ),
    );
    assert_same_run(&whole, &split, "muscle.psi vs snh.psi + fibre-stvk");
    // summary.json names both parts: the body's Ψ_iso and the fibre part,
    // each with the file's (shared) parameters
    assert_eq!(whole["energy"]["name"], "muscle");
    assert_eq!(whole["fibre_energy"]["name"], "muscle");
    for part in ["energy", "fibre_energy"] {
        let p = &whole[part]["params"];
        assert_eq!((&p["mu"], &p["k"]), (&1.5.into(), &20.0.into()), "{part}");
    }
    assert_eq!(split["fibre_energy"]["params"]["mu"], 20.0);
}

/// Every refusal: exit code 1, `scene.toml:LINE:COL: `key`: message`.
#[test]
fn fibre_energy_errors_are_located() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("muscle.psi"), MUSCLE).unwrap();
    let snh = "name = \"snh\"";
    let muscle = "psi = \"muscle.psi\"";
    let fibres = |energy: &str| format!("[fibers]\nenergy = \"{energy}\"\ndirection = [1, 0, 0]");
    let cases = [
        (
            bar(muscle, ""),
            "`energy.psi`",
            "add a `[fibers]` section with one of direction",
        ),
        (
            bar(muscle, &fibres("fibre-arap")),
            "`fibers.energy`",
            "conflicts with energy.psi",
        ),
        (
            bar(
                muscle,
                "[fibers]\nparams = { k = 3.0 }\ndirection = [1, 0, 0]",
            ),
            "`fibers.params`",
            "conflicts with energy.psi",
        ),
        (
            bar(snh, &fibres("muscle.psi")),
            "`fibers.energy`",
            "has an isotropic part besides its fibre part (`fiber a`)",
        ),
        (
            bar(snh, &fibres(&lib("snh"))),
            "`fibers.energy`",
            "has no fibre part in 3D",
        ),
        (
            bar(snh, &fibres("snh")),
            "`fibers.energy`",
            "`snh` is an isotropic energy, not a fibre energy",
        ),
        (
            bar(snh, &fibres("fibre_stvkk")),
            "`fibers.energy`",
            "unknown fibre energy `fibre_stvkk` (known: fibre_arap, fibre_stvk, fibre_fung",
        ),
        (
            bar(
                snh,
                "[fibers]\nparams = { k9 = 1.0 }\ndirection = [1, 0, 0]",
            ),
            "`fibers.params`",
            "k9",
        ),
    ];
    for (k, (text, key, want)) in cases.iter().enumerate() {
        let o = sim(dir.path(), &format!("bad{k}"), text);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{key}: {err}");
        assert!(
            err.contains(&format!("bad{k}.toml:")) && err.contains(key) && err.contains(want),
            "{key} / {want}: {err}"
        );
        // nothing was written for a scene refused before running
        let out = dir.path().join(format!("out-bad{k}"));
        let written = fs::read_dir(&out).map(|d| d.count()).unwrap_or(0);
        assert_eq!(written, 0, "{key}: files left in {}", out.display());
    }
}
