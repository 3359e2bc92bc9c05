//! `[solver] factor_reuse`: reuse of a Cholesky factor as the CG
//! preconditioner (`ecc_fem::linear::FactorReuse`): the library's default
//! policy unless the key says otherwise.

use ecc_fem::linear::FactorReuse;
use ecc_scene::SceneFile;
use ecc_scene::sim::build::newton_params;

const MESH: &str =
    "name = \"bar\"\n[mesh]\nfile = \"data:bar-2523.mesh\"\n[energy]\nname = \"arap\"\n";

fn reuse_of(solver: &str) -> Result<FactorReuse, String> {
    let text = format!("{MESH}[solver]\n{solver}\n");
    let f = SceneFile::parse(&text, "scene.toml", ".").map_err(|e| e.to_string())?;
    Ok(newton_params(&f.scene.solver, 1.0).factor_reuse)
}

#[test]
fn factor_reuse_is_the_default_policy_unless_set() {
    assert_eq!(reuse_of("").unwrap(), FactorReuse::ONE_STEP);
    assert_eq!(reuse_of("").unwrap(), FactorReuse::default());
    assert_eq!(reuse_of("factor_reuse = false").unwrap(), FactorReuse::OFF);
    assert_eq!(
        reuse_of("factor_reuse = true").unwrap(),
        FactorReuse::STALE_CG
    );
}

#[test]
fn a_bad_factor_reuse_value_is_a_located_error() {
    let err = reuse_of("factor_reuse = \"yes\"").unwrap_err();
    assert!(
        err.contains("factor_reuse") || err.contains("line"),
        "{err}"
    );
    assert!(err.contains("scene.toml"), "{err}");
}

#[test]
fn the_key_round_trips_and_is_omitted_when_unset() {
    let text = format!("{MESH}[solver]\nfactor_reuse = true\n");
    let f = SceneFile::parse(&text, "scene.toml", ".").unwrap();
    let back = toml::to_string(&f.scene).unwrap();
    assert!(back.contains("factor_reuse = true"), "{back}");
    let f = SceneFile::parse(MESH, "scene.toml", ".").unwrap();
    assert!(!toml::to_string(&f.scene).unwrap().contains("factor_reuse"));
}
