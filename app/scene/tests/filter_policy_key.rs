//! `[solver] filter_policy`: the per-iteration filter policy
//! (`ecc_fem::FilterPolicy`). Parameterisations default to trust-region
//! Newton, deformation scenes to the fixed filter; `filter = "adaptive"`
//! keeps meaning the trust-region policy.
//!
//! `[solver] extrapolate`: the line-search extrapolation
//! (`ecc_fem::NewtonParams::extrapolate`), likewise on by default for
//! parameterisations and off for deformation scenes; either can be set.

use ecc_fem::{Filter, FilterPolicy};
use ecc_scene::SceneFile;
use ecc_scene::sim::build::{newton_params, param_newton_params};
use ecc_scene::spec::validate;

const MESH: &str =
    "name = \"bar\"\n[mesh]\nfile = \"data:bar-2523.mesh\"\n[energy]\nname = \"arap\"\n";

fn parse(solver: &str) -> Result<SceneFile, String> {
    let text = format!("{MESH}[solver]\n{solver}\n");
    let f = SceneFile::parse(&text, "scene.toml", ".").map_err(|e| e.to_string())?;
    validate::check(&f.scene).map_err(|e| f.locate(e).to_string())?;
    Ok(f)
}

/// (deformation policy, parameterisation policy, untrusted filter).
fn policies(solver: &str) -> (FilterPolicy, FilterPolicy, Filter) {
    let f = parse(solver).unwrap();
    let p = param_newton_params(&f.scene.solver, 1.0);
    (
        newton_params(&f.scene.solver, 1.0).filter_policy,
        p.filter_policy,
        p.filter,
    )
}

#[test]
fn defaults_differ_by_problem_kind() {
    use FilterPolicy::*;
    assert_eq!(policies(""), (Fixed, TrustRegionNewton, Filter::Clamp));
    assert_eq!(
        policies("filter = \"abs\""),
        (Fixed, TrustRegionNewton, Filter::Abs)
    );
    assert_eq!(
        policies("filter = \"adaptive\""),
        (TrustRegion, TrustRegion, Filter::Clamp)
    );
}

#[test]
fn each_policy_can_be_selected() {
    use FilterPolicy::*;
    for (value, want) in [
        ("fixed", Fixed),
        ("trust-region", TrustRegion),
        ("trust-region-newton", TrustRegionNewton),
    ] {
        let (d, p, _) = policies(&format!("filter_policy = \"{value}\""));
        assert_eq!((d, p), (want, want), "{value}");
    }
    let (d, p, _) = policies("filter = \"adaptive\"\nfilter_policy = \"trust-region\"");
    assert_eq!((d, p), (TrustRegion, TrustRegion));
}

#[test]
fn bad_or_conflicting_values_are_located_errors() {
    let err = parse("filter_policy = \"newton\"").unwrap_err();
    assert!(
        err.contains("filter_policy") || err.contains("line"),
        "{err}"
    );
    assert!(err.contains("scene.toml"), "{err}");
    let err = parse("filter = \"adaptive\"\nfilter_policy = \"fixed\"").unwrap_err();
    assert!(err.contains("solver.filter_policy"), "{err}");
    assert!(err.contains("adaptive"), "{err}");
}

#[test]
fn the_key_round_trips_and_is_omitted_when_unset() {
    let f = parse("filter_policy = \"trust-region-newton\"").unwrap();
    let back = toml::to_string(&f.scene).unwrap();
    assert!(
        back.contains("filter_policy = \"trust-region-newton\""),
        "{back}"
    );
    let f = SceneFile::parse(MESH, "scene.toml", ".").unwrap();
    assert!(!toml::to_string(&f.scene).unwrap().contains("filter_policy"));
}

/// `extrapolate` of (deformation, parameterisation) parameters.
fn extrapolate(solver: &str) -> (bool, bool) {
    let f = parse(solver).unwrap();
    (
        newton_params(&f.scene.solver, 1.0).extrapolate,
        param_newton_params(&f.scene.solver, 1.0).extrapolate,
    )
}

#[test]
fn extrapolation_defaults_by_problem_kind_and_both_can_be_set() {
    assert_eq!(extrapolate(""), (false, true));
    assert_eq!(extrapolate("extrapolate = true"), (true, true));
    assert_eq!(extrapolate("extrapolate = false"), (false, false));
}

#[test]
fn a_bad_extrapolate_value_is_a_located_error_and_the_key_round_trips() {
    let err = parse("extrapolate = \"yes\"").unwrap_err();
    assert!(err.contains("extrapolate"), "{err}");
    assert!(err.contains("scene.toml:7:"), "{err}");
    let f = parse("extrapolate = true").unwrap();
    let back = toml::to_string(&f.scene).unwrap();
    assert!(back.contains("extrapolate = true"), "{back}");
    let f = parse("").unwrap();
    assert!(!toml::to_string(&f.scene).unwrap().contains("extrapolate"));
}
