//! Setup of the 1M-triangle parameterisation (issue #11, item 6): read an
//! OBJ, validate it, Tutte-embed it — each timed, best of `timing::REPEATS` runs.
//!
//! `cargo run --release -p ecc-mesh --example setup_timing [RINGS] [DIR]`
//!
//! The mesh is the generated bumpy disk: `disk_tri(RINGS, 1)` (6·RINGS²
//! triangles; 409 rings → 1,003,686) lifted to z = 0.05 sin(8πx) sin(8πy),
//! written once to DIR/bumpy_disk_RINGS.obj (default DIR: the temp dir).

use std::path::PathBuf;

use ecc_mesh::{
    TutteWeights, ValidationOptions, disk_tri, read_tri_mesh, tutte_embedding, validate_tri,
    write_obj,
};

#[path = "common/best.rs"]
mod timing;
use timing::best;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let rings: usize = args.next().map_or(Ok(409), |a| a.parse())?;
    let dir = args.next().map_or_else(std::env::temp_dir, PathBuf::from);
    let path = dir.join(format!("bumpy_disk_{rings}.obj"));
    if !path.exists() {
        let mut m = disk_tri(rings, 1.0);
        let k = 8.0 * std::f64::consts::PI;
        for p in &mut m.positions {
            p[2] = 0.05 * (k * p[0]).sin() * (k * p[1]).sin();
        }
        write_obj(&path, &m)?;
    }
    let (t_read, m) = best(|| read_tri_mesh(&path));
    let m = m?;
    let opts = ValidationOptions::default();
    let (t_val, v) = best(|| validate_tri(m.clone(), false, &opts));
    let mesh = v?.mesh;
    let (t_tutte, uv) = best(|| tutte_embedding(&mesh, TutteWeights::Uniform));
    let uv = uv?;
    let sum: f64 = uv.iter().map(|p| p[0] + 2.0 * p[1]).sum();
    println!(
        "{}: {} V, {} F; read {t_read:.3} s, validate {t_val:.3} s, tutte (uniform) {t_tutte:.3} s; checksum {sum:.12e}",
        path.display(),
        mesh.positions.len(),
        mesh.triangles.len()
    );
    Ok(())
}
