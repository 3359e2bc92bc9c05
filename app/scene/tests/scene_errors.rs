//! Scene-file errors name the key, its table and its line.

use ecc_scene::{RunOptions, RuntimeEnergies, SceneError, SceneFile, Silent, run_scene};

fn parse(text: &str) -> Result<SceneFile, SceneError> {
    SceneFile::parse(text, "scene.toml", ".")
}

/// Run a parsed scene without writing anything.
fn dry(text: &str) -> SceneError {
    let f = parse(text).expect("the text parses");
    let opts = RunOptions {
        dry_run: true,
        ..Default::default()
    };
    run_scene(&f, &RuntimeEnergies, &opts, &mut Silent).expect_err("the scene is invalid")
}

const BASE: &str = "[mesh]\ngenerate = \"bar\"\nresolution = 1\n\n[energy]\nname = \"arap\"\n";

#[test]
fn unknown_key_has_line_column_table_and_suggestion() {
    let text = format!("{BASE}\n[effects]\ngravty = [0, -9.8, 0]\n");
    let e = parse(&text).unwrap_err();
    assert_eq!(
        e.to_string(),
        "scene.toml:9:1: unknown key `gravty` in [effects]; did you mean `gravity`?"
    );
    let e = parse("nmae = \"x\"\n[mesh]\ngenerate = \"bar\"\n").unwrap_err();
    assert!(
        e.to_string().starts_with(
            "scene.toml:1:1: unknown key `nmae` at the top level; did you mean `name`?"
        ),
        "{e}"
    );
}

#[test]
fn unknown_key_in_an_inline_table_and_an_array_of_tables() {
    let text = format!("{BASE}\n[effects]\ninertia = {{ dt = 0.01, integratr = \"bdf2\" }}\n");
    let e = parse(&text).unwrap_err().to_string();
    assert!(e.starts_with("scene.toml:9:"), "{e}");
    assert!(
        e.contains("unknown key `integratr` in [effects.inertia]; did you mean `integrator`?"),
        "{e}"
    );
    let text = format!(
        "{BASE}\n[[effects.handles]]\nids = [0]\n\n[[effects.handles]]\nplan = {{ point = [0, 0, 0], normal = [1, 0, 0] }}\n"
    );
    let e = parse(&text).unwrap_err().to_string();
    assert!(
        e.starts_with("scene.toml:12:1: unknown key `plan` in [effects.handles"),
        "{e}"
    );
    assert!(e.contains("did you mean `plane`?"), "{e}");
}

#[test]
fn wrong_type_names_the_key_and_what_was_expected() {
    let text = format!("{BASE}\n[effects.inertia]\ndt = \"fast\"\n");
    let e = parse(&text).unwrap_err().to_string();
    assert!(
        e.starts_with(
            "scene.toml:9:6: wrong type for `dt` in [effects.inertia]: expected a number"
        ),
        "{e}"
    );
    let text = format!("{BASE}\n[solver]\nmax_iters = -3\n");
    let e = parse(&text).unwrap_err().to_string();
    assert!(e.contains("`max_iters` in [solver]"), "{e}");
    assert!(e.starts_with("scene.toml:9:"), "{e}");
}

#[test]
fn unknown_enum_value_and_missing_key() {
    let text = format!("{BASE}\n[effects.inertia]\ndt = 0.01\nintegrator = \"bdf3\"\n");
    let e = parse(&text).unwrap_err().to_string();
    assert!(e.starts_with("scene.toml:10:"), "{e}");
    assert!(
        e.contains("unknown value `bdf3`") && e.contains("did you mean `bdf2`?"),
        "{e}"
    );
    let text = format!("{BASE}\n[effects.inertia]\nmass = \"lumped\"\n");
    let e = parse(&text).unwrap_err().to_string();
    assert!(e.contains("missing key `dt` in [effects.inertia]"), "{e}");
    let e = parse("[energy]\nname = \"arap\"\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing key `mesh`"), "{e}");
}

#[test]
fn syntax_errors_have_a_position() {
    let e = parse("[mesh\ngenerate = \"bar\"\n").unwrap_err();
    assert!(
        matches!(e, SceneError::Parse { at: Some(l), .. } if l.line == 1),
        "{e}"
    );
}

#[test]
fn invalid_values_name_the_key_and_line() {
    let e = dry(&format!("{BASE}\n[effects.inertia]\ndt = -0.5\n"));
    assert_eq!(e.key(), Some("effects.inertia.dt"));
    assert!(
        e.to_string()
            .starts_with("scene.toml:9:1: `effects.inertia.dt`: must be a positive"),
        "{e}"
    );
    let e = dry(&format!("{BASE}\n[effects]\ngravity = [0, -9.8]\n"));
    assert_eq!(e.key(), Some("effects.gravity"));
    assert!(e.to_string().contains("expected 3 components"), "{e}");
    assert_eq!(e.location().map(|l| l.line), Some(9));
    let e = dry(&format!("{BASE}\n[effects]\ndamping = {{ beta = 0.1 }}\n"));
    assert!(e.to_string().contains("damping needs dynamics"), "{e}");
    let e = dry(&format!(
        "{BASE}\n[[effects.handles]]\nbox = {{ min = [5, 5, 5], max = [6, 6, 6] }}\n"
    ));
    assert_eq!(e.key(), Some("effects.handles[0]"));
    assert!(e.to_string().contains("selects no vertex"), "{e}");
}

#[test]
fn unknown_energy_and_parameter() {
    let e = dry("[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"snhh\"\n");
    assert_eq!(e.key(), Some("energy.name"));
    assert!(e.to_string().contains("did you mean `snh`?"), "{e}");
    assert_eq!(e.location().map(|l| l.line), Some(5));
    let e = dry(
        "[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"snh\"\nparams = { muu = 1.0 }\n",
    );
    assert_eq!(e.key(), Some("energy.params"));
    assert!(e.to_string().contains("unknown parameter `muu`"), "{e}");
}

#[test]
fn missing_files_are_named() {
    let e = dry("[mesh]\nfile = \"no/such/mesh.obj\"\n[energy]\nname = \"arap\"\n");
    assert_eq!(e.key(), Some("mesh.file"));
    let s = e.to_string();
    assert!(
        s.starts_with("scene.toml:2:1: `mesh.file`: file not found:")
            && s.contains("no/such/mesh.obj"),
        "{s}"
    );
    let e = SceneFile::read("/no/such/scene.toml").unwrap_err();
    assert!(matches!(e, SceneError::Read { .. }), "{e}");
}

#[test]
fn dimension_and_shape_mismatches() {
    let e = dry("[mesh]\ngenerate = \"disk\"\nresolution = 3\n[energy]\nname = \"arap\"\n");
    assert_eq!(e.key(), Some("mesh.resolution"));
    let e = dry(
        "[mesh]\ngenerate = \"disk\"\n[energy]\nname = \"arap\"\n[effects]\ngravity = [0, -1, 0]\n",
    );
    assert!(
        e.to_string()
            .contains("expected 2 components for this 2D scene"),
        "{e}"
    );
    let e = dry(
        "[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"arap\"\n[effects.parameterize]\n",
    );
    assert!(
        e.to_string()
            .contains("parameterisation needs a triangle surface"),
        "{e}"
    );
    let e = dry(
        "[mesh]\ngenerate = \"bar\"\nresolution = 1\n[energy]\nname = \"arap\"\n[effects]\nground = { height = 0.0 }\n",
    );
    assert_eq!(e.key(), Some("effects.ground.height"));
    assert!(e.to_string().contains("strictly above"), "{e}");
}

#[test]
fn generated_meshes_too_large_are_refused_before_building() {
    let e = dry("[mesh]\ngenerate = \"bar\"\nresolution = 100000000\n[energy]\nname = \"arap\"\n");
    assert_eq!(e.key(), Some("mesh.resolution"));
    let m = e.to_string();
    assert!(
        m.contains("asks for 24000000000000000000000000 elements"),
        "{m}"
    );
    assert!(m.contains("at most 50000000"), "{m}");
    let e = dry(
        "[mesh]\ngenerate = \"box\"\ncells = [9223372036854775807, 2, 2]\n[energy]\nname = \"arap\"\n",
    );
    assert!(e.to_string().contains("`mesh.cells`: asks for"), "{e}");
    let e = dry("[mesh]\ngenerate = \"disk\"\nrings = 1000000000\n[energy]\nname = \"arap\"\n");
    assert_eq!(e.key(), Some("mesh.rings"));
}

#[test]
fn unreferenced_mesh_vertices_are_refused_unless_dropping_is_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    // vertex 3 (1-based 4) is used by no triangle
    std::fs::write(
        dir.path().join("stray.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 0\nv 1 1 0\nf 1 2 3\nf 2 5 3\n",
    )
    .unwrap();
    let scene = |extra: &str| {
        format!(
            "[mesh]\nfile = \"stray.obj\"\n{extra}\n[energy]\nname = \"arap\"\n\n\
             [[effects.handles]]\nids = [0, 4]\n"
        )
    };
    let run = |text: &str| {
        let f = SceneFile::parse(text, "scene.toml", dir.path()).unwrap();
        let opts = RunOptions {
            dry_run: true,
            ..Default::default()
        };
        run_scene(&f, &RuntimeEnergies, &opts, &mut Silent)
    };
    let e = run(&scene("")).expect_err("a stray vertex is refused");
    assert_eq!(e.key(), Some("mesh.file"));
    let msg = e.to_string();
    assert!(
        msg.contains(
            "the mesh is not usable: 1 vertex is used by no element (id 3); remove it from \
             the file or let it be dropped (set `drop_unreferenced = true` in [mesh] to drop unused vertices)"
        ),
        "{msg}"
    );
    // Dropped on request; handle ids keep naming the file's vertices (4 exists only
    // in the file's numbering: after dropping vertex 3 there are 4 vertices).
    let report = run(&scene("drop_unreferenced = true")).expect("dropping makes it usable");
    let ecc_scene::FinalState::Planar { x, triangles, .. } = report.state else {
        panic!("a planar body")
    };
    assert_eq!(x.len(), 4);
    assert_eq!(triangles, vec![[0, 1, 2], [1, 3, 2]]);
    assert_eq!(report.handles, vec![vec![0, 3]]);
}
