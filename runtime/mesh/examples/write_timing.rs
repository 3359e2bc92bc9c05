//! Output of the 1M-triangle parameterisation (issue #11, item 6): write
//! the bumpy disk as OBJ with uvs (as `ecc sim` writes its frames) and as
//! VTK with one point-data array — each timed, best of `timing::REPEATS` runs —
//! then read the OBJ back and check the round trip is bit-exact. For scale,
//! the time to write the OBJ's bytes alone (atomically) is printed too.
//!
//! `cargo run --release -p ecc-mesh --example write_timing [RINGS] [DIR]`
//!
//! Reads DIR/bumpy_disk_RINGS.obj (written by the `setup_timing` example;
//! default DIR: the temp dir), sets uvs = the positions' xy, writes
//! DIR/write_timing_RINGS.obj and .vtk and deletes them afterwards.

use std::path::PathBuf;

use ecc_mesh::{read_tri_mesh, write_obj, write_vtk_tri};

#[path = "common/best.rs"]
mod timing;
use timing::best;

fn bits2(p: &[[f64; 2]]) -> Vec<[u64; 2]> {
    p.iter().map(|q| q.map(f64::to_bits)).collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let rings: usize = args.next().map_or(Ok(409), |a| a.parse())?;
    let dir = args.next().map_or_else(std::env::temp_dir, PathBuf::from);
    let input = dir.join(format!("bumpy_disk_{rings}.obj"));
    let mut m = read_tri_mesh(&input)?;
    let uvs: Vec<[f64; 2]> = m.positions.iter().map(|p| [p[0], p[1]]).collect();
    m.uvs = Some(uvs.clone());
    let heights: Vec<f64> = m.positions.iter().map(|p| p[2]).collect();

    let obj = dir.join(format!("write_timing_{rings}.obj"));
    let vtk = dir.join(format!("write_timing_{rings}.vtk"));
    let (t_obj, r) = best(|| write_obj(&obj, &m));
    r?;
    let (t_vtk, r) = best(|| write_vtk_tri(&vtk, &m, &[("height", &heights, 1)]));
    r?;
    let (obj_mb, vtk_mb) = (
        std::fs::metadata(&obj)?.len() as f64 / 1e6,
        std::fs::metadata(&vtk)?.len() as f64 / 1e6,
    );

    // the floor: the same bytes written atomically (temp file, sync, rename)
    let bytes = std::fs::read(&obj)?;
    let (t_floor, r) = best(|| ecc_util::write_atomic(&obj, &bytes));
    r?;
    drop(bytes);

    let back = read_tri_mesh(&obj)?;
    let exact = back.triangles == m.triangles
        && back.positions.len() == m.positions.len()
        && back
            .positions
            .iter()
            .zip(&m.positions)
            .all(|(a, b)| a.map(f64::to_bits) == b.map(f64::to_bits))
        && back.uvs.as_deref().map(bits2) == Some(bits2(&uvs));
    std::fs::remove_file(&obj)?;
    std::fs::remove_file(&vtk)?;
    println!(
        "{}: {} V, {} F; write_obj (uvs) {t_obj:.3} s ({obj_mb:.1} MB), \
         write_vtk_tri (1 array) {t_vtk:.3} s ({vtk_mb:.1} MB); \
         the OBJ's bytes alone through write_atomic {t_floor:.3} s; round trip bit-exact: {exact}",
        input.display(),
        m.positions.len(),
        m.triangles.len()
    );
    if !exact {
        return Err("the OBJ did not read back bit-exactly".into());
    }
    Ok(())
}
