//! Writing results: to standard output, or atomically to a file (`-o`).

use std::io::Write;
use std::path::Path;

use crate::error::CliError;

/// Print `text` to standard output, or write it to `path` atomically.
pub fn emit(path: Option<&Path>, text: &str) -> Result<(), CliError> {
    match path {
        Some(p) => write_atomic(p, text.as_bytes()).map_err(|source| CliError::Write {
            path: p.display().to_string(),
            source,
        }),
        None => print_stdout(text),
    }
}

/// Print `text` (plus a final newline if missing) to standard output.
///
/// A closed pipe (`ecc … | head`) is not an error: the reader has what it
/// wanted, so the rest is dropped silently and the command's exit status
/// still reflects its own outcome (as in ripgrep; Rust ignores SIGPIPE).
pub fn print_stdout(text: &str) -> Result<(), CliError> {
    let mut out = std::io::stdout().lock();
    let res = out.write_all(text.as_bytes()).and_then(|_| {
        if text.ends_with('\n') {
            Ok(())
        } else {
            out.write_all(b"\n")
        }
    });
    match res.and_then(|_| out.flush()) {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        r => r.map_err(CliError::Stdout),
    }
}

/// Write `bytes` to `path` atomically ([`ecc_util::write_atomic`]: a
/// temporary file in the same directory, flushed, synced and renamed over
/// `path`, so readers never see a partial file and a failure leaves any old
/// file untouched).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    ecc_util::write_atomic(path, bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_and_cleans_up() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "two");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "no temporary file left behind");
        let missing = dir.path().join("no/such/dir/out.txt");
        assert!(write_atomic(&missing, b"x").is_err());
    }
}
