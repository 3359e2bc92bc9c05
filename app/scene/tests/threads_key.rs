//! `[solver] threads` and `[solver] ordering`: the Cholesky factor's thread
//! policy (`ecc_fem::linear::cholesky::ThreadPolicy`) and fill-reducing
//! ordering (`ecc_fem::linear::ordering::FillOrdering`), by their stable
//! names, reported back under `linear` in the summary.

use ecc_fem::linear::cholesky::{CholeskyParams, FactorPrecision, ThreadPolicy};
use ecc_fem::linear::ordering::FillOrdering;
use ecc_scene::sim::build::newton_params;
use ecc_scene::{RunOptions, RuntimeEnergies, SceneFile, Silent, run_scene};

const MESH: &str =
    "name = \"bar\"\n[mesh]\nfile = \"data:bar-2523.mesh\"\n[energy]\nname = \"arap\"\n";

fn params_of(solver: &str) -> Result<CholeskyParams, String> {
    let text = format!("{MESH}[solver]\n{solver}\n");
    let f = SceneFile::parse(&text, "scene.toml", ".").map_err(|e| e.to_string())?;
    Ok(newton_params(&f.scene.solver, 1.0).cholesky)
}

#[test]
fn the_defaults_are_the_library_defaults() {
    assert_eq!(params_of("").unwrap(), CholeskyParams::default());
}

#[test]
fn every_policy_and_ordering_is_selected_by_its_name() {
    for p in ThreadPolicy::ALL {
        let got = params_of(&format!("threads = \"{}\"", p.name())).unwrap();
        assert_eq!(got.threads, p);
        assert_eq!(got.ordering, FillOrdering::default());
    }
    for o in FillOrdering::ALL.into_iter().chain([FillOrdering::Auto]) {
        let got = params_of(&format!("ordering = \"{}\"", o.name())).unwrap();
        assert_eq!(got.ordering, o);
        assert_eq!(got.threads, ThreadPolicy::default());
    }
    let both = params_of("threads = \"split\"\nordering = \"amd\"").unwrap();
    assert_eq!(
        both,
        CholeskyParams {
            ordering: FillOrdering::Amd,
            threads: ThreadPolicy::Split,
            ..Default::default()
        }
    );
}

#[test]
fn the_precision_is_auto_unless_asked() {
    assert_eq!(params_of("").unwrap().precision, FactorPrecision::Auto);
    for p in [
        FactorPrecision::Auto,
        FactorPrecision::Mixed,
        FactorPrecision::Double,
    ] {
        let name = serde_json::to_value(p).unwrap();
        let got = params_of(&format!("precision = {name}")).unwrap();
        assert_eq!(got.precision, p);
    }
}

#[test]
fn a_bad_value_is_a_located_error() {
    for bad in [
        "threads = \"2\"",
        "threads = 2",
        "ordering = \"nd\"",
        "precision = \"single\"",
    ] {
        let err = params_of(bad).unwrap_err();
        // the key's line: 5 lines of MESH, then `[solver]`
        assert!(err.contains("scene.toml:7:"), "{bad}: {err}");
    }
}

#[test]
fn the_keys_round_trip_and_are_omitted_when_unset() {
    let text = format!("{MESH}[solver]\nthreads = \"split\"\nordering = \"block-amd\"\n");
    let f = SceneFile::parse(&text, "scene.toml", ".").unwrap();
    let back = toml::to_string(&f.scene).unwrap();
    assert!(back.contains("threads = \"split\""), "{back}");
    assert!(back.contains("ordering = \"block-amd\""), "{back}");
    let back = toml::to_string(&SceneFile::parse(MESH, "scene.toml", ".").unwrap().scene).unwrap();
    assert!(
        !back.contains("threads") && !back.contains("ordering"),
        "{back}"
    );
}

/// The summary of `[effects.parameterize]` on a generated disk of `rings`
/// rings with `solver` keys, in a pool of `threads`.
fn disk_summary(rings: usize, solver: &str, threads: usize) -> serde_json::Value {
    let text = format!(
        "[mesh]\ngenerate = \"disk\"\nrings = {rings}\n[energy]\nname = \"sd\"\n\
         [effects.parameterize]\ntutte = \"uniform\"\n[solver]\n{solver}\n"
    );
    let f = SceneFile::parse(&text, "scene.toml", ".").unwrap();
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let s = pool
        .install(|| run_scene(&f, &RuntimeEnergies, &opts, &mut Silent))
        .unwrap()
        .summary;
    assert!(s.frames[1].converged, "{solver}");
    serde_json::to_value(&s).unwrap()
}

/// A small (6-ring) disk solved to 1e-8 with `solver` keys, in a pool of
/// `threads`: its `linear` summary.
fn linear_json(solver: &str, threads: usize) -> serde_json::Value {
    disk_summary(6, &format!("tol = 1e-8\n{solver}"), threads)["linear"].clone()
}

#[test]
fn the_summary_reports_the_policy_ordering_and_split() {
    let w = linear_json(
        "linear = \"cholesky\"\nthreads = \"split\"\nordering = \"amd\"",
        2,
    );
    assert_eq!(w["threads"], "split");
    assert_eq!(w["ordering"], "amd");
    // a 6-ring disk is far below the size where a split pays
    assert_eq!(w["split"], false);
    let w = linear_json("linear = \"cholesky\"", 1);
    assert_eq!(w["threads"], ThreadPolicy::default().name());
    // the default `auto` reports the ordering it used: block AMD on a disk
    // far below METIS's size
    assert_eq!(FillOrdering::default(), FillOrdering::Auto);
    assert_eq!(w["ordering"], FillOrdering::BlockAmd.name());
    // PCG has no factor: no keys
    let w = linear_json("linear = \"pcg\"", 1);
    assert!(
        w.get("threads").is_none() && w.get("split").is_none(),
        "{w}"
    );
}

/// A 60-ring disk (≈ 22k triangles, large enough to split on two threads)
/// with `linear = "cholesky"` and `solver` keys: its summary.
fn split_disk_json(solver: &str) -> serde_json::Value {
    disk_summary(60, &format!("linear = \"cholesky\"\n{solver}"), 2)
}

/// A mixed split factor refines every Newton step's solve by CG (so
/// `cg_iterations` counts at least one per Newton iteration; this disk's
/// trust-region steps on raw Hessians also leave the factor mixed);
/// `precision = "double"` solves directly, and so does the default `auto`
/// on this disk, below `MIXED_MIN_FLOPS`. All are reported.
#[test]
fn the_summary_reports_the_precision_and_the_refinement() {
    let run = split_disk_json("precision = \"mixed\"");
    let mixed = &run["linear"];
    assert_eq!(mixed["split"], true, "{mixed}");
    assert_eq!(mixed["precision"], "mixed");
    let (cg, newton) = (&mixed["cg_iterations"], &run["newton_iterations"]);
    assert!(
        cg.as_u64() >= newton.as_u64() && newton.as_u64() > Some(0),
        "{run}"
    );
    for asked in ["precision = \"double\"", ""] {
        let double = &split_disk_json(asked)["linear"];
        assert_eq!(double["split"], true, "{asked}");
        assert_eq!(double["precision"], "double", "{asked}");
        assert_eq!(double["cg_iterations"], 0, "{asked}");
    }
    // a factor that is not split is double whatever was asked
    let small = linear_json("linear = \"cholesky\"", 2);
    assert_eq!(small["split"], false);
    assert_eq!(small["precision"], "double");
}
