//! Where a scene's fibre energy comes from (`ecc_scene::terms::fibre`):
//! `[fibers] energy` through the provider's `fibre2`/`fibre3`, or the fibre
//! part of `[energy] psi` through `body2`/`body3`, which then needs
//! `[fibers]` directions and refuses a second fibre energy. The provider
//! here stands in for the CLI's (no compiler in this crate): `muscle.psi`
//! is Stable Neo-Hookean plus the fibre part `fibre-stvk` with the shared
//! parameter `mu` (μ of both parts), `fibre-only.psi` the fibre part alone.

use std::path::Path;

use ecc_runtime::energies::{FibreStvk, StableNeoHookean};
use ecc_runtime::{Energy, FibreEnergy};
use ecc_scene::sim::FinalState;
use ecc_scene::{
    BodyEnergy, EnergyError, EnergyRequest, EnergySource, RunOptions, RunReport, RuntimeEnergies,
    SceneError, SceneFile, Silent, run_scene,
};

/// [`RuntimeEnergies`] plus two pretend `.psi` files (see the module docs).
struct WithPsi;

fn stem(p: &Path) -> &str {
    p.file_name().and_then(|s| s.to_str()).unwrap_or_default()
}

/// `mu` of the request (default 1), the one shared parameter of `muscle.psi`.
fn mu(req: &EnergyRequest<'_>) -> Result<f64, EnergyError> {
    match req.params {
        [] => Ok(1.0),
        [(k, v)] if k == "mu" => Ok(*v),
        other => Err(EnergyError::Param(format!("unknown parameters {other:?}"))),
    }
}

fn body<const D: usize>(req: &EnergyRequest<'_>) -> Result<BodyEnergy<D>, EnergyError>
where
    StableNeoHookean: Energy<D>,
    FibreStvk: FibreEnergy<D>,
{
    match req.psi.map(stem) {
        Some("muscle.psi") => {
            let mu = mu(req)?;
            Ok(BodyEnergy {
                energy: Box::new(StableNeoHookean::new(mu, 10.0)),
                fibre: Some(Box::new(FibreStvk { mu })),
            })
        }
        _ => Err(EnergyError::File("only muscle.psi here".into())),
    }
}

impl EnergySource for WithPsi {
    fn energy2(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<2>>, EnergyError> {
        RuntimeEnergies.energy2(req)
    }
    fn energy3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn Energy<3>>, EnergyError> {
        RuntimeEnergies.energy3(req)
    }
    fn names(&self) -> Vec<String> {
        RuntimeEnergies.names()
    }
    fn body2(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<2>, EnergyError> {
        match req.psi {
            Some(_) => body::<2>(req),
            None => self.energy2(req).map(BodyEnergy::isotropic),
        }
    }
    fn body3(&self, req: &EnergyRequest<'_>) -> Result<BodyEnergy<3>, EnergyError> {
        match req.psi {
            Some(_) => body::<3>(req),
            None => self.energy3(req).map(BodyEnergy::isotropic),
        }
    }
    fn fibre3(&self, req: &EnergyRequest<'_>) -> Result<Box<dyn FibreEnergy<3>>, EnergyError> {
        match req.psi.map(stem) {
            Some("fibre-only.psi") => Ok(Box::new(FibreStvk { mu: mu(req)? })),
            Some(_) => Err(EnergyError::File("not a pure fibre file".into())),
            None => ecc_scene::energy::runtime_fibre::<3>(req),
        }
    }
}

fn run(text: &str) -> Result<RunReport, SceneError> {
    let f = SceneFile::parse(text, "scene.toml", ".")?;
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    run_scene(&f, &WithPsi, &opts, &mut Silent)
}

/// A cantilevered bar under gravity pulled at its tip, with `energy` and `fibres`.
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

fn final_x(r: &RunReport) -> Vec<[f64; 3]> {
    match &r.state {
        FinalState::Volume { x, .. } => x.clone(),
        _ => panic!("a tet body"),
    }
}

/// The fibre part of `[energy] psi` is the fibre term on `[fibers]`
/// directions, with `[energy] params` in both parts: the same run as the
/// isotropic energy by name plus `[fibers] energy` by name.
#[test]
fn the_fibre_part_of_energy_psi_is_the_fibre_term() {
    let direction = "[fibers]\ndirection = [1, 0, 0]";
    let by_psi = run(&bar(
        "psi = \"muscle.psi\"\nparams = { mu = 3.0 }",
        direction,
    ))
    .unwrap();
    let by_names = run(&bar(
        "name = \"snh\"\nparams = { mu = 3.0 }",
        "[fibers]\nenergy = \"fibre-stvk\"\nparams = { mu = 3.0 }\ndirection = [1, 0, 0]",
    ))
    .unwrap();
    let names: Vec<&str> = by_psi
        .summary
        .terms
        .iter()
        .map(|t| t.name.as_str())
        .collect();
    assert_eq!(names, ["elastic", "fibre", "gravity"]);
    assert_eq!(by_psi.summary.converged_frames, 2);
    assert_eq!(final_x(&by_psi), final_x(&by_names));
    assert_eq!(by_psi.summary.final_energy, by_names.summary.final_energy);
    // the summary names the fibre energy with its parameters
    let fib = by_psi
        .summary
        .fibre_energy
        .as_ref()
        .expect("a fibre energy");
    assert_eq!(Some(fib), by_names.summary.fibre_energy.as_ref());
    assert_eq!(fib.params.get("mu"), Some(&3.0));
    assert!(!fib.barrier);
    // and the fibre part is there: without [fibers] the result differs
    let plain = run(&bar("name = \"snh\"\nparams = { mu = 3.0 }", "")).unwrap();
    assert_ne!(final_x(&plain), final_x(&by_psi));
    assert_eq!(plain.summary.fibre_energy, None);
}

/// `[fibers] energy = "x.psi"` asks the provider for that file's fibre part,
/// with `[fibers] params`.
#[test]
fn fibers_energy_may_be_a_psi_file() {
    let by_psi = run(&bar(
        "name = \"snh\"",
        "[fibers]\nenergy = \"fibre-only.psi\"\nparams = { mu = 7.0 }\ndirection = [0, 0, 1]",
    ))
    .unwrap();
    let by_name = run(&bar(
        "name = \"snh\"",
        "[fibers]\nenergy = \"fibre-stvk\"\nparams = { mu = 7.0 }\ndirection = [0, 0, 1]",
    ))
    .unwrap();
    assert_eq!(final_x(&by_psi), final_x(&by_name));
}

/// A fibre part without directions, a second fibre energy or fibre
/// parameters beside it, and fibres in a parameterisation are located
/// errors naming the fix; nothing is dropped silently.
#[test]
fn a_fibre_part_is_never_ignored() {
    let muscle = "psi = \"muscle.psi\"";
    let cases = [
        (
            bar(muscle, ""),
            "energy.psi",
            "add a `[fibers]` section with one of direction",
        ),
        (
            bar(
                muscle,
                "[fibers]\nenergy = \"fibre-arap\"\ndirection = [1, 0, 0]",
            ),
            "fibers.energy",
            "conflicts with energy.psi",
        ),
        (
            bar(
                muscle,
                "[fibers]\nparams = { mu = 2.0 }\ndirection = [1, 0, 0]",
            ),
            "fibers.params",
            "set in `[energy] params`",
        ),
        (
            bar(
                "name = \"snh\"",
                "[fibers]\nenergy = \"fibre-stvkk\"\ndirection = [1, 0, 0]",
            ),
            "fibers.energy",
            "did you mean `fibre-stvk`?",
        ),
        (
            bar(
                "name = \"snh\"",
                "[fibers]\nparams = { k9 = 2.0 }\ndirection = [1, 0, 0]",
            ),
            "fibers.params",
            "k9",
        ),
    ];
    for (text, key, want) in cases {
        let err = run(&text)
            .err()
            .unwrap_or_else(|| panic!("accepted:\n{text}"));
        let shown = err.to_string();
        assert!(shown.contains(&format!("`{key}`")), "{key}: {shown}");
        assert!(shown.contains(want), "{want}: {shown}");
    }
}

#[test]
fn a_parameterisation_takes_no_fibres() {
    let disk = |energy: &str, fibres: &str| {
        format!(
            "[mesh]\ngenerate = \"disk\"\nrings = 2\n[energy]\n{energy}\n{fibres}\n\
             [effects.parameterize]\ntutte = \"uniform\"\n"
        )
    };
    let err = run(&disk("name = \"sd\"", "[fibers]\ndirection = [1, 0]"))
        .expect_err("fibres in a parameterisation");
    assert!(
        err.to_string()
            .contains("a parameterisation takes no fibre term"),
        "{err}"
    );
    let err =
        run(&disk("psi = \"muscle.psi\"", "")).expect_err("a fibre part in a parameterisation");
    let shown = err.to_string();
    assert!(
        shown.contains("`energy.psi`") && shown.contains("takes no fibre term"),
        "{shown}"
    );
}

/// The runtime's provider has no `.psi` interpreter: a `.psi` fibre energy
/// is refused with that reason (the CLI and Python providers take it).
#[test]
fn the_runtime_provider_refuses_psi_fibre_files() {
    let text = bar(
        "name = \"snh\"",
        "[fibers]\nenergy = \"x.psi\"\ndirection = [1, 0, 0]",
    );
    let f = SceneFile::parse(&text, "scene.toml", ".").unwrap();
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    let err = run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).unwrap_err();
    let shown = err.to_string();
    assert!(
        shown.contains("`fibers.energy`") && shown.contains("no .psi interpreter"),
        "{shown}"
    );
}
