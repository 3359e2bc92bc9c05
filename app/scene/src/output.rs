//! The output folder: checked before any work, every file written
//! atomically (temporary file in the same folder, flushed, synced, then
//! renamed over the destination), so a reader never sees a partial frame,
//! picture or summary.

use std::fs;
use std::path::{Path, PathBuf};

use ecc_mesh::{PointData, TetMesh, TriMesh, write_obj, write_vtk_tet, write_vtk_tri};

use crate::error::{OutputFailure, SceneError, WriteFailure};

/// Write `bytes` to `path` atomically ([`ecc_util::write_atomic`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), SceneError> {
    ecc_util::write_atomic(path, bytes).map_err(|e| SceneError::Write {
        path: path.display().to_string(),
        source: e.into(),
    })
}

/// An output folder that was proven writable.
#[derive(Debug)]
pub struct OutputDir {
    path: PathBuf,
    written: Vec<String>,
}

impl OutputDir {
    /// Create the folder (and parents) and prove it is writable by writing
    /// and removing a probe file. Fails before any simulation work.
    pub fn prepare(path: &Path) -> Result<Self, SceneError> {
        let fail = |source: OutputFailure| SceneError::Output {
            path: path.display().to_string(),
            source,
        };
        if path.exists() && !path.is_dir() {
            return Err(fail(OutputFailure::NotAFolder));
        }
        fs::create_dir_all(path).map_err(|e| fail(OutputFailure::Create(e)))?;
        let probe = path.join(".ecc-write-probe");
        ecc_util::write_atomic(&probe, b"ecc").map_err(|source| {
            fail(OutputFailure::Probe {
                path: probe.display().to_string(),
                source,
            })
        })?;
        fs::remove_file(&probe).map_err(|e| fail(OutputFailure::RemoveProbe(e)))?;
        Ok(OutputDir {
            path: path.to_path_buf(),
            written: Vec::new(),
        })
    }

    /// The folder.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Files written so far (names relative to the folder).
    pub fn written(&self) -> &[String] {
        &self.written
    }

    /// Write a file atomically.
    pub fn write(&mut self, name: &str, bytes: &[u8]) -> Result<(), SceneError> {
        write_atomic(&self.path.join(name), bytes)?;
        self.record(name);
        Ok(())
    }

    fn record(&mut self, name: &str) {
        if !self.written.iter().any(|w| w == name) {
            self.written.push(name.to_string());
        }
    }

    fn mesh_err(&self, name: &str, e: ecc_mesh::MeshError) -> SceneError {
        SceneError::Write {
            path: self.path.join(name).display().to_string(),
            source: WriteFailure::Mesh(e),
        }
    }

    /// Write a triangle mesh as OBJ (atomic, ecc-mesh writer).
    pub fn obj(&mut self, name: &str, mesh: &TriMesh) -> Result<(), SceneError> {
        write_obj(self.path.join(name), mesh).map_err(|e| self.mesh_err(name, e))?;
        self.record(name);
        Ok(())
    }

    /// Write a triangle mesh as VTK with point data.
    pub fn vtk_tri(
        &mut self,
        name: &str,
        mesh: &TriMesh,
        data: &[PointData<'_>],
    ) -> Result<(), SceneError> {
        write_vtk_tri(self.path.join(name), mesh, data).map_err(|e| self.mesh_err(name, e))?;
        self.record(name);
        Ok(())
    }

    /// Write a tet mesh as VTK with point data.
    pub fn vtk_tet(
        &mut self,
        name: &str,
        mesh: &TetMesh,
        data: &[PointData<'_>],
    ) -> Result<(), SceneError> {
        write_vtk_tet(self.path.join(name), mesh, data).map_err(|e| self.mesh_err(name, e))?;
        self.record(name);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let mut out = OutputDir::prepare(&dir.path().join("a/b")).unwrap();
        out.write("x.txt", b"one").unwrap();
        out.write("x.txt", b"two").unwrap();
        let names: Vec<_> = fs::read_dir(out.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        assert_eq!(names, vec!["x.txt".to_string()]);
        assert_eq!(fs::read_to_string(out.path().join("x.txt")).unwrap(), "two");
        assert_eq!(out.written(), ["x.txt".to_string()]);
    }

    #[test]
    fn a_file_in_the_way_is_an_output_error() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("file");
        fs::write(&f, "x").unwrap();
        let e = OutputDir::prepare(&f).unwrap_err();
        assert!(matches!(e, SceneError::Output { .. }), "{e}");
        let e = OutputDir::prepare(&f.join("sub")).unwrap_err();
        assert!(matches!(e, SceneError::Output { .. }), "{e}");
    }
}
