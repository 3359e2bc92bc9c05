//! The scene, mesh and output rows of `docs/ERRORS.md`: each test runs
//! `ecc sim` on one kind of bad input and checks the exit status (1), the
//! key part of the message — `scene.toml:LINE:COL: \`key\`: what is wrong`
//! — and that no output file is left behind in the output folder.

mod bad_input_support;

use bad_input_support::{Scratch, only_inputs, says};

/// A valid body and energy, to which each test adds one bad thing.
const BAR: &str = "[mesh]\ngenerate = \"bar\"\nresolution = 1\n";
const ARAP: &str = "[energy]\nname = \"arap\"\n";

/// Run `ecc sim scene.toml -q -o out` and return stderr; nothing may be
/// written (the folder holds only the inputs afterwards).
fn sim_fails(s: &Scratch, scene: &str, inputs: &[&str]) -> String {
    s.write("scene.toml", scene);
    let e = s.fails(&["sim", "scene.toml", "-q", "-o", "out"]);
    let mut all = inputs.to_vec();
    all.push("scene.toml");
    only_inputs(s, &all);
    e
}

/// A scene whose mesh is the file `name` with `contents`.
fn mesh_fails(name: &str, contents: &[u8], extra: &str) -> String {
    let s = Scratch::new();
    s.write(name, contents);
    sim_fails(
        &s,
        &format!("[mesh]\nfile = \"{name}\"\n{ARAP}{extra}"),
        &[name],
    )
}

#[test]
fn scene_file_missing_or_not_toml() {
    let s = Scratch::new();
    let e = s.fails(&["sim", "missing.toml", "-q", "-o", "out"]);
    says(&e, &["cannot read `missing.toml`", "No such file"]);
    let e = sim_fails(&s, "[mesh\ngenerate = \"bar\"\n", &[]);
    says(&e, &["scene.toml:1:6:", "invalid table header"]);
}

#[test]
fn scene_unknown_key_with_suggestion() {
    let s = Scratch::new();
    let e = sim_fails(
        &s,
        &format!("{BAR}{ARAP}[effects]\ngravty = [0, -9.8, 0]\n"),
        &[],
    );
    says(
        &e,
        &["scene.toml:7:1: unknown key `gravty` in [effects]; did you mean `gravity`?"],
    );
    let e = sim_fails(&s, &format!("{BAR}{ARAP}[solvr]\ntol = 1e-6\n"), &[]);
    says(
        &e,
        &[
            "scene.toml:6:",
            "unknown key `solvr`",
            "did you mean `solver`?",
        ],
    );
}

#[test]
fn scene_wrong_type() {
    let s = Scratch::new();
    let e = sim_fails(
        &s,
        &format!("{BAR}{ARAP}[effects.inertia]\ndt = \"fast\"\n"),
        &[],
    );
    says(
        &e,
        &["scene.toml:7:6: wrong type for `dt` in [effects.inertia]: expected a number"],
    );
}

#[test]
fn scene_values_out_of_range_or_not_finite() {
    let s = Scratch::new();
    for (extra, parts) in [
        (
            "[effects.inertia]\ndt = -1\n",
            &["scene.toml:7:1: `effects.inertia.dt`: must be a positive finite number, got -1"][..],
        ),
        (
            "[effects]\ngravity = [0, nan, 0]\n",
            &["`effects.gravity`: component 1 is not finite"][..],
        ),
        (
            "[solver]\ntol = inf\n",
            &["`solver.tol`: must be a positive finite number, got inf"][..],
        ),
        (
            "[[effects.handles]]\nids = [100000]\n",
            &["`effects.handles[0].ids`: vertex 100000 does not exist (the mesh has 20 vertices)"]
                [..],
        ),
        (
            "[output]\nformats = [\"stl\"]\n",
            &["unknown value `stl`", "did you mean `vtk`?"][..],
        ),
    ] {
        let e = sim_fails(&s, &format!("{BAR}{ARAP}{extra}"), &[]);
        says(&e, parts);
    }
    let e = sim_fails(&s, &format!("frames = 0\n{BAR}{ARAP}"), &[]);
    says(&e, &["scene.toml:1:1: `frames`: must be at least 1"]);
}

#[test]
fn scene_generated_mesh_too_large() {
    // These used to overflow the generator's index arithmetic (a panic) or
    // abort on a failed multi-terabyte allocation.
    let s = Scratch::new();
    for (mesh, parts) in [
        (
            "generate = \"bar\"\nresolution = 100000000\n",
            &["scene.toml:3:1: `mesh.resolution`: asks for 24000000000000000000000000 elements"][..],
        ),
        (
            "generate = \"grid\"\ncells = [100000000, 100000000]\n",
            &["`mesh.cells`: asks for", "at most 50000000 are supported"][..],
        ),
        (
            "generate = \"box\"\ncells = [9223372036854775807, 2, 2]\n",
            &["`mesh.cells`: asks for"][..],
        ),
        (
            "generate = \"disk\"\nrings = 1000000000\n",
            &["`mesh.rings`: asks for"][..],
        ),
        (
            "generate = \"bar\"\nresolution = 9223372036854775807\n",
            &["`mesh.resolution`: asks for"][..],
        ),
    ] {
        let e = sim_fails(&s, &format!("[mesh]\n{mesh}{ARAP}"), &[]);
        says(&e, parts);
    }
}

#[test]
fn scene_unknown_energy_or_dimension() {
    let s = Scratch::new();
    let e = sim_fails(
        &s,
        &format!("{BAR}[energy]\nname = \"stable_neohooken\"\n"),
        &[],
    );
    says(
        &e,
        &[
            "scene.toml:5:1: `energy.name`: unknown energy `stable_neohooken`",
            "snh",
        ],
    );
    let e = sim_fails(&s, &format!("{BAR}[energy]\nname = \"mips\"\n"), &[]);
    says(
        &e,
        &["`energy.name`: `mips` has no 3D version (it exists in 2D)"],
    );
}

#[test]
fn scene_energy_parameters_nan_or_unknown() {
    let s = Scratch::new();
    let e = sim_fails(
        &s,
        &format!("{BAR}[energy]\nname = \"snh\"\nparams = {{ mu = nan }}\n"),
        &[],
    );
    says(&e, &["scene.toml:6:12: `energy.params.mu`: must be finite"]);
    let e = sim_fails(
        &s,
        &format!("{BAR}[energy]\nname = \"snh\"\nparams = {{ nu = 1.0 }}\n"),
        &[],
    );
    says(
        &e,
        &["`energy.params`: unknown parameter `nu` (known: mu, lambda)"],
    );
}

#[test]
fn scene_psi_energy_that_does_not_compile() {
    let s = Scratch::new();
    s.write("aniso.psi", "psi = s1^2 + 2*s2^2 + s3^2\n");
    let e = sim_fails(
        &s,
        &format!("{BAR}[energy]\npsi = \"aniso.psi\"\n"),
        &["aniso.psi"],
    );
    says(&e, &["`energy.psi`", "is not isotropic", "aniso.psi:1:7"]);
    let e = sim_fails(
        &s,
        &format!("{BAR}[energy]\npsi = \"nope.psi\"\n"),
        &["aniso.psi"],
    );
    says(&e, &["`energy.psi`", "nope.psi"]);
}

#[test]
fn mesh_file_missing_or_unsupported() {
    let s = Scratch::new();
    let e = sim_fails(&s, &format!("[mesh]\nfile = \"missing.obj\"\n{ARAP}"), &[]);
    says(
        &e,
        &[
            "scene.toml:2:1: `mesh.file`: file not found",
            "missing.obj",
            "relative to the scene file",
        ],
    );
    let e = sim_fails(
        &s,
        &format!("[mesh]\nfile = \"data:nope.obj\"\n{ARAP}"),
        &[],
    );
    says(&e, &["file not found", "nope.obj", "ECC_DATA_DIR"]);
    let e = mesh_fails("body.stl", b"solid x\n", "");
    says(&e, &["unsupported mesh file extension \"stl\""]);
}

#[test]
fn mesh_bad_indices() {
    let e = mesh_fails("idx.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "");
    says(
        &e,
        &[
            "`mesh.file`",
            "idx.obj:4: face refers to vertex 9 but the file defines only 3 vertices",
        ],
    );
    let medit = "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n\
                 0 0 1 0\nTetrahedra\n1\n0 1 2 3 0\nEnd\n";
    let e = mesh_fails("zero.mesh", medit.as_bytes(), "");
    says(
        &e,
        &["zero.mesh:11: tetrahedron 1 has vertex index 0: MEDIT indices are 1-based"],
    );
}

#[test]
fn mesh_unreferenced_vertices() {
    let e = mesh_fails(
        "stray.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 7 7 0\nf 1 2 3\n",
        "",
    );
    says(
        &e,
        &[
            "`mesh.file`",
            "1 vertex is used by no element (id 3)",
            "set `drop_unreferenced = true` in [mesh]",
        ],
    );
}

#[test]
fn mesh_not_finite_or_not_a_mesh() {
    let e = mesh_fails("nan.obj", b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "");
    says(&e, &["nan.obj:2: vertex x is not finite: `nan`"]);
    let e = mesh_fails("garbage.off", &[0x00, 0xff, 0x13, 0x37, b'\n', 0xc3], "");
    says(
        &e,
        &["`mesh.file`", "garbage.off:1: expected an `OFF` header"],
    );
    let e = mesh_fails(
        "quad.obj",
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
        "",
    );
    says(
        &e,
        &["quad.obj:5: face has 4 corners: only triangles are supported"],
    );
}

#[test]
fn mesh_degenerate_rest_elements() {
    let e = mesh_fails(
        "flat.obj",
        b"v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n",
        "",
    );
    says(
        &e,
        &["the mesh is not usable: element 0 is degenerate: rest area 0e0"],
    );
    let medit = "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n\
                 1 1 0 0\nTetrahedra\n1\n1 2 3 4 0\nEnd\n";
    let e = mesh_fails("flat.mesh", medit.as_bytes(), "");
    says(&e, &["element 0 is degenerate: rest volume 0e0"]);
    // a mesh scaled out of f64's range is not "below the tolerance"
    let s = Scratch::new();
    let e = sim_fails(
        &s,
        &format!("[mesh]\ngenerate = \"bar\"\nresolution = 1\nscale = 1e300\n{ARAP}"),
        &[],
    );
    says(
        &e,
        &[
            "`mesh`: the mesh is not usable: element 0 is degenerate",
            "the coordinates are too large",
        ],
    );
}

#[test]
fn mesh_inverted_rest_elements() {
    let e = mesh_fails(
        "inv.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n",
        "",
    );
    says(&e, &["element 1 is inverted: signed rest area -5e-1 < 0"]);
    let medit = "MeshVersionFormatted 1\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n\
                 0 0 1 0\nTetrahedra\n1\n1 3 2 4 0\nEnd\n";
    let e = mesh_fails("inv.mesh", medit.as_bytes(), "");
    says(
        &e,
        &[
            "element 0 is inverted",
            "swap two vertices of every element",
        ],
    );
}

#[test]
fn mesh_non_manifold_or_not_a_disk_where_a_parameterisation_needs_one() {
    let p = "[effects.parameterize]\n";
    let e = mesh_fails(
        "fan.obj",
        b"v 0 0 0\nv 1 0 0\nv 0 1 0.5\nv 0 -1 0.5\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
        p,
    );
    says(
        &e,
        &[
            "cannot parameterise this mesh",
            "edge [0, 1] is non-manifold",
        ],
    );
    let e = mesh_fails(
        "two.obj",
        b"v 0 0 0\nv 1 0 0\nv 1 1 0.1\nv 0 1 0\nf 1 2 3\nf 1 3 4\nv 5 5 0\nv 6 5 0\nv 5 6 0.2\nf 5 6 7\n",
        p,
    );
    says(
        &e,
        &["cannot parameterise this mesh", "2 connected components"],
    );
    let tet = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
    let e = mesh_fails("closed.obj", tet, p);
    says(
        &e,
        &[
            "needs a disk (exactly one boundary loop)",
            "0 boundary loops",
        ],
    );
    let e = mesh_fails("surface.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 1\nf 1 2 3\n", "");
    says(&e, &["a triangle surface in 3D can only be parameterised"]);
}

#[test]
fn output_folder_that_cannot_be_written() {
    let s = Scratch::new();
    s.write("scene.toml", format!("{BAR}{ARAP}"));
    s.write("a_file", "not a folder");
    let e = s.fails(&["sim", "scene.toml", "-q", "-o", "a_file/out"]);
    says(
        &e,
        &[
            "output folder `a_file/out` cannot be written",
            "Not a directory",
        ],
    );
    only_inputs(&s, &["a_file", "scene.toml"]);
}
