//! Timings of reading, validating and Tutte-embedding the public meshes,
//! and of generating the large benchmark grids.
//!
//! `cargo run --release -p ecc-mesh --example mesh_timing [DATA_DIR]`
//! (DATA_DIR defaults to `$ECC_DATA_DIR` or the repository's `data/`).

use std::path::PathBuf;
use std::time::Instant;

use ecc_mesh::{
    TutteWeights, ValidationOptions, box_tet_with_at_least, grid_tri_with_at_least, read_tet_mesh,
    read_tri_mesh, tutte_embedding_report, validate_tet, validate_tri,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(ecc_mesh::data_dir);
    let strict = ValidationOptions {
        require_manifold: true,
        require_oriented: true,
        require_single_component: true,
        ..Default::default()
    };
    for name in [
        "hand_1_i_f5000.obj",
        "camelhead.off",
        "armadillo_cut_low.obj",
    ] {
        let t = Instant::now();
        let m = read_tri_mesh(dir.join(name))?;
        let read = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let v = validate_tri(m, false, &strict)?;
        let val = t.elapsed().as_secs_f64();
        println!(
            "{name}: {} V, {} F; read {read:.3} s, validate {val:.3} s",
            v.mesh.positions.len(),
            v.mesh.triangles.len()
        );
        for w in [
            TutteWeights::Uniform,
            TutteWeights::MeanValue,
            TutteWeights::Cotangent,
        ] {
            let t = Instant::now();
            let e = tutte_embedding_report(&v.mesh, w)?;
            println!(
                "  tutte {w:?}: {:.3} s, {} flipped",
                t.elapsed().as_secs_f64(),
                e.flipped.len()
            );
        }
    }
    for name in ["hand.mesh", "bar-2523.msh"] {
        let t = Instant::now();
        let m = read_tet_mesh(dir.join(name))?;
        let read = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let v = validate_tet(m, &strict)?;
        println!(
            "{name}: {} V, {} T; read {read:.3} s, validate {:.3} s",
            v.mesh.positions.len(),
            v.mesh.tets.len(),
            t.elapsed().as_secs_f64()
        );
    }
    let t = Instant::now();
    let g = grid_tri_with_at_least(1_000_000);
    let gen_time = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let n = validate_tri(g, true, &strict)?.mesh.triangles.len();
    println!(
        "grid_tri_with_at_least(1e6): {n} F; generate {gen_time:.3} s, validate {:.3} s",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    let b = box_tet_with_at_least(300_000);
    let gen_time = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let n = validate_tet(b, &strict)?.mesh.tets.len();
    println!(
        "box_tet_with_at_least(3e5): {n} T; generate {gen_time:.3} s, validate {:.3} s",
        t.elapsed().as_secs_f64()
    );
    Ok(())
}
