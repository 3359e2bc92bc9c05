//! `[solver] extrapolate`: the line-search extrapolation
//! (`ecc_fem::NewtonParams::extrapolate`). Parameterisations default to on,
//! deformation scenes to off; either can be set explicitly.

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

/// (deformation, parameterisation).
fn extrapolate(solver: &str) -> (bool, bool) {
    let f = parse(solver).unwrap();
    (
        newton_params(&f.scene.solver, 1.0).extrapolate,
        param_newton_params(&f.scene.solver, 1.0).extrapolate,
    )
}

#[test]
fn defaults_differ_by_problem_kind_and_both_can_be_set() {
    assert_eq!(extrapolate(""), (false, true));
    assert_eq!(extrapolate("extrapolate = true"), (true, true));
    assert_eq!(extrapolate("extrapolate = false"), (false, false));
}

#[test]
fn a_bad_value_is_a_located_error_and_the_key_round_trips() {
    let err = parse("extrapolate = \"yes\"").unwrap_err();
    assert!(err.contains("extrapolate"), "{err}");
    assert!(err.contains("scene.toml:7:"), "{err}");
    let f = parse("extrapolate = true").unwrap();
    let back = toml::to_string(&f.scene).unwrap();
    assert!(back.contains("extrapolate = true"), "{back}");
    let f = parse("").unwrap();
    assert!(!toml::to_string(&f.scene).unwrap().contains("extrapolate"));
}
