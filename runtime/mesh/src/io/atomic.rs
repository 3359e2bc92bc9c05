//! Atomic file output for the mesh writers: [`ecc_util::write_atomic_with`]
//! (temporary file in the destination folder, flushed, synced, renamed over
//! the destination; a failed write leaves any existing file intact) with
//! failures reported as [`MeshError::Io`] naming the destination.

use std::io::Write;
use std::path::Path;

use crate::error::MeshError;

/// Write `path` atomically with the bytes produced by `body`.
pub(crate) fn write_atomic(
    path: &Path,
    body: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), MeshError> {
    ecc_util::write_atomic_with(path, body).map_err(|source| MeshError::Io {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use std::fs;

    use super::*;

    #[test]
    fn failed_body_leaves_no_file_and_keeps_old_content() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        fs::write(&path, "old").unwrap();
        let err = write_atomic(&path, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("boom"))
        })
        .unwrap_err();
        assert!(err.to_string().contains("boom"));
        assert_eq!(fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
        write_atomic(&path, |w| w.write_all(b"new")).unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "new");
        assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn missing_directory_is_an_io_error() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("nope").join("out.txt");
        let err = write_atomic(&path, |w| w.write_all(b"x")).unwrap_err();
        assert!(matches!(err, MeshError::Io { .. }), "{err}");
        assert!(err.to_string().contains("nope"));
        assert!(!dir.path().join("nope").exists());
    }
}
